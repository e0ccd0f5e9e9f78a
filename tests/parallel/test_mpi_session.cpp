// The command line's PETSc options, and the one-process defaults of the MPI session.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "nodus/parallel/mpi_session.hpp"

namespace {

using nodus::parallel::split_petsc_options;

std::vector<std::string> words(std::initializer_list<const char*> list) {
  return {list.begin(), list.end()};
}

TEST(SplitPetscOptions, GivesPetscItsOptionsWithTheirValuesAndKeepsTheRestInOrder) {
  const char* argv[] = {"nodus",
                        "run",
                        "k.yaml",
                        "-ksp_view",
                        "--out",
                        "dir",
                        "-pc_factor_mat_solver_type",
                        "superlu_dist",
                        "-mat_mumps_icntl_14",
                        "50",
                        "-q",
                        "-mat_mumps_cntl_1",
                        "-0.5",
                        "-mg_levels_pc_type",
                        "pbjacobi",
                        "-sub_pc_type",
                        "icc",
                        "-log_view"};
  const auto split = split_petsc_options(static_cast<int>(std::size(argv)), argv);
  EXPECT_EQ(split.petsc, words({"-ksp_view", "-pc_factor_mat_solver_type", "superlu_dist",
                                "-mat_mumps_icntl_14", "50", "-mat_mumps_cntl_1", "-0.5",
                                "-mg_levels_pc_type", "pbjacobi", "-sub_pc_type", "icc", "-log_view"}));
  EXPECT_EQ(split.rest, words({"nodus", "run", "k.yaml", "--out", "dir", "-q"}));
}

TEST(SplitPetscOptions, LeavesNodusOptionsAndPositionalArgumentsAlone) {
  // The program name is never an option, and a lone prefix ("-pc_") is no PETSc option.
  const char* argv[] = {"-ksp_type", "run", "-pc_", "-o", "-mat_x"};
  const auto split = split_petsc_options(static_cast<int>(std::size(argv)), argv);
  EXPECT_EQ(split.petsc, words({"-mat_x"}));
  EXPECT_EQ(split.rest, words({"-ksp_type", "run", "-pc_", "-o"}));
}

TEST(MpiSession, IsOneProcessUntilMpiStarts) {
  // The test runs without a launcher: no solver here has started MPI.
  if (nodus::parallel::active()) GTEST_SKIP() << "MPI already started in this process";
  EXPECT_EQ(nodus::parallel::rank(), 0);
  EXPECT_EQ(nodus::parallel::size(), 1);
  EXPECT_TRUE(nodus::parallel::is_root());
  nodus::parallel::barrier();  // a no-op
}

TEST(MpiSession, RefusesPetscOptionsWithoutPetsc) {
  if (nodus::parallel::available()) GTEST_SKIP() << "built with PETSc";
  EXPECT_THROW(nodus::parallel::initialize({"-ksp_view"}), std::invalid_argument);
  EXPECT_NO_THROW(nodus::parallel::initialize({}));
}

}  // namespace
