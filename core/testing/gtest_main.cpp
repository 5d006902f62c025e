// main() of every tmlab test executable (tmlab_add_gtest): GoogleTest's, but a run with a skipped test
// exits with kSkipExitCode, which ctest reports as "Skipped", not "Passed".
#include "core/testing/gtest_exit.hpp"

#include <gtest/gtest.h>

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  return tmlab::testing::gtest_exit_code(RUN_ALL_TESTS());
}
