#include "nodus/output/logging.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

namespace nodus::output {

void use_stderr_logger() {
  constexpr const char* kName = "nodus";
  std::shared_ptr<spdlog::logger> logger = spdlog::get(kName);
  if (!logger) logger = spdlog::stderr_color_mt(kName);
  logger->set_pattern("[%H:%M:%S] %v");
  spdlog::set_default_logger(logger);
}

}  // namespace nodus::output
