// RunOutput protocol (staging, summary.json last, FAILED on unwinding) and make_manifest.
#include "core/base/error.hpp"
#include "core/base/interrupt.hpp"
#include "core/io/atomic_file.hpp"
#include "core/results/run_output.hpp"
#include "core/testing/temp_dir.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <sstream>

#include <sched.h>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

using tmlab::testing::read_file;
using tmlab::testing::write_file;

class RunOutputTest : public tmlab::testing::TempDirTest {
 protected:
  const fs::path& root_ = dir_;  // where each test puts its result directories
};

TEST_F(RunOutputTest, FinalizeMovesFilesAndWritesSummaryLast) {
  const fs::path dir = root_ / "results" / "cube";
  {
    tmlab::RunOutput out(dir);
    EXPECT_TRUE(fs::exists(dir / "RUNNING"));
    EXPECT_TRUE(fs::is_directory(dir / ".incomplete"));
    const fs::path vtu = out.file("steps/step_000001.vtu");
    EXPECT_EQ(vtu, dir / ".incomplete" / "steps" / "step_000001.vtu");
    write_file(vtu, "<VTKFile/>");
    out.write_json("manifest.json", {{"a", 1}});
    EXPECT_FALSE(fs::exists(dir / "manifest.json"));  // staged, not in place yet
    EXPECT_FALSE(fs::exists(dir / "summary.json"));
    out.finalize({{"steps", 12}});
    EXPECT_TRUE(out.finalized());
  }
  EXPECT_TRUE(fs::exists(dir / "steps" / "step_000001.vtu"));
  EXPECT_TRUE(fs::exists(dir / "manifest.json"));
  EXPECT_FALSE(fs::exists(dir / ".incomplete"));
  EXPECT_FALSE(fs::exists(dir / "RUNNING"));
  EXPECT_FALSE(fs::exists(dir / "FAILED"));
  const auto summary = nlohmann::json::parse(read_file(dir / "summary.json"));
  EXPECT_EQ(summary["steps"], 12);
  EXPECT_EQ(summary["status"], "complete");
  EXPECT_EQ(summary["files"], (nlohmann::json{"manifest.json", "steps"}));
  EXPECT_GE(summary["wall_seconds"].get<double>(), 0.0);
  EXPECT_EQ(summary["finished_utc"].get<std::string>().back(), 'Z');
}

TEST_F(RunOutputTest, ExceptionBeforeFinalizeLeavesFailedAndNoSummary) {
  const fs::path dir = root_ / "diverges";
  try {
    tmlab::RunOutput out(dir);
    write_file(out.file("u.vtu"), "partial");
    throw tmlab::Error("step 17: element 4 inverted");
  } catch (const tmlab::Error&) {
  }
  EXPECT_FALSE(fs::exists(dir / "summary.json"));
  EXPECT_FALSE(fs::exists(dir / "RUNNING"));
  EXPECT_FALSE(fs::exists(dir / "u.vtu"));                 // never moved into place
  EXPECT_TRUE(fs::exists(dir / ".incomplete" / "u.vtu"));  // kept for inspection
  ASSERT_TRUE(fs::exists(dir / "FAILED"));
  EXPECT_NE(read_file(dir / "FAILED").find("exception"), std::string::npos) << read_file(dir / "FAILED");
}

TEST_F(RunOutputTest, ExplicitFailRecordsTheMessage) {
  const fs::path dir = root_ / "explicit";
  try {
    tmlab::RunOutput out(dir);
    try {
      throw tmlab::Error("mesh.msh:12: bad node");
    } catch (const std::exception& e) {
      out.fail(e.what());
      throw;
    }
  } catch (const tmlab::Error&) {
  }
  EXPECT_NE(read_file(dir / "FAILED").find("mesh.msh:12: bad node"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "summary.json"));
}

TEST_F(RunOutputTest, RerunClearsPreviousResultFirst) {
  const fs::path dir = root_ / "rerun";
  {
    tmlab::RunOutput out(dir);
    write_file(out.file("old.txt"), "old");
    out.finalize();
  }
  ASSERT_TRUE(fs::exists(dir / "summary.json"));
  {
    tmlab::RunOutput out(dir);
    EXPECT_FALSE(fs::exists(dir / "summary.json"));  // the old run no longer marks it complete
    EXPECT_FALSE(fs::exists(dir / "old.txt"));
  }  // destroyed without finalize
  EXPECT_TRUE(fs::exists(dir / "FAILED"));
  EXPECT_FALSE(fs::exists(dir / "summary.json"));
  {
    tmlab::RunOutput out(dir);
    EXPECT_FALSE(fs::exists(dir / "FAILED"));
    out.finalize();
    EXPECT_THROW(out.finalize(), tmlab::Error);
  }
  EXPECT_TRUE(fs::exists(dir / "summary.json"));
}

TEST_F(RunOutputTest, RefusesForeignDirectoryAndBadNames) {
  const fs::path dir = root_ / "home";
  fs::create_directories(dir);
  write_file(dir / "thesis.tex", "precious");
  EXPECT_THROW(tmlab::RunOutput out(dir), tmlab::Error);
  EXPECT_TRUE(fs::exists(dir / "thesis.tex"));

  tmlab::RunOutput out(root_ / "ok");
  EXPECT_THROW(out.file("../escape.txt"), tmlab::Error);
  EXPECT_THROW(out.file("/abs.txt"), tmlab::Error);
  EXPECT_THROW(out.file(""), tmlab::Error);
  out.finalize();
}

TEST_F(RunOutputTest, SecondWriterIsRefusedAndNamesTheFirst) {
  const fs::path dir = root_ / "busy";
  {
    tmlab::RunOutput first(dir);
    write_file(first.file("a.txt"), "first");
    try {
      tmlab::RunOutput second(dir);
      FAIL() << "a second writer was accepted";
    } catch (const tmlab::Error& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("another tmlab run is writing"), std::string::npos) << m;
      EXPECT_NE(m.find("pid " + std::to_string(::getpid())), std::string::npos) << m;
    }
    // The refused writer touched nothing: the first run goes on and completes.
    EXPECT_TRUE(fs::exists(dir / "RUNNING"));
    EXPECT_FALSE(fs::exists(dir / "FAILED"));
    first.finalize();
  }
  EXPECT_EQ(read_file(dir / "a.txt"), "first");
  EXPECT_FALSE(fs::exists(dir / "FAILED"));
  // Released with the first: a new run may start.
  tmlab::RunOutput again(dir);
  again.finalize();
}

TEST_F(RunOutputTest, LockHoldsAcrossProcesses) {
  const fs::path dir = root_ / "shared";
  int ready[2], done[2];
  ASSERT_EQ(::pipe(ready), 0);
  ASSERT_EQ(::pipe(done), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    {
      tmlab::RunOutput out(dir);
      char c = 'r';
      (void)!::write(ready[1], &c, 1);
      (void)!::read(done[0], &c, 1);  // hold the directory until the parent has tried
      out.finalize();
    }
    std::_Exit(0);
  }
  char c = 0;
  ASSERT_EQ(::read(ready[0], &c, 1), 1);
  try {
    tmlab::RunOutput second(dir);
    ADD_FAILURE() << "the directory held by pid " << child << " was taken";
  } catch (const tmlab::Error& e) {
    EXPECT_NE(std::string(e.what()).find("pid " + std::to_string(child)), std::string::npos) << e.what();
  }
  c = 'd';
  ASSERT_EQ(::write(done[1], &c, 1), 1);
  int status = 0;
  ::waitpid(child, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_TRUE(fs::exists(dir / "summary.json"));
  EXPECT_FALSE(fs::exists(dir / "FAILED"));
}

TEST_F(RunOutputTest, StaleRunningMarkerIsReportedAndCleared) {
  // A process killed with SIGKILL leaves RUNNING and .incomplete/ but no lock.
  const fs::path dir = root_ / "stale";
  fs::create_directories(dir / ".incomplete");
  write_file(dir / ".tmlab-result", R"({"format": "tmlab-result/1", "run_id": "1", "files": []})");
  write_file(dir / "RUNNING",
             R"({"pid": 999999, "hostname": "gone", "started_utc": "2026-01-01T00:00:00Z"})");
  write_file(dir / ".incomplete" / "half.h5", "half");
  std::ostringstream log;
  tmlab::RunOutput out(dir, &log);
  EXPECT_NE(log.str().find("stale RUNNING marker (pid 999999 on gone"), std::string::npos) << log.str();
  EXPECT_FALSE(fs::exists(dir / ".incomplete" / "half.h5"));
  out.finalize();
  EXPECT_TRUE(fs::exists(dir / "summary.json"));
}

TEST_F(RunOutputTest, InterruptLeavesInterruptedNotFailed) {
  const fs::path dir = root_ / "stopped";
  try {
    tmlab::RunOutput out(dir);
    write_file(out.file("timeseries.h5"), "partial");
    try {
      throw tmlab::Interrupted(2, "SIGINT received at t = 0.5 s (step 5 of 10)");
    } catch (const std::exception& e) {
      out.abandon(e);
      EXPECT_TRUE(out.interrupted());
      throw;
    }
  } catch (const tmlab::Interrupted&) {
  }
  ASSERT_TRUE(fs::exists(dir / "INTERRUPTED"));
  EXPECT_NE(read_file(dir / "INTERRUPTED").find("step 5 of 10"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "FAILED"));
  EXPECT_FALSE(fs::exists(dir / "RUNNING"));
  EXPECT_FALSE(fs::exists(dir / "summary.json"));
  EXPECT_TRUE(fs::exists(dir / ".incomplete" / "timeseries.h5"));
  // An interrupted directory is a result directory: the next run may reuse it.
  tmlab::RunOutput next(dir);
  EXPECT_FALSE(fs::exists(dir / "INTERRUPTED"));
  next.finalize();
}

TEST_F(RunOutputTest, ResumeKeepsTheStagedFilesOfAnInterruptedRun) {
  const fs::path dir = root_ / "resumable";
  using Previous = tmlab::RunOutput::Previous;
  // Nothing to resume: refused, and the directory is not locked afterwards.
  EXPECT_THROW(tmlab::RunOutput(dir, nullptr, Previous::ResumeInterrupted), tmlab::Error);
  try {
    tmlab::RunOutput out(dir);
    write_file(out.file("part-1/summary.json"), "{}");
    out.abandon(tmlab::Interrupted(2, "SIGINT received"));
  } catch (const tmlab::Interrupted&) {
  }
  ASSERT_TRUE(fs::exists(dir / "INTERRUPTED"));
  {
    tmlab::RunOutput resumed(dir, nullptr, Previous::ResumeInterrupted);
    EXPECT_FALSE(fs::exists(dir / "INTERRUPTED"));
    EXPECT_TRUE(fs::exists(resumed.file("part-1/summary.json")));  // kept for reuse
    write_file(resumed.file("part-2/summary.json"), "{}");
    resumed.finalize();
  }
  EXPECT_TRUE(fs::exists(dir / "part-1" / "summary.json"));
  EXPECT_TRUE(fs::exists(dir / "part-2" / "summary.json"));
  // A finished directory has nothing to resume; a normal run discards everything.
  EXPECT_THROW(tmlab::RunOutput(dir, nullptr, Previous::ResumeInterrupted), tmlab::Error);
  tmlab::RunOutput fresh(dir);
  EXPECT_FALSE(fs::exists(fresh.file("part-1/summary.json")));
  fresh.finalize();
}

TEST_F(RunOutputTest, ResumeStoppedAlsoKeepsTheStagedFilesOfAFailedRun) {
  const fs::path dir = root_ / "failed";
  using Previous = tmlab::RunOutput::Previous;
  {
    tmlab::RunOutput out(dir);
    write_file(out.file("part-1/summary.json"), "{}");
    out.fail("part 2 did not converge");
  }
  ASSERT_TRUE(fs::exists(dir / "FAILED"));
  // ResumeInterrupted does not take a failed run; ResumeStopped does, keeping its staged parts.
  EXPECT_THROW(tmlab::RunOutput(dir, nullptr, Previous::ResumeInterrupted), tmlab::Error);
  ASSERT_TRUE(fs::exists(dir / "FAILED"));  // the refusal changed nothing
  {
    tmlab::RunOutput resumed(dir, nullptr, Previous::ResumeStopped);
    EXPECT_FALSE(fs::exists(dir / "FAILED"));
    EXPECT_TRUE(fs::exists(resumed.file("part-1/summary.json")));
    resumed.finalize();
  }
  // A complete result has nothing to resume, whichever way.
  try {
    tmlab::RunOutput again(dir, nullptr, Previous::ResumeStopped);
    ADD_FAILURE() << "a complete result was resumed";
  } catch (const tmlab::Error& e) {
    EXPECT_NE(std::string(e.what()).find("nothing to resume"), std::string::npos) << e.what();
  }
}

TEST_F(RunOutputTest, ResumeContinuesARunWhoseProcessDied) {
  // What SIGKILL leaves: a RUNNING marker of a process that is gone and the staged files.
  const fs::path dir = root_ / "killed";
  fs::create_directories(dir / ".incomplete");
  write_file(dir / ".tmlab-result", R"({"format": "tmlab-result/1", "run_id": "1", "files": []})");
  write_file(dir / "RUNNING", "{\"pid\": 999999999, \"hostname\": \"h\"}\n");
  write_file(dir / ".incomplete" / "checkpoint.h5", "x");
  std::ostringstream log;
  tmlab::RunOutput resumed(dir, &log, tmlab::RunOutput::Previous::ResumeInterrupted);
  EXPECT_NE(log.str().find("resuming from its staged files"), std::string::npos) << log.str();
  EXPECT_TRUE(fs::exists(resumed.file("checkpoint.h5")));
  resumed.finalize();
}

TEST_F(RunOutputTest, FinalizeLeavesNoStagingBehind) {
  const fs::path dir = root_ / "swap";
  {
    tmlab::RunOutput out(dir);
    write_file(out.file("x.txt"), "x");
    out.finalize();
  }
  // Only the result is left in the parent: no staging tree, no lock file.
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(root_)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"swap"}));
  EXPECT_EQ(read_file(dir / "x.txt"), "x");
}

/// Runs `body` in a child process with a `kib` KiB tmpfs mounted (in a mount namespace of its own) on
/// `mount_point`; returns the child's exit status, or -1 when no tmpfs can be mounted here.
template <typename F>
int with_small_tmpfs(const fs::path& mount_point, int kib, F&& body) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    const bool root = ::geteuid() == 0;
    if (root ? ::unshare(CLONE_NEWNS) != 0 : ::unshare(CLONE_NEWUSER | CLONE_NEWNS) != 0) ::_exit(77);
    if (!root) {
      const std::string uid = "0 " + std::to_string(::getuid()) + " 1\n";
      const std::string gid = "0 " + std::to_string(::getgid()) + " 1\n";
      write_file("/proc/self/setgroups", "deny");
      write_file("/proc/self/uid_map", uid);
      write_file("/proc/self/gid_map", gid);
    }
    ::mount("none", "/", nullptr, MS_REC | MS_PRIVATE, nullptr);
    const std::string size = "size=" + std::to_string(kib) + "k";
    if (::mount("tmpfs", mount_point.c_str(), "tmpfs", 0, size.c_str()) != 0) ::_exit(77);
    ::_exit(body());
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 77) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 100 + WTERMSIG(status);
}

TEST_F(RunOutputTest, AFullDiskEndsInFailedWithTheReasonNeverInRunning) {
  // Issue 26: a full disk left RUNNING (the FAILED marker could not be written) and the next run
  // called it a crash. RUNNING reserves its room; FAILED is made from it.
  const fs::path mnt = root_ / "small";
  fs::create_directories(mnt);
  const int rc = with_small_tmpfs(mnt, 64, [&]() -> int {
    const fs::path dir = mnt / "r";
    try {
      tmlab::RunOutput out(dir);
      std::string block(4096, 'x');
      for (int k = 0;; ++k) tmlab::write_file_atomically(mnt / ("filler" + std::to_string(k)), block);
    } catch (const std::exception&) {
    }
    // The filler threw once the disk was full; the run above ended by the exception.
    if (fs::exists(dir / "RUNNING")) return 1;
    if (!fs::exists(dir / "FAILED")) return 2;
    if (read_file(dir / "FAILED").find("exception") == std::string::npos) return 3;
    for (int k = 0; fs::exists(mnt / ("filler" + std::to_string(k))); ++k)
      if (k % 2 == 0) fs::remove(mnt / ("filler" + std::to_string(k)));
    try {  // a run that meets the full disk while writing its own result
      tmlab::RunOutput out(dir);
      try {
        for (int k = 0;; ++k)
          tmlab::write_file_atomically(out.file("big" + std::to_string(k)), std::string(8192, 'y'));
      } catch (const std::exception& e) {
        out.fail(e.what());
      }
    } catch (const std::exception&) {
      return 5;
    }
    if (fs::exists(dir / "RUNNING")) return 6;
    if (!fs::exists(dir / "FAILED")) return 7;
    if (read_file(dir / "FAILED").find("No space left on device") == std::string::npos) return 8;
    return 0;
  });
  if (rc == -1) GTEST_SKIP() << "no tmpfs can be mounted here (needs root or user namespaces)";
  EXPECT_EQ(rc, 0) << "step that failed (see the child's checks)";
}

TEST(ResultNames, SafeCharactersOnly) {
  EXPECT_EQ(tmlab::result_name_problem("liver-probe_2.p2+ida"), "");
  EXPECT_NE(tmlab::result_name_problem(""), "");
  EXPECT_NE(tmlab::result_name_problem("a';touch${IFS}X;'"), "");
  EXPECT_NE(tmlab::result_name_problem("a b"), "");
  EXPECT_NE(tmlab::result_name_problem("a/b"), "");
  EXPECT_NE(tmlab::result_name_problem(".hidden"), "");
  EXPECT_NE(tmlab::result_name_problem("-rf"), "");
  EXPECT_NE(tmlab::result_name_problem("$(x)"), "");
  EXPECT_NE(tmlab::result_name_problem(std::string(101, 'a')), "");
  EXPECT_NE(tmlab::result_name_problem("caf\xc3\xa9"), "");
}

TEST_F(RunOutputTest, ManifestRecordsBuildInputsAndTimes) {
  const fs::path input = root_ / "mesh.msh";
  write_file(input, "a");
  tmlab::ManifestInput in;
  in.command_line = tmlab::command_line(2, std::array<const char*, 2>{"tmlab", "run"}.data());
  in.config = {{"dt", 1e-3}};
  in.input_files = {input};
  const nlohmann::json m = tmlab::make_manifest(in);
  EXPECT_EQ(m["command_line"], (nlohmann::json{"tmlab", "run"}));
  EXPECT_EQ(m["config"]["dt"], 1e-3);
  EXPECT_TRUE(m["git"]["sha"].is_string());
  EXPECT_TRUE(m["git"]["dirty"].is_boolean());
  EXPECT_TRUE(m["build"].contains("type"));
  EXPECT_TRUE(m["build"].contains("compiler"));
  EXPECT_TRUE(m["build"].contains("flags"));
  EXPECT_FALSE(m["tmlab_version"].get<std::string>().empty());
  EXPECT_FALSE(m["hostname"].get<std::string>().empty());
  EXPECT_EQ(m["started_utc"].get<std::string>().size(), std::string("2026-01-01T00:00:00Z").size());
  ASSERT_EQ(m["inputs"].size(), 1u);
  EXPECT_EQ(m["inputs"][0]["size"], 1);
  EXPECT_EQ(m["inputs"][0]["fnv1a64"], "af63dc4c8601ec8c");  // FNV-1a-64("a")
  EXPECT_TRUE(fs::path(m["inputs"][0]["path"].get<std::string>()).is_absolute());

  in.input_files = {root_ / "missing.msh"};
  try {
    tmlab::make_manifest(in);
    FAIL() << "expected tmlab::Error";
  } catch (const tmlab::Error& e) {
    EXPECT_NE(std::string(e.what()).find("missing.msh"), std::string::npos);
  }
}

TEST(ManifestHelpers, HashAndTime) {
  EXPECT_EQ(tmlab::fnv1a64("", 0), 0xcbf29ce484222325ULL);
  EXPECT_EQ(tmlab::fnv1a64("foobar", 6), 0x85944171f73967e8ULL);
  EXPECT_EQ(tmlab::utc_iso8601(std::chrono::system_clock::from_time_t(0)), "1970-01-01T00:00:00Z");
  EXPECT_EQ(tmlab::utc_iso8601(std::chrono::system_clock::from_time_t(1700000000)), "2023-11-14T22:13:20Z");
}

}  // namespace
