#include "nodus/solver/petsc_solver.hpp"

#include <limits>
#include <stdexcept>
#include <tuple>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "nodus/parallel/mpi_session.hpp"

#ifdef NODUS_HAVE_PETSC
#include <petscksp.h>

#include "nodus/parallel/petsc_check.hpp"
#endif

namespace nodus::solver {

#ifdef NODUS_HAVE_PETSC
namespace {

constexpr auto check = parallel::check_petsc;

/// Makes a solver's own options database PETSc's default while it lives (PetscOptionsPush): MUMPS reads its
/// `-mat_mumps_*` options when it factorises, not only when the solver is set up.
class OptionsInForce {
 public:
  explicit OptionsInForce(PetscOptions options) { check(PetscOptionsPush(options), "PetscOptionsPush"); }
  ~OptionsInForce() { PetscOptionsPop(); }
  OptionsInForce(const OptionsInForce&) = delete;
  OptionsInForce& operator=(const OptionsInForce&) = delete;
};

class PetscSolver final : public LinearSolver {
 public:
  PetscSolver(bool symmetric, const std::string& options, LocalRows local_rows)
      : symmetric_(symmetric), local_rows_(std::move(local_rows)) {
    if (!parallel::well_formed_options(options))
      throw std::invalid_argument(
          fmt::format("solver.petsc_options: expected PETSc options (-name [value] ...), got '{}'", options));
    parallel::ensure_initialized();
    // This solver's options: nodus's defaults, the scenario's, then the command line's; a later one wins
    // where two set the same option. MUMPS's usual symmetric ordering, not the compressed one it picks for
    // LDL^T by default (as the serial mumps solver): 2.63 s against 3.57 s a factorisation of the 27-fibre
    // bundle on 2 ranks (docs/parallel.md).
    try {
      check(PetscOptionsCreate(&options_), "PetscOptionsCreate");
      // MUMPS as an option, not only by PCFactorSetMatSolverType below: a `-pc_type` among the options sets
      // the preconditioner anew, which drops the package set before (with `-pc_type lu` PETSc then took its
      // own LU: 36 s against 2 s at 27 fibres on one rank, and none on several).
      check(PetscOptionsInsertString(options_, "-pc_factor_mat_solver_type mumps -mat_mumps_icntl_12 1"),
            "PetscOptionsInsertString");
      check(PetscOptionsInsertString(options_, options.c_str()), "PetscOptionsInsertString");
      std::string command_line;
      for (const std::string& word : parallel::command_line_options()) command_line += word + " ";
      check(PetscOptionsInsertString(options_, command_line.c_str()), "PetscOptionsInsertString");
      const OptionsInForce in_force(options_);
      check(KSPCreate(PETSC_COMM_WORLD, &ksp_), "KSPCreate");
      check(KSPSetType(ksp_, KSPPREONLY), "KSPSetType");
      PC pc = nullptr;
      check(KSPGetPC(ksp_, &pc), "KSPGetPC");
      check(PCSetType(pc, symmetric ? PCCHOLESKY : PCLU), "PCSetType");
      check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
      check(KSPSetFromOptions(ksp_), "KSPSetFromOptions");
    } catch (...) {
      release();  // the destructor does not run for an object whose constructor threw
      throw;
    }
  }
  ~PetscSolver() override { release(); }
  PetscSolver(const PetscSolver&) = delete;
  PetscSolver& operator=(const PetscSolver&) = delete;

  void analyze(const SparseMatrix& a) override {
    if (a.rows() != a.cols()) throw std::logic_error("PetscSolver::analyze: the matrix is not square");
    reset();
    VecScatterDestroy(&gather_);
    VecDestroy(&whole_);
    VecDestroy(&x_);
    VecDestroy(&b_);
    build_operator(a, rows_of(a));
    check(MatCreateVecs(a_, &x_, &b_), "MatCreateVecs");
    check(VecScatterCreateToAll(x_, &gather_, &whole_), "VecScatterCreateToAll");
  }

  bool factorize(const SparseMatrix& a) override {
    if (a.nonZeros() != pattern_nonzeros_)
      throw std::logic_error("PetscSolver::factorize: the pattern changed since analyze()");
    copy_values(a);
    const OptionsInForce in_force(options_);
    if (!operators_set_) {
      check(KSPSetOperators(ksp_, a_, a_), "KSPSetOperators");
      operators_set_ = true;
    }
    // A factorisation, not a solve on the kept factor (solve_on_factor).
    PC pc = nullptr;
    check(KSPGetPC(ksp_, &pc), "KSPGetPC");
    if (on_factor_) {
      check(KSPSetType(ksp_, KSPPREONLY), "KSPSetType");
      check(KSPSetPCSide(ksp_, PC_LEFT), "KSPSetPCSide");
      check(KSPSetNormType(ksp_, KSP_NORM_NONE), "KSPSetNormType");
      check(PCSetReusePreconditioner(pc, PETSC_FALSE), "PCSetReusePreconditioner");
      on_factor_ = false;
    }
    // The factorisation runs here. A singular matrix is a failed PC, not an error: Newton cuts the step.
    const PetscErrorCode code = KSPSetUp(ksp_);
    PCFailedReason reason = PC_NOERROR;
    check(PCGetFailedReason(pc, &reason), "PCGetFailedReason");
    if (code != 0 && reason == PC_NOERROR) check(code, "KSPSetUp (the factorisation)");
    // After a failed factorisation PETSc's MUMPS interface skips the next ones (it takes the failure for a
    // failed analysis): the next factorisation starts from a new analysis.
    if (reason != PC_NOERROR) reset();
    return reason == PC_NOERROR;
  }

  Eigen::VectorXd solve(const Eigen::VectorXd& b) override {
    Eigen::VectorXd x(b.size());
    const OptionsInForce in_force(options_);
    // A failed solve gives a vector Newton recognises as failed, as the other solvers do.
    if (!solve_into(b, x)) x.setConstant(std::numeric_limits<double>::quiet_NaN());
    return x;
  }

  std::string name() const override { return symmetric_ ? "petsc_cholesky" : "petsc_lu"; }
  /// "PETSc 3.18.5 on 2 ranks: KSP preonly, PC cholesky, factorised by mumps": the options in force, the
  /// command line's included.
  std::string package() const override {
    std::string text = fmt::format("PETSc {}.{}.{} on {} rank{}", PETSC_VERSION_MAJOR, PETSC_VERSION_MINOR,
                                   PETSC_VERSION_SUBMINOR, parallel::size(), parallel::size() > 1 ? "s" : "");
    KSPType ksp_type = nullptr;
    PC pc = nullptr;
    PCType pc_type = nullptr;
    if (KSPGetType(ksp_, &ksp_type) != 0 || KSPGetPC(ksp_, &pc) != 0 || PCGetType(pc, &pc_type) != 0)
      return text;
    text += fmt::format(": KSP {}, PC {}", ksp_type ? ksp_type : "?", pc_type ? pc_type : "?");
    PetscBool factor = PETSC_FALSE;
    if (PetscObjectTypeCompareAny(reinterpret_cast<PetscObject>(pc), &factor, PCLU, PCCHOLESKY, PCILU, PCICC,
                                  "") == 0 &&
        factor == PETSC_TRUE) {
      MatSolverType package = nullptr;
      if (PCFactorGetMatSolverType(pc, &package) == 0 && package)
        text += fmt::format(", factorised by {}", package);
    }
    return text;
  }

  /// PETSc's GMRES on the ranks' rows, preconditioned on the right by the kept factor (so that its residual
  /// is the true one, |a x - b|, and its test the one of the default solver), at most `max_iterations`
  /// iterations. The factor stays while the operator changes (PCSetReusePreconditioner). A new pattern with
  /// the same rows on each rank becomes the operator; one with other rows (a new split among the ranks) would
  /// not fit the factor's layout and is refused, which makes Newton refactorise.
  KrylovSolve solve_on_factor(const SparseMatrix& a, bool new_pattern, const Eigen::VectorXd& b,
                              double tolerance, int max_iterations, Eigen::VectorXd& x) override {
    if (!operators_set_) return {};
    const OptionsInForce in_force(options_);
    if (new_pattern) {
      const std::pair<PetscInt, PetscInt> rows = rows_of(a);
      // Decided by all ranks together: one whose rows stayed must not set the operator alone.
      int same = rows.first == first_ && rows.second == last_ ? 1 : 0;
      check(MPI_Allreduce(MPI_IN_PLACE, &same, 1, MPI_INT, MPI_MIN, PETSC_COMM_WORLD) == MPI_SUCCESS ? 0 : 1,
            "MPI_Allreduce");
      if (same == 0) {
        spdlog::debug(
            "petsc: the new pattern's rows [{}, {}) are not the factor's [{}, {}) on this rank "
            "(or on another)",
            rows.first, rows.second, first_, last_);
        return {};
      }
      build_operator(a, rows);
      check(KSPSetOperators(ksp_, a_, a_), "KSPSetOperators");
    }
    copy_values(a);
    PC pc = nullptr;
    check(KSPGetPC(ksp_, &pc), "KSPGetPC");
    if (!on_factor_) {
      check(PCSetReusePreconditioner(pc, PETSC_TRUE), "PCSetReusePreconditioner");
      check(KSPSetType(ksp_, KSPGMRES), "KSPSetType");
      check(KSPSetPCSide(ksp_, PC_RIGHT), "KSPSetPCSide");
      check(KSPSetNormType(ksp_, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
      check(KSPSetInitialGuessNonzero(ksp_, PETSC_FALSE), "KSPSetInitialGuessNonzero");
      on_factor_ = true;
    }
    check(KSPGMRESSetRestart(ksp_, max_iterations), "KSPGMRESSetRestart");
    check(KSPSetTolerances(ksp_, tolerance, 0.0, PETSC_DEFAULT, max_iterations), "KSPSetTolerances");
    KrylovSolve result;
    result.accepted = solve_into(b, x);
    PetscInt iterations = 0;
    check(KSPGetIterationNumber(ksp_, &iterations), "KSPGetIterationNumber");
    result.iterations = static_cast<int>(iterations);
    return result;
  }

 private:
  /// This rank's rows [first, last) of `a`: those it assembled (`local_rows`), or PETSc's even split.
  std::pair<PetscInt, PetscInt> rows_of(const SparseMatrix& a) const {
    PetscInt local = PETSC_DECIDE, global = static_cast<PetscInt>(a.rows()), last = 0;
    const std::pair<int, int> given = local_rows_ ? local_rows_() : std::pair{-1, -1};
    if (given.first >= 0) local = given.second - given.first;
    check(PetscSplitOwnership(PETSC_COMM_WORLD, &local, &global), "PetscSplitOwnership");
    check(MPI_Scan(&local, &last, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD) == MPI_SUCCESS ? 0 : 1, "MPI_Scan");
    if (given.first >= 0 && (given.first != last - local || given.second != last))
      throw std::logic_error(
          fmt::format("PetscSolver: rows [{}, {}) given for this rank, [{}, {}) follow from "
                      "the ranks' counts",
                      given.first, given.second, last - local, last));
    return {last - local, last};
  }

  /// The operator a_ of the pattern of `a`, this rank's `rows`, values not yet set (the one it replaces is
  /// released; the KSP keeps its own reference until it is given another).
  void build_operator(const SparseMatrix& a, std::pair<PetscInt, PetscInt> rows) {
    MatDestroy(&a_);
    std::tie(first_, last_) = rows;
    const PetscInt n = static_cast<PetscInt>(a.rows()), local = last_ - first_;
    // This rank's rows, compressed: the tangent is stored by columns, so each entry of the owned rows is
    // found once here and its place in the value array kept for the factorisations.
    std::vector<PetscInt> counts(static_cast<std::size_t>(local), 0);
    for (Eigen::Index c = 0; c < a.outerSize(); ++c)
      for (SparseMatrix::InnerIterator it(a, c); it; ++it)
        if (it.row() >= first_ && it.row() < last_) ++counts[static_cast<std::size_t>(it.row() - first_)];
    row_start_.assign(static_cast<std::size_t>(local) + 1, 0);
    for (std::size_t r = 0; r < counts.size(); ++r) row_start_[r + 1] = row_start_[r] + counts[r];
    columns_.assign(static_cast<std::size_t>(row_start_.back()), 0);
    entries_.assign(columns_.size(), 0);
    std::vector<PetscInt> fill(row_start_.begin(), row_start_.end() - 1);
    for (Eigen::Index c = 0; c < a.outerSize(); ++c)
      for (SparseMatrix::InnerIterator it(a, c); it; ++it)
        if (it.row() >= first_ && it.row() < last_) {
          const auto k = static_cast<std::size_t>(fill[static_cast<std::size_t>(it.row() - first_)]++);
          columns_[k] = static_cast<PetscInt>(c);
          entries_[k] = &it.value() - a.valuePtr();
        }
    values_.assign(columns_.size(), 0.0);
    pattern_nonzeros_ = a.nonZeros();

    check(MatCreate(PETSC_COMM_WORLD, &a_), "MatCreate");
    check(MatSetSizes(a_, local, local, n, n), "MatSetSizes");
    check(MatSetType(a_, MATAIJ), "MatSetType");
    check(MatSeqAIJSetPreallocationCSR(a_, row_start_.data(), columns_.data(), values_.data()),
          "MatSeqAIJSetPreallocationCSR");
    check(MatMPIAIJSetPreallocationCSR(a_, row_start_.data(), columns_.data(), values_.data()),
          "MatMPIAIJSetPreallocationCSR");
    check(MatSetOption(a_, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE), "MatSetOption");
  }

  /// The values of `a` (of the operator's pattern) into the operator.
  void copy_values(const SparseMatrix& a) {
    if (a.nonZeros() != pattern_nonzeros_)
      throw std::logic_error("PetscSolver: the pattern changed since the operator was built");
    for (std::size_t k = 0; k < entries_.size(); ++k) values_[k] = a.valuePtr()[entries_[k]];
    for (PetscInt r = 0; r < last_ - first_; ++r) {
      const PetscInt row = first_ + r;
      const PetscInt begin = row_start_[static_cast<std::size_t>(r)];
      const PetscInt count = row_start_[static_cast<std::size_t>(r) + 1] - begin;
      check(MatSetValues(a_, 1, &row, count, columns_.data() + begin, values_.data() + begin, INSERT_VALUES),
            "MatSetValues");
    }
    check(MatAssemblyBegin(a_, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    check(MatAssemblyEnd(a_, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  }

  /// KSPSolve of a x = b into `x` on every rank (the same bits on each); false if it failed.
  bool solve_into(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
    PetscScalar* values = nullptr;
    check(VecGetArray(b_, &values), "VecGetArray");
    for (PetscInt r = 0; r < last_ - first_; ++r) values[r] = b[first_ + r];
    check(VecRestoreArray(b_, &values), "VecRestoreArray");
    const PetscErrorCode code = KSPSolve(ksp_, b_, x_);
    KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
    check(KSPGetConvergedReason(ksp_, &reason), "KSPGetConvergedReason");
    if (code != 0 || reason < 0) return false;
    // Every rank receives the whole solution, the same bits on each.
    check(VecScatterBegin(gather_, x_, whole_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
    check(VecScatterEnd(gather_, x_, whole_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
    const PetscScalar* all = nullptr;
    check(VecGetArrayRead(whole_, &all), "VecGetArrayRead");
    x.resize(b.size());
    for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = all[i];
    check(VecRestoreArrayRead(whole_, &all), "VecRestoreArrayRead");
    return true;
  }

  /// Frees what PETSc holds for this solver (what was created so far).
  void release() {
    if (!parallel::active()) return;  // MPI already stopped at exit: nothing can be freed any more
    VecScatterDestroy(&gather_);
    VecDestroy(&whole_);
    VecDestroy(&x_);
    VecDestroy(&b_);
    MatDestroy(&a_);
    KSPDestroy(&ksp_);
    PetscOptionsDestroy(&options_);
  }

  /// Forgets the operator and its factor (the solver's type and options stay): the next factorize() sets the
  /// operator again and analyses it, whatever its size.
  void reset() {
    if (operators_set_) check(KSPReset(ksp_), "KSPReset");
    operators_set_ = false;
  }

  bool symmetric_;
  LocalRows local_rows_;
  PetscOptions options_ = nullptr;
  KSP ksp_ = nullptr;
  Mat a_ = nullptr;
  Vec x_ = nullptr, b_ = nullptr, whole_ = nullptr;
  VecScatter gather_ = nullptr;
  bool operators_set_ = false;
  bool on_factor_ = false;  // the KSP is set for solves on the kept factor (GMRES), not for a factorisation
  PetscInt first_ = 0, last_ = 0;        // this rank's rows [first_, last_)
  std::vector<PetscInt> row_start_;      // compressed rows of the owned block
  std::vector<PetscInt> columns_;        // their column indices
  std::vector<std::ptrdiff_t> entries_;  // where each entry's value lies in the matrix's value array
  std::vector<PetscScalar> values_;
  Eigen::Index pattern_nonzeros_ = -1;
};

}  // namespace

std::unique_ptr<LinearSolver> make_petsc_solver(bool symmetric, const std::string& options,
                                                LocalRows local_rows) {
  return std::make_unique<PetscSolver>(symmetric, options, std::move(local_rows));
}

#else

std::unique_ptr<LinearSolver> make_petsc_solver(bool, const std::string&, LocalRows) {
  throw std::invalid_argument(
      "solver.linear_solver: petsc needs nodus built with PETSc (install petsc-dev and rebuild)");
}

#endif

}  // namespace nodus::solver
