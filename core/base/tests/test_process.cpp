// run_process: an argument vector reaches the program verbatim (no shell), exit codes and signals
// are reported, output goes where asked, and a missing program is an error, not a crash.
#include "core/base/error.hpp"
#include "core/base/process.hpp"
#include "core/testing/temp_dir.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

namespace fs = std::filesystem;

namespace {

using tmlab::testing::read_file;

class ProcessTest : public tmlab::testing::TempDirTest {};

TEST_F(ProcessTest, ShellMetacharactersAreNeverInterpreted) {
  // Each of these would create a file through a shell; as argv entries they are just text.
  const fs::path victim = dir_ / "X";
  const std::vector<std::string> hostile = {"a';touch${IFS}" + victim.string() + ";'",
                                            "$(touch " + victim.string() + ")",
                                            "`touch " + victim.string() + "`", "; touch " + victim.string(),
                                            "\"; touch " + victim.string() + "; \""};
  std::vector<std::string> argv = {"/bin/echo"};
  argv.insert(argv.end(), hostile.begin(), hostile.end());
  const fs::path log = dir_ / "echo.log";
  const tmlab::ProcessStatus st = tmlab::run_process(argv, tmlab::ProcessOutput::to_file(log));
  ASSERT_TRUE(st.ok()) << st.describe();
  EXPECT_FALSE(fs::exists(victim));
  std::string expected;
  for (const auto& h : hostile) expected += (expected.empty() ? "" : " ") + h;
  EXPECT_EQ(read_file(log), expected + "\n");
}

TEST_F(ProcessTest, ExitStatusSignalAndMissingProgram) {
  const auto f = tmlab::run_process({"/bin/sh", "-c", "exit 3"}, tmlab::ProcessOutput::discard());
  EXPECT_TRUE(f.started);
  EXPECT_EQ(f.exit_code, 3);
  EXPECT_FALSE(f.ok());
  EXPECT_EQ(f.describe(), "exit status 3");

  const auto k = tmlab::run_process({"/bin/sh", "-c", "kill -9 $$"}, tmlab::ProcessOutput::discard());
  EXPECT_EQ(k.signal, 9);
  EXPECT_FALSE(k.ok());

  const auto m = tmlab::run_process({"/nonexistent/tmlab-no-such-program"}, tmlab::ProcessOutput::discard());
  EXPECT_FALSE(m.started);
  EXPECT_FALSE(m.ok());
  EXPECT_NE(m.describe().find("could not start"), std::string::npos) << m.describe();

  EXPECT_THROW(tmlab::run_process({}), tmlab::Error);
  EXPECT_THROW(
      tmlab::run_process({"/bin/true"}, tmlab::ProcessOutput::to_file(dir_ / "no" / "such" / "dir.log")),
      tmlab::Error);
}

TEST_F(ProcessTest, StandardErrorGoesToTheSameLog) {
  const fs::path log = dir_ / "both.log";
  const auto st =
      tmlab::run_process({"/bin/sh", "-c", "echo out; echo err 1>&2"}, tmlab::ProcessOutput::to_file(log));
  ASSERT_TRUE(st.ok());
  EXPECT_EQ(read_file(log), "out\nerr\n");
}

TEST(PythonInterpreter, EnvironmentOverrides) {
  ::setenv("TMLAB_PYTHON", "/opt/my/python3", 1);
  EXPECT_EQ(tmlab::python_interpreter(), "/opt/my/python3");
  ::unsetenv("TMLAB_PYTHON");
  const std::string p = tmlab::python_interpreter();
  EXPECT_TRUE(p == "/usr/bin/python3" || p == "python3") << p;
}

}  // namespace
