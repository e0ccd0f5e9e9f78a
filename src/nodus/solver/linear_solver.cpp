#include "nodus/solver/linear_solver.hpp"

#include <dmumps_c.h>
#include <klu.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include <fmt/core.h>
#include <omp.h>
#include <Eigen/CholmodSupport>
#include <Eigen/UmfPackSupport>
#include <unsupported/Eigen/IterativeSolvers>

#include "nodus/parallel/mpi_session.hpp"

#ifdef NODUS_HAVE_PETSC
#include <mpi.h>
#endif

namespace nodus::solver {
namespace {

/// A factorisation held by a LinearSolver, as the preconditioner of one of Eigen's iterative solvers (the
/// interface they expect of a preconditioner: compute() is a no-op, the factor is the solver's last one).
class FactorPreconditioner {
 public:
  void use(LinearSolver& factor) { factor_ = &factor; }
  template <class Matrix>
  FactorPreconditioner& analyzePattern(const Matrix& /*a*/) {
    return *this;
  }
  template <class Matrix>
  FactorPreconditioner& factorize(const Matrix& /*a*/) {
    return *this;
  }
  template <class Matrix>
  FactorPreconditioner& compute(const Matrix& /*a*/) {
    return *this;
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const { return factor_->solve(b); }
  Eigen::ComputationInfo info() const { return Eigen::Success; }

 private:
  LinearSolver* factor_ = nullptr;
};

/// Orders with METIS only: a fill-reducing ordering, and the same for every matrix.
template <class Solver>
void use_metis(Solver& solver) {
  cholmod_common& c = solver.cholmod();
  c.nmethods = 1;
  c.method[0].ordering = CHOLMOD_METIS;
  c.postorder = 1;
  c.print = 0;  // a matrix that is not positive definite is expected; it is reported through info()
}

/// While it lives, one OpenMP thread where `one` holds: OpenMP's OpenBLAS, which Debian's MUMPS calls for
/// its dense kernels, then runs its calls on one thread. The number of threads before is restored after.
class OneOpenMpThread {
 public:
  explicit OneOpenMpThread(bool one) : saved_(one ? omp_get_max_threads() : 0) {
    if (one) omp_set_num_threads(1);
  }
  ~OneOpenMpThread() {
    if (saved_ > 0) omp_set_num_threads(saved_);
  }
  OneOpenMpThread(const OneOpenMpThread&) = delete;
  OneOpenMpThread& operator=(const OneOpenMpThread&) = delete;

 private:
  int saved_;
};

/// MUMPS in this process alone (OpenMP threads and the system BLAS), multifrontal: LDL^T with 2x2 pivots for
/// a symmetric matrix, definite or not, or LU for any matrix, ordered by AMD or PORD. The analysis is kept
/// until the pattern changes, and the values are copied from the matrix at each factorisation. Without PETSc
/// it is the sequential library; with PETSc, the MPI library on MPI_COMM_SELF (cmake/FindMUMPS.cmake), which
/// starts MPI if it has not started.
class MumpsSolver final : public LinearSolver {
 public:
  explicit MumpsSolver(bool symmetric) : symmetric_(symmetric) {
#ifdef NODUS_HAVE_PETSC
    parallel::ensure_initialized();
    id_.comm_fortran = static_cast<MUMPS_INT>(MPI_Comm_c2f(MPI_COMM_SELF));
#else
    id_.comm_fortran = kUseCommWorld;
#endif
    id_.par = 1;                  // this process factorises (there is no other)
    id_.sym = symmetric ? 2 : 0;  // 2: general symmetric (LDL^T with pivoting), 0: unsymmetric
    call(-1, "initialisation");
    icntl(1) = -1;  // no messages: a failure is reported through INFOG(1) and factorize()'s result
    icntl(2) = -1;
    icntl(3) = -1;
    icntl(4) = 0;
    // The ordering (set in analyze()): PORD for large matrices, AMD for small ones. Of the orderings of
    // Debian's build (AMD, AMF, QAMD, PORD, SCOTCH; no METIS), PORD gives the fastest factorisations of the
    // contact tangents of twisted bundles: at 75 fibres (134,325 unknowns) LDL^T 11.4 s against 17.8 s with
    // SCOTCH and 23.3 s with AMD. On the 3x1 knot (5,463 unknowns, LU) AMD factorises faster: `thread` took
    // 118 s with AMD, 120 s with AMF or QAMD, 127 s with SCOTCH and 128 s with PORD, the same steps and
    // iterations (docs/performance.md). On a lone rod PORD is 20 % slower than SCOTCH.
    //
    // No scaling. MUMPS's automatic choice (ICNTL(8) = 77) computes an iterative row and column scaling at
    // every factorisation, a few passes over the entries: on the 3x1 yarn's twist (5,463 unknowns, LU) 13 %
    // of the run's samples, and the linear solve took 24 % less time without it, for the same steps, Newton
    // iterations and factorisations (LDL^T without friction: 7 % less; docs/performance.md).
    icntl(8) = 0;
    icntl(10) = 0;  // no iterative refinement: Newton refines anyway (as for UMFPACK)
    // The usual symmetric ordering, not the compressed one MUMPS picks by default for LDL^T: that one's
    // analysis took 15 s at 75 fibres (against 1.1 s) for a slower factorisation.
    icntl(12) = 1;
#ifdef NODUS_HAVE_PETSC
    // The MPI library factorises the root front with ScaLAPACK by default, which the sequential one cannot:
    // on one process, the sequential library's own kernels, and so its results.
    icntl(13) = 1;
#endif
  }
  ~MumpsSolver() override {
#ifdef NODUS_HAVE_PETSC
    if (!parallel::active()) return;  // MPI stopped at exit: MUMPS can no longer free its memory
#endif
    id_.job = -2;  // frees MUMPS's memory
    dmumps_c(&id_);
  }
  MumpsSolver(const MumpsSolver&) = delete;
  MumpsSolver& operator=(const MumpsSolver&) = delete;

  void analyze(const SparseMatrix& a) override {
    rows_.clear();
    cols_.clear();
    entries_.clear();
    for (int c = 0; c < a.outerSize(); ++c) {
      for (SparseMatrix::InnerIterator it(a, c); it; ++it) {
        if (symmetric_ && it.row() > c) continue;  // the upper triangle, as CHOLMOD reads it
        rows_.push_back(static_cast<MUMPS_INT>(it.row() + 1));
        cols_.push_back(static_cast<MUMPS_INT>(c + 1));
        entries_.push_back(&it.value() - a.valuePtr());
      }
    }
    values_.assign(entries_.size(), 0.0);
    pattern_nonzeros_ = a.nonZeros();
    // AMD below kSmall unknowns, PORD above (the constructor). Between 5,463 unknowns (AMD faster) and
    // 134,325 (PORD twice as fast) the two were not compared; 10,000 keeps every larger case as it was
    // measured. PORD could not order the smallest matrices anyway: it finds no separator in a matrix whose
    // unknowns are all coupled (one beam element, 18 free unknowns: "no valid number of stages in
    // multisector", and it ends the process).
    icntl(7) = a.rows() < kSmall ? 0 : 4;
    id_.n = static_cast<MUMPS_INT>(a.rows());
    id_.nnz = static_cast<MUMPS_INT8>(entries_.size());
    id_.irn = rows_.data();
    id_.jcn = cols_.data();
    id_.a = values_.data();
    const OneOpenMpThread one_thread(small());
    call(1, "analysis");
  }

  bool factorize(const SparseMatrix& a) override {
    if (a.nonZeros() != pattern_nonzeros_)
      throw std::logic_error("MumpsSolver::factorize: the pattern changed since analyze()");
    for (std::size_t i = 0; i < entries_.size(); ++i) values_[i] = a.valuePtr()[entries_[i]];
    // The workspace is estimated in the analysis; pivoting can need more. MUMPS says so (INFOG(1) = -8, -9
    // or -14 to -17), and the factorisation is tried again with a larger margin.
    const OneOpenMpThread one_thread(small());
    for (int attempt = 0;; ++attempt) {
      id_.job = 2;
      dmumps_c(&id_);
      const int error = infog(1);
      const bool workspace = error == -8 || error == -9 || (error <= -14 && error >= -17);
      if (!workspace || attempt == 4) return error >= 0;
      icntl(14) = 2 * std::max(icntl(14), 20);
    }
  }

  Eigen::VectorXd solve(const Eigen::VectorXd& b) override {
    Eigen::VectorXd x = b;
    id_.rhs = x.data();
    id_.nrhs = 1;
    id_.lrhs = static_cast<MUMPS_INT>(x.size());
    id_.job = 3;
    {
      const OneOpenMpThread one_thread(small());
      dmumps_c(&id_);
    }
    // A failed solve gives a vector Newton recognises as failed, as Eigen's solvers do.
    if (infog(1) < 0) x.setConstant(std::numeric_limits<double>::quiet_NaN());
    return x;
  }

  std::string name() const override {
    return symmetric_ ? "mumps_ldlt" : "mumps_lu";
  }
  std::string package() const override {
    return "MUMPS " MUMPS_VERSION;
  }
  bool analysis_reads_values() const override {
    return false;
  }  // it is handed zeros (analyze)

 private:
#ifndef NODUS_HAVE_PETSC
  static constexpr MUMPS_INT kUseCommWorld = -987654;  // the sequential library's only communicator
#endif
  /// Smaller matrices are ordered by AMD (analyze()) and factorised and solved on one OpenMP thread: on the
  /// 3x1 knot's twist (5,463 unknowns) MUMPS's calls took 1.5 times as long on two threads as on one, the
  /// threads of OpenBLAS's small dense kernels costing more than they share (docs/performance.md).
  static constexpr Eigen::Index kSmall = 10000;
  bool small() const {
    return id_.n < kSmall;
  }

  MUMPS_INT& icntl(int i) {
    return id_.icntl[i - 1];
  }  // 1-based, as in MUMPS's guide
  int infog(int i) const {
    return id_.infog[i - 1];
  }

  void call(int job, const char* what) {
    id_.job = job;
    dmumps_c(&id_);
    if (infog(1) < 0)
      throw std::runtime_error(
          fmt::format("MUMPS {} failed: INFOG(1) = {}, INFOG(2) = {}", what, infog(1), infog(2)));
  }

  bool symmetric_;
  DMUMPS_STRUC_C id_{};
  std::vector<MUMPS_INT> rows_, cols_;   // 1-based coordinates of the entries handed to MUMPS
  std::vector<std::ptrdiff_t> entries_;  // where each entry's value lies in the matrix's value array
  std::vector<double> values_;
  Eigen::Index pattern_nonzeros_ = -1;
};

/// `cholmod`: supernodal LL^T where the matrix is positive definite; where it is not (buckled states),
/// MUMPS's multifrontal LDL^T with pivoting, analysed the first time the pattern needs it. `cholmod_ldlt`:
/// CHOLMOD's simplicial LDL^T (no pivoting, accepts negative pivots) alone, kept for comparison: on a bundle
/// of 27 fibres it is 13 times slower than the LL^T and 18 times slower than MUMPS (docs/performance.md).
class CholmodSolver final : public LinearSolver {
 public:
  explicit CholmodSolver(bool try_llt) : try_llt_(try_llt) {
    use_metis(llt_);
    use_metis(ldlt_);
  }
  void analyze(const SparseMatrix& a) override {
    if (try_llt_) {
      llt_.analyzePattern(a);
      fallback_analyzed_ = false;  // MUMPS analyses the new pattern only if a factorisation needs it
    } else {
      ldlt_.analyzePattern(a);
    }
  }
  bool factorize(const SparseMatrix& a) override {
    if (!try_llt_) {
      ldlt_.factorize(a);
      return ldlt_.info() == Eigen::Success;
    }
    llt_.factorize(a);
    using_llt_ = llt_.info() == Eigen::Success && llt_.cholmod().status == CHOLMOD_OK;
    if (using_llt_) return true;
    if (!fallback_) fallback_ = std::make_unique<MumpsSolver>(true);
    if (!fallback_analyzed_) {
      fallback_->analyze(a);
      fallback_analyzed_ = true;
    }
    return fallback_->factorize(a);
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& b) override {
    if (!try_llt_) return ldlt_.solve(b);
    if (using_llt_) return llt_.solve(b);
    return fallback_->solve(b);
  }
  std::string name() const override { return try_llt_ ? "cholmod" : "cholmod_ldlt"; }
  std::string package() const override {
    std::string text = fmt::format("SuiteSparse CHOLMOD {}.{}.{}", CHOLMOD_MAIN_VERSION, CHOLMOD_SUB_VERSION,
                                   CHOLMOD_SUBSUB_VERSION);
    if (fallback_) text += ", and " + fallback_->package() + " for tangents not positive definite";
    return text;
  }
  bool analysis_reads_values() const override { return false; }  // cholmod_analyze, MUMPS's (above)

 private:
  bool try_llt_;
  bool using_llt_ = false;
  bool fallback_analyzed_ = false;
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Upper> llt_;
  Eigen::CholmodSimplicialLDLT<SparseMatrix, Eigen::Upper> ldlt_;
  std::unique_ptr<MumpsSolver> fallback_;  ///< made the first time a tangent is not positive definite
};

class UmfpackSolver final : public LinearSolver {
 public:
  // No iterative refinement: Newton refines the solution anyway, and the two refinement steps UMFPACK makes
  // by default cost 10 % of a knot run (12.3 s against 13.6 s for its forming, same convergence).
  UmfpackSolver() { lu_.umfpackControl()(UMFPACK_IRSTEP) = 0; }
  void analyze(const SparseMatrix& a) override { lu_.analyzePattern(a); }
  bool factorize(const SparseMatrix& a) override {
    lu_.factorize(a);
    return lu_.info() == Eigen::Success;
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& b) override { return lu_.solve(b); }
  std::string name() const override { return "umfpack"; }
  std::string package() const override {
    return fmt::format("SuiteSparse UMFPACK {}.{}.{}", UMFPACK_MAIN_VERSION, UMFPACK_SUB_VERSION,
                       UMFPACK_SUBSUB_VERSION);
  }
  // umfpack_symbolic is given the values. Its documentation says that they only serve its statistics (how
  // many nonzeros the ordering puts on the diagonal); nodus does not rely on that.
  bool analysis_reads_values() const override { return true; }

 private:
  Eigen::UmfPackLU<SparseMatrix> lu_;
};

/// KLU (SuiteSparse): a left-looking sparse LU with partial pivoting, for the small, sparse tangents of one
/// or a few rods, where the supernodal and multifrontal methods' dense kernels have little to do. After each
/// analysis the first factorisation chooses the pivots; the next ones keep that pivot sequence
/// (klu_refactor), and a solve whose residual shows that the sequence no longer serves is done again after a
/// factorisation that pivots anew.
class KluSolver final : public LinearSolver {
 public:
  KluSolver() {
    klu_defaults(&common_);
    common_.halt_if_singular = 1;
  }
  KluSolver(const KluSolver&) = delete;
  KluSolver& operator=(const KluSolver&) = delete;
  ~KluSolver() override { free_all(); }

  void analyze(const SparseMatrix& a) override {
    free_all();
    a_ = a;
    a_.makeCompressed();
    symbolic_ = klu_analyze(static_cast<int>(a_.cols()), a_.outerIndexPtr(), a_.innerIndexPtr(), &common_);
    if (symbolic_ == nullptr)
      throw std::runtime_error(fmt::format("KLU could not analyse the matrix (status {})", common_.status));
  }

  bool factorize(const SparseMatrix& a) override {
    if (symbolic_ == nullptr) throw std::logic_error("KluSolver::factorize: analyze() was not called");
    if (a.nonZeros() != a_.nonZeros() || a.cols() != a_.cols())
      throw std::logic_error("KluSolver::factorize: the pattern changed since analyze()");
    std::copy(a.valuePtr(), a.valuePtr() + a.nonZeros(), a_.valuePtr());
    norm_a_ = (a_.cwiseAbs() * Eigen::VectorXd::Ones(a_.cols())).maxCoeff();
    if (numeric_ != nullptr && klu_refactor(a_.outerIndexPtr(), a_.innerIndexPtr(), a_.valuePtr(), symbolic_,
                                            numeric_, &common_) == 1) {
      refactored_ = true;
      return true;
    }
    return factor_anew();
  }

  Eigen::VectorXd solve(const Eigen::VectorXd& b) override {
    Eigen::VectorXd x = solve_once(b);
    if (refactored_ && !accurate(b, x)) {
      if (!factor_anew())
        return Eigen::VectorXd::Constant(b.size(), std::numeric_limits<double>::quiet_NaN());
      x = solve_once(b);
    }
    return x;
  }

  std::string name() const override { return "klu"; }
  std::string package() const override {
    return fmt::format("SuiteSparse KLU {}.{}.{}", KLU_MAIN_VERSION, KLU_SUB_VERSION, KLU_SUBSUB_VERSION);
  }
  // The pivots chosen by the first factorisation after an analysis decide the later ones' round-off: a run
  // that must repeat itself exactly analyses where the run it repeats did.
  bool analysis_reads_values() const override { return true; }

 private:
  bool factor_anew() {
    if (numeric_ != nullptr) klu_free_numeric(&numeric_, &common_);
    numeric_ = klu_factor(a_.outerIndexPtr(), a_.innerIndexPtr(), a_.valuePtr(), symbolic_, &common_);
    refactored_ = false;
    return numeric_ != nullptr;
  }
  Eigen::VectorXd solve_once(const Eigen::VectorXd& b) {
    if (numeric_ == nullptr) throw std::logic_error("KluSolver::solve: no factorisation to solve with");
    Eigen::VectorXd x = b;
    klu_solve(symbolic_, numeric_, static_cast<int>(x.size()), 1, x.data(), &common_);
    return x;
  }
  /// Whether |a x - b| is at round-off level: below 1e-10 of |a| |x| + |b| (infinity norms).
  bool accurate(const Eigen::VectorXd& b, const Eigen::VectorXd& x) const {
    if (!x.allFinite()) return false;
    const double r = (a_ * x - b).lpNorm<Eigen::Infinity>();
    return r <= 1e-10 * (norm_a_ * x.lpNorm<Eigen::Infinity>() + b.lpNorm<Eigen::Infinity>());
  }
  void free_all() {
    if (numeric_ != nullptr) klu_free_numeric(&numeric_, &common_);
    if (symbolic_ != nullptr) klu_free_symbolic(&symbolic_, &common_);
    refactored_ = false;
  }

  klu_common common_{};
  klu_symbolic* symbolic_ = nullptr;
  klu_numeric* numeric_ = nullptr;
  /// The matrix of the last factorisation, compressed (KLU reads it again when it refactors), and its
  /// infinity norm.
  SparseMatrix a_;
  double norm_a_ = 0.0;
  bool refactored_ = false;
};

}  // namespace

KrylovSolve LinearSolver::solve_on_factor(const SparseMatrix& a, bool /*new_pattern*/,
                                          const Eigen::VectorXd& b, double tolerance, int max_iterations,
                                          Eigen::VectorXd& x) {
  Eigen::GMRES<SparseMatrix, FactorPreconditioner> gmres;
  gmres.preconditioner().use(*this);
  gmres.compute(a);
  gmres.setMaxIterations(max_iterations);
  gmres.set_restart(max_iterations);
  // Its own stopping test is on the preconditioned residual, which reads up to 100 times smaller than the
  // true one on the knot's tangents: it is asked for 1e-3 of the tolerance, and each extra iteration costs
  // little against a factorisation.
  gmres.setTolerance(1e-3 * tolerance);
  x = gmres.solve(b);
  // The increment is accepted on the true residual.
  return {(a * x - b).norm() <= tolerance * b.norm(), static_cast<int>(gmres.iterations())};
}

std::unique_ptr<LinearSolver> make_linear_solver(LinearSolverKind kind) {
  switch (kind) {
    case LinearSolverKind::cholmod:
      return std::make_unique<CholmodSolver>(true);
    case LinearSolverKind::cholmod_ldlt:
      return std::make_unique<CholmodSolver>(false);
    case LinearSolverKind::umfpack:
      return std::make_unique<UmfpackSolver>();
    case LinearSolverKind::mumps_ldlt:
      return std::make_unique<MumpsSolver>(true);
    case LinearSolverKind::mumps_lu:
      return std::make_unique<MumpsSolver>(false);
    case LinearSolverKind::klu:
      return std::make_unique<KluSolver>();
  }
  return nullptr;
}

}  // namespace nodus::solver
