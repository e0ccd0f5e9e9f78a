#include "nodus/solver/linear_solver.hpp"

#include <dmumps_c.h>

#include <limits>
#include <stdexcept>
#include <vector>

#include <fmt/core.h>
#include <Eigen/CholmodSupport>
#include <Eigen/UmfPackSupport>

namespace nodus::solver {
namespace {

/// Orders with METIS only: the fill-reducing ordering the issue asks for, and the same for every matrix.
template <class Solver>
void use_metis(Solver& solver) {
  cholmod_common& c = solver.cholmod();
  c.nmethods = 1;
  c.method[0].ordering = CHOLMOD_METIS;
  c.postorder = 1;
  c.print = 0;  // a matrix that is not positive definite is expected; it is reported through info()
}

/// MUMPS (the sequential library: one process, OpenMP threads and the system BLAS), multifrontal: LDL^T with
/// 2x2 pivots for a symmetric matrix, definite or not, or LU for any matrix, ordered by PORD. The analysis is
/// kept until the pattern changes, and the values are copied from the matrix at each factorisation.
class MumpsSolver final : public LinearSolver {
 public:
  explicit MumpsSolver(bool symmetric) : symmetric_(symmetric) {
    id_.comm_fortran = kUseCommWorld;
    id_.par = 1;                  // this process factorises (there is no other)
    id_.sym = symmetric ? 2 : 0;  // 2: general symmetric (LDL^T with pivoting), 0: unsymmetric
    call(-1, "initialisation");
    icntl(1) = -1;  // no messages: a failure is reported through INFOG(1) and factorize()'s result
    icntl(2) = -1;
    icntl(3) = -1;
    icntl(4) = 0;
    // PORD: of the orderings of Debian's build (AMD, AMF, QAMD, PORD, SCOTCH; no METIS), the fastest
    // factorisations of the contact tangents of twisted bundles: at 75 fibres LDL^T 11.4 s against 17.8 s
    // with SCOTCH and 23.3 s with AMD (docs/performance.md). On a lone rod it is 20 % slower than SCOTCH.
    icntl(7) = 4;
    icntl(10) = 0;  // no iterative refinement: Newton refines anyway (as for UMFPACK)
    // The usual symmetric ordering, not the compressed one MUMPS picks by default for LDL^T: that one's
    // analysis took 15 s at 75 fibres (against 1.1 s) for a slower factorisation.
    icntl(12) = 1;
  }
  ~MumpsSolver() override {
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
    id_.n = static_cast<MUMPS_INT>(a.rows());
    id_.nnz = static_cast<MUMPS_INT8>(entries_.size());
    id_.irn = rows_.data();
    id_.jcn = cols_.data();
    id_.a = values_.data();
    call(1, "analysis");
  }

  bool factorize(const SparseMatrix& a) override {
    if (a.nonZeros() != pattern_nonzeros_)
      throw std::logic_error("MumpsSolver::factorize: the pattern changed since analyze()");
    for (std::size_t i = 0; i < entries_.size(); ++i) values_[i] = a.valuePtr()[entries_[i]];
    // The workspace is estimated in the analysis; pivoting can need more. MUMPS says so (INFOG(1) = -8, -9
    // or -14 to -17), and the factorisation is tried again with a larger margin.
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
    dmumps_c(&id_);
    // A failed solve gives a vector Newton recognises as failed, as Eigen's solvers do.
    if (infog(1) < 0) x.setConstant(std::numeric_limits<double>::quiet_NaN());
    return x;
  }

  std::string name() const override { return symmetric_ ? "mumps_ldlt" : "mumps_lu"; }
  bool analysis_reads_values() const override { return false; }  // it is handed zeros (analyze)

 private:
  static constexpr MUMPS_INT kUseCommWorld = -987654;  // the sequential library's only communicator

  MUMPS_INT& icntl(int i) { return id_.icntl[i - 1]; }  // 1-based, as in MUMPS's guide
  int infog(int i) const { return id_.infog[i - 1]; }

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
  // umfpack_symbolic is given the values. Its documentation says that they only serve its statistics (how
  // many nonzeros the ordering puts on the diagonal); nodus does not rely on that.
  bool analysis_reads_values() const override { return true; }

 private:
  Eigen::UmfPackLU<SparseMatrix> lu_;
};

}  // namespace

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
  }
  return nullptr;
}

}  // namespace nodus::solver
