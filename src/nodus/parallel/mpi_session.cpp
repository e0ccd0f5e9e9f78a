#include "nodus/parallel/mpi_session.hpp"

#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include <fmt/format.h>

#ifdef NODUS_HAVE_PETSC
#include <mpi.h>
#include <petscsys.h>

#include "nodus/parallel/petsc_check.hpp"
#endif

extern char** environ;

namespace nodus::parallel {
namespace {

/// The prefixes of PETSc's options for the linear solve: the Krylov method, the preconditioner, the matrix,
/// the options files, and the inner solvers of multigrid levels (-mg_levels_, -mg_coarse_) and of block
/// preconditioners (-sub_).
bool is_petsc_option(std::string_view arg) {
  for (std::string_view prefix : {"-ksp_", "-pc_", "-mat_", "-options_", "-mg_", "-sub_"})
    if (arg.starts_with(prefix) && arg.size() > prefix.size()) return true;
  return arg == "-log_view" || arg.starts_with("-log_view:");
}

/// A value follows an option unless it is itself an option (a negative number is a value).
bool is_value(std::string_view arg) {
  if (!arg.starts_with('-') || arg.size() == 1) return true;
  const char c = arg[1];
  return (c >= '0' && c <= '9') || c == '.';
}

#ifdef NODUS_HAVE_PETSC
bool started_here = false;  // PetscInitialize was called by this module

constexpr auto check = check_petsc;
#endif

std::vector<std::string> given_options;  // the command line's, from initialize()

}  // namespace

const std::vector<std::string>& command_line_options() {
  return given_options;
}

bool well_formed_options(const std::string& options) {
  std::istringstream words(options);
  bool after_option = false;  // a value may follow
  for (std::string w; words >> w;) {
    if (!is_value(w)) {
      after_option = true;
    } else if (after_option) {
      after_option = false;
    } else {
      return false;  // a value that follows no option
    }
  }
  return true;
}

std::vector<std::string> environment_for_another_program() {
  std::vector<std::string> environment;
  const bool strip = active();
  for (char** e = environ; *e != nullptr; ++e) {
    const std::string_view entry = *e;
    bool runtime = false;
    for (std::string_view prefix : {"OMPI_", "PMIX_", "PMI_", "OPAL_", "ORTE_"})
      runtime = runtime || entry.starts_with(prefix);
    if (!(strip && runtime)) environment.emplace_back(entry);
  }
  return environment;
}

bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"})
    if (std::getenv(name) != nullptr) return true;
  return false;
}

SplitArguments split_petsc_options(int argc, const char* const* argv) {
  SplitArguments split;
  for (int i = 0; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (i > 0 && is_petsc_option(arg)) {
      split.petsc.emplace_back(arg);
      if (i + 1 < argc && is_value(argv[i + 1])) split.petsc.emplace_back(argv[++i]);
    } else {
      split.rest.emplace_back(arg);
    }
  }
  return split;
}

#ifdef NODUS_HAVE_PETSC

bool available() {
  return true;
}

bool active() {
  int initialized = 0, finalized = 0;
  MPI_Initialized(&initialized);
  MPI_Finalized(&finalized);
  return initialized != 0 && finalized == 0;
}

void initialize(const std::vector<std::string>& petsc_options) {
  if (PetscInitializeCalled) return;
  // PetscInitialize reads argv as a command line: the program name first, then the options.
  std::vector<std::string> words{"nodus"};
  words.insert(words.end(), petsc_options.begin(), petsc_options.end());
  std::vector<char*> pointers;
  for (std::string& w : words) pointers.push_back(w.data());
  pointers.push_back(nullptr);
  int argc = static_cast<int>(words.size());
  char** argv = pointers.data();
  check(PetscInitialize(&argc, &argv, nullptr, nullptr), "PetscInitialize");
  // PETSc's own error handler prints a traceback and aborts MPI; nodus reports errors itself, once.
  check(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr), "PetscPushErrorHandler");
  started_here = true;
  given_options = petsc_options;
}

void ensure_initialized() {
  if (PetscInitializeCalled) return;
  initialize({});
  std::atexit(finalize);
}

void finalize() {
  if (!started_here || PetscFinalizeCalled) return;
  PetscFinalize();  // also MPI_Finalize, since PetscInitialize started MPI
  started_here = false;
}

int rank() {
  if (!active()) return 0;
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

int size() {
  if (!active()) return 1;
  int n = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &n);
  return n;
}

void barrier() {
  if (active()) MPI_Barrier(MPI_COMM_WORLD);
}

void abort_all(int status) {
  if (size() > 1) MPI_Abort(MPI_COMM_WORLD, status);
}

bool root_value(bool value) {
  if (size() <= 1) return value;
  int v = value ? 1 : 0;
  if (MPI_Bcast(&v, 1, MPI_INT, 0, MPI_COMM_WORLD) != MPI_SUCCESS)
    throw std::runtime_error("MPI_Bcast failed");
  return v != 0;
}

void share_segments(double* values, const std::vector<int>& starts) {
  const int n = size();
  if (n <= 1) return;
  std::vector<int> counts(static_cast<std::size_t>(n));
  for (std::size_t r = 0; r < counts.size(); ++r) counts[r] = starts[r + 1] - starts[r];
  if (MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, values, counts.data(), starts.data(), MPI_DOUBLE,
                     MPI_COMM_WORLD) != MPI_SUCCESS)
    throw std::runtime_error("MPI_Allgatherv failed");
}

void sum_over_ranks(double* values, std::size_t count) {
  if (size() <= 1 || count == 0) return;
  if (MPI_Allreduce(MPI_IN_PLACE, values, static_cast<int>(count), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD) !=
      MPI_SUCCESS)
    throw std::runtime_error("MPI_Allreduce failed");
}

#else  // without PETSc: one process

bool available() {
  return false;
}
bool active() {
  return false;
}
void initialize(const std::vector<std::string>& petsc_options) {
  if (!petsc_options.empty())
    throw std::invalid_argument(fmt::format(
        "PETSc option '{}' given, but this nodus was built without PETSc (install petsc-dev and rebuild)",
        petsc_options.front()));
}
void ensure_initialized() {}
void finalize() {}
int rank() {
  return 0;
}
int size() {
  return 1;
}
void barrier() {}
void abort_all(int) {}
bool root_value(bool value) {
  return value;
}
void share_segments(double*, const std::vector<int>&) {}
void sum_over_ranks(double*, std::size_t) {}
#endif

}  // namespace nodus::parallel
