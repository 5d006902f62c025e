// gtest main for the reference tests: MPI (and deal.II) initialised once per process.
#include "core/testing/gtest_exit.hpp"
#include "reference_fem/dealii/reference_runner.hpp"

#include <gtest/gtest.h>

int main(int argc, char** argv) {
  tmlab::ref::MpiSession mpi(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  // Under mpirun only rank 0 prints gtest's report.
  if (tmlab::ref::MpiSession::rank() != 0) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  return tmlab::testing::gtest_exit_code(RUN_ALL_TESTS());
}
