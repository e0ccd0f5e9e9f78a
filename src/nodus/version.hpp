#pragma once
/// What nodus is: its version and the commit it was built from, for the records of a run (summary.json) and
/// `nodus --version`.

#include <string_view>

namespace nodus {

/// The project's version (CMakeLists.txt), "0.1.0".
std::string_view version();
/// `git describe --always --dirty` of the source tree at build time ("f6f8517c3a1b", with "-dirty" where it
/// had uncommitted changes); "unknown" when built outside a git checkout.
std::string_view commit();

}  // namespace nodus
