#include "nodus/output/provenance.hpp"

#include <fstream>
#include <sstream>
#include <thread>
#include <utility>

#include <omp.h>

#include "nodus/parallel/mpi_session.hpp"
#include "nodus/version.hpp"

namespace nodus::output {

std::string processor_model(const std::string& cpuinfo) {
  std::istringstream in(cpuinfo);
  for (std::string line; std::getline(in, line);) {
    if (!line.starts_with("model name")) continue;
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    const std::size_t start = line.find_first_not_of(" \t", colon + 1);
    if (start == std::string::npos) continue;
    return line.substr(start, line.find_last_not_of(" \t\r") + 1 - start);
  }
  return "unknown";
}

Provenance this_process(std::vector<std::string> linear_solvers) {
  Provenance p;
  p.version = std::string(nodus::version());
  p.commit = std::string(nodus::commit());
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::ostringstream text;
  text << cpuinfo.rdbuf();
  p.processor = processor_model(text.str());
  p.hardware_threads = static_cast<int>(std::thread::hardware_concurrency());
  p.threads = omp_get_max_threads();
  p.mpi_ranks = parallel::size();
  p.linear_solvers = std::move(linear_solvers);
  return p;
}

}  // namespace nodus::output
