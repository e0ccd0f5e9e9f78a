#pragma once
/// Where the library's log lines go.

namespace nodus::output {

/// Makes spdlog's default logger (used by spdlog::info etc.) write to stderr, coloured when stderr is a
/// terminal, with the pattern "[HH:MM:SS] message", so that stdout stays free for results. Idempotent.
void use_stderr_logger();

}  // namespace nodus::output
