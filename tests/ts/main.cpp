// GoogleTest main for the PETSc-level tests: PETSc is initialized once for all of them, and
// only rank 0 prints GoogleTest's report (every rank runs every test: they are collective).
#include <gtest/gtest.h>
#include <petscvshmm.h>

#include <cstdio>
#include <cstdlib>

int main(int argc, char **argv)
{
  ::testing::InitGoogleTest(&argc, argv);
  if (PetscInitialize(&argc, &argv, nullptr, nullptr)) return 1;
  if (TSVSHMMInitializePackage()) return 1;
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank && !getenv("VSHMM_TEST_ALL_RANKS")) {
    ::testing::TestEventListeners &listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  int status = RUN_ALL_TESTS();
  if (status) fprintf(stderr, "[%d] tests failed on this rank\n", rank);
  int global = status;
  MPI_Allreduce(&status, &global, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  if (PetscFinalize()) {
    fprintf(stderr, "[%d] PetscFinalize failed\n", rank);
    return 1;
  }
  return global;
}
