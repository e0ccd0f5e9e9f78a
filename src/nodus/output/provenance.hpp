#pragma once
/// Where a result came from: the program, the machine and how the run used it, as summary.json records it.

#include <string>
#include <vector>

namespace nodus::output {

struct Provenance {
  std::string version;                      ///< nodus's version, "0.1.0"
  std::string commit;                       ///< the commit it was built from (nodus::commit())
  std::string processor;                    ///< the processor's model name (/proc/cpuinfo), or "unknown"
  int hardware_threads = 0;                 ///< threads the machine runs at once (cores, with SMT)
  int threads = 0;                          ///< OpenMP threads of this process (OMP_NUM_THREADS)
  int mpi_ranks = 1;                        ///< processes of the run (mpirun -n)
  std::vector<std::string> linear_solvers;  ///< "name: package", as RunSummary::linear_solvers
};

/// The provenance of this process's run, with the linear solvers it used.
Provenance this_process(std::vector<std::string> linear_solvers);

/// The processor's model name from a /proc/cpuinfo text (its first "model name" line), or "unknown".
std::string processor_model(const std::string& cpuinfo);

}  // namespace nodus::output
