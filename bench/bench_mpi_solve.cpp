// One Newton iteration's linear solve of the twisted bundle on MPI ranks (issue 20): the tangent of
// bundle_problem.hpp factorised and solved by the petsc solver (MUMPS through PETSc, the rows split among the
// ranks), or by nodus's serial mumps for comparison. Not Google Benchmark: every rank must run the same
// iterations (they factorise together), so the repetitions are fixed. A timed run, not a test.
//
//   mpirun -n N bench_mpi_solve FIBRES [REPEATS] [--serial | --distributed] [PETSc options:
//   -mat_mumps_icntl_28 2 ...]
//
// --distributed: each rank evaluates the elements at its own nodes and assembles their rows (the evaluation
// of a petsc run on several ranks), instead of the whole problem.
// Prints, on rank 0: the unknowns, the assembly time, the first factorisation (analysis included), the median
// and the spread of REPEATS factorise-and-solve, and |K du - r| / |r|; then, for the rank with most, the
// tangent's entries that rank holds and its peak resident memory. Results: docs/parallel.md.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <sys/resource.h>

#include "bundle_problem.hpp"
#include "nodus/parallel/mpi_session.hpp"
#include "nodus/solver/linear_solver.hpp"
#include "nodus/solver/petsc_solver.hpp"

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  const nodus::parallel::SplitArguments split = nodus::parallel::split_petsc_options(argc, argv);
  nodus::parallel::initialize(split.petsc);
  const std::vector<std::string>& args = split.rest;
  if (args.size() < 2) {
    if (nodus::parallel::is_root())
      std::fprintf(stderr,
                   "usage: bench_mpi_solve FIBRES [REPEATS] [--serial | --distributed] [PETSc options]\n");
    nodus::parallel::finalize();
    return 2;
  }
  const int fibres = std::atoi(args[1].c_str());
  const int repeats = args.size() > 2 && !args[2].starts_with("--") ? std::atoi(args[2].c_str()) : 5;
  const bool serial = std::find(args.begin(), args.end(), "--serial") != args.end();
  const bool distributed = std::find(args.begin(), args.end(), "--distributed") != args.end();
  const bool root = nodus::parallel::is_root();

  if (!serial && !nodus::parallel::available()) {
    std::fprintf(stderr, "bench_mpi_solve: this build has no PETSc (run with --serial)\n");
    return 2;
  }
  nodus::bench::Setup s(fibres);
  if (distributed && !serial) s.problem->distribute(true);
  Eigen::VectorXd r;
  nodus::parallel::barrier();
  auto start = std::chrono::steady_clock::now();
  s.problem->evaluate(r, true);
  const double assembly = seconds_since(start);
  {
    auto linear = serial
                      ? nodus::solver::make_linear_solver(nodus::solver::LinearSolverKind::mumps_ldlt)
                      : nodus::solver::make_petsc_solver(true, "", [&] { return s.problem->local_rows(); });
    nodus::parallel::barrier();
    start = std::chrono::steady_clock::now();
    linear->analyze(s.problem->tangent());
    bool ok = linear->factorize(s.problem->tangent());
    Eigen::VectorXd du = linear->solve(r);
    nodus::parallel::barrier();
    const double first = seconds_since(start);
    std::vector<double> times;
    for (int i = 0; i < repeats; ++i) {
      nodus::parallel::barrier();
      start = std::chrono::steady_clock::now();
      ok = linear->factorize(s.problem->tangent()) && ok;
      du = linear->solve(r);
      nodus::parallel::barrier();
      times.push_back(seconds_since(start));
    }
    std::sort(times.begin(), times.end());
    // Over each rank's own rows (all of them unless distributed), summed over the ranks.
    auto [first_row, last_row] = s.problem->local_rows();
    if (first_row < 0) first_row = 0, last_row = static_cast<int>(r.size());
    double squares = (s.problem->tangent() * du - r).segment(first_row, last_row - first_row).squaredNorm();
    if (s.problem->distributed()) nodus::parallel::sum_over_ranks(&squares, 1);
    const double residual = std::sqrt(squares) / r.norm();
    if (root)
      std::printf(
          "fibres %d, unknowns %ld, contact elements %zu, ranks %d, %s: assembly %.3f s, first factorisation "
          "%.3f s, factorise+solve median %.3f s (min %.3f, max %.3f, %d repeats), |K du - r|/|r| %.1e%s\n",
          fibres, static_cast<long>(s.problem->size()), s.geometry.elements.size(), nodus::parallel::size(),
          serial        ? "serial mumps LDL^T"
          : distributed ? "petsc (MUMPS LDL^T unless PETSc options say otherwise), distributed evaluation"
                        : "petsc (MUMPS LDL^T unless PETSc options say otherwise)",
          assembly, first, times[times.size() / 2], times.front(), times.back(), repeats, residual,
          ok ? "" : " (a factorisation failed)");
    // Each rank's share of the tangent and its peak memory (kB on Linux), the largest over the ranks.
    const auto ranks = static_cast<std::size_t>(nodus::parallel::size());
    const auto me = static_cast<std::size_t>(nodus::parallel::rank());
    std::vector<double> entries(ranks, 0.0), peak(ranks, 0.0);
    entries[me] = static_cast<double>(s.problem->tangent().nonZeros());
    // The beam elements and contact elements each rank evaluates (those with a node among its blocks; an
    // element across two ranks' blocks counts for both).
    std::vector<double> beam_elements(ranks, 0.0), contact_elements(ranks, 0.0);
    const nodus::solver::BlockRange mine = s.problem->local_blocks();
    const auto touches = [&](const std::vector<int>& nodes) {
      return std::any_of(nodes.begin(), nodes.end(), [&](int n) { return mine.contains(n); });
    };
    for (const std::vector<int>& nodes : s.bundle.model.element_nodes())
      beam_elements[me] += touches(nodes) ? 1.0 : 0.0;
    for (const std::vector<int>& nodes : nodus::bench::contact_couplings(s.bundle.model, s.geometry))
      contact_elements[me] += touches(nodes) ? 1.0 : 0.0;
    nodus::parallel::sum_over_ranks(beam_elements.data(), ranks);
    nodus::parallel::sum_over_ranks(contact_elements.data(), ranks);
    if (root && ranks > 1 && s.problem->distributed())
      for (std::size_t k = 0; k < ranks; ++k)
        std::printf("rank %zu evaluates %.0f beam elements and %.0f contact elements\n", k, beam_elements[k],
                    contact_elements[k]);
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    peak[me] = static_cast<double>(usage.ru_maxrss);
    nodus::parallel::sum_over_ranks(entries.data(), entries.size());
    nodus::parallel::sum_over_ranks(peak.data(), peak.size());
    if (root)
      std::printf("tangent entries held, largest rank: %.0f; peak resident memory, largest rank: %.0f MB\n",
                  *std::max_element(entries.begin(), entries.end()),
                  *std::max_element(peak.begin(), peak.end()) / 1024.0);
  }
  nodus::parallel::finalize();
  return 0;
}
