// The exit status of a test executable, so that a skip never reads as a pass (issue 27): ctest shows a
// test as "Skipped" when its executable exits with kSkipExitCode (SKIP_RETURN_CODE, set for every test
// by tmlab_add_gtest), which it does when no test failed and at least one called GTEST_SKIP.
#pragma once

#include <gtest/gtest.h>

namespace tmlab::testing {

inline constexpr int kSkipExitCode = 77;

/// RUN_ALL_TESTS()'s result, or kSkipExitCode when it passed with a skipped test.
inline int gtest_exit_code(int run_all_tests_result) {
  if (run_all_tests_result != 0) return run_all_tests_result;
  return ::testing::UnitTest::GetInstance()->skipped_test_count() > 0 ? kSkipExitCode : 0;
}

}  // namespace tmlab::testing
