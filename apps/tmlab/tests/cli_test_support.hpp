// Shared by the command-line tests: run the built `tmlab` driver (through a shell for readable
// tests, or with an argument vector when the arguments themselves are hostile) and capture its
// exit status and combined output. Each test gets its own temporary directory from
// tmlab::testing::TempDirTest (core/testing/temp_dir.hpp).
#pragma once

#include "core/base/process.hpp"
#include "core/testing/temp_dir.hpp"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <sched.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <optional>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace tmlab::cli_test {

struct Result {
  int status = -1;     ///< exit status of the driver (-1 if it did not exit normally)
  std::string output;  ///< stdout and stderr together
};

/// Runs `tmlab <args>` (TMLAB_CLI, set by CMake) with TMLAB_ROOT pointing at the source tree.
inline Result run(const std::string& args) {
  const std::string cmd =
      std::string("TMLAB_ROOT='") + TMLAB_SOURCE_DIR + "' '" + TMLAB_CLI + "' " + args + " 2>&1";
  Result r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), buf.size(), p)) r.output += buf.data();
  const int st = pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

/// Runs `tmlab argv...` with an argument vector (no shell): every argument arrives verbatim.
/// `log` receives stdout and stderr.
inline Result run_argv(const std::vector<std::string>& args, const std::filesystem::path& log) {
  ::setenv("TMLAB_ROOT", TMLAB_SOURCE_DIR, 1);
  std::vector<std::string> argv{TMLAB_CLI};
  argv.insert(argv.end(), args.begin(), args.end());
  const tmlab::ProcessStatus st = tmlab::run_process(argv, tmlab::ProcessOutput::to_file(log));
  Result r;
  r.status = st.started && st.signal == 0 ? st.exit_code : -1;
  FILE* f = std::fopen(log.c_str(), "r");
  if (f) {
    std::array<char, 4096> buf{};
    while (std::fgets(buf.data(), buf.size(), f)) r.output += buf.data();
    std::fclose(f);
  }
  return r;
}

/// Waits (up to 5 minutes: the machine may be busy) until `p` exists.
inline bool wait_for(const std::filesystem::path& p) {
  for (int i = 0; i < 3000; ++i) {
    if (std::filesystem::exists(p)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return false;
}

/// The exit status of a spawned process (-signal when a signal ended it).
inline int wait_exit(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (WIFSIGNALED(status)) return -WTERMSIG(status);
  return WEXITSTATUS(status);
}

/// One of the silicone phantom files in the repository (calibration/data/phantom/).
inline std::filesystem::path phantom_a1() {
  return std::filesystem::path(TMLAB_SOURCE_DIR) / "calibration" / "data" / "phantom" / "EF10_0T" /
         "EF10_0T_A1.csv";
}

// ---- Result-directory properties and signals (issue 26) ----------------------------------------

/// One entry of a file-tree snapshot: "dir", "link:<target>" or "file:<size>:<hash>".
/// Keys are absolute paths, so snapshots of several roots can be merged and compared.
using Snapshot = std::map<std::string, std::string>;

/// Every entry under `root` (root itself included), symlinks recorded and not followed; file
/// contents hashed, so a rewrite with other bytes shows. A missing root gives an empty snapshot.
inline Snapshot snapshot(const std::filesystem::path& root) {
  namespace fs = std::filesystem;
  Snapshot s;
  std::error_code ec;
  auto record = [&s](const fs::path& p) {
    std::error_code e;
    const fs::file_status st = fs::symlink_status(p, e);
    if (e) return;
    if (fs::is_symlink(st)) {
      s[p.string()] = "link:" + fs::read_symlink(p, e).string();
    } else if (fs::is_directory(st)) {
      s[p.string()] = "dir";
    } else {
      std::ifstream in(p, std::ios::binary);
      const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      s[p.string()] =
          "file:" + std::to_string(bytes.size()) + ":" + std::to_string(std::hash<std::string>{}(bytes));
    }
  };
  if (!fs::exists(fs::symlink_status(root, ec))) return s;
  record(root);
  if (!fs::is_directory(fs::symlink_status(root, ec))) return s;
  for (auto it = fs::recursive_directory_iterator(root, fs::directory_options::skip_permission_denied, ec);
       !ec && it != fs::recursive_directory_iterator(); it.increment(ec))
    record(it->path());
  return s;
}

/// The entries of `before` that are missing or different in `after`, one per line ("" when none).
inline std::string lost_or_changed(const Snapshot& before, const Snapshot& after) {
  std::string out;
  for (const auto& [path, what] : before) {
    const auto it = after.find(path);
    if (it == after.end())
      out += "removed: " + path + "\n";
    else if (it->second != what)
      out += "changed: " + path + " (" + what + " -> " + it->second + ")\n";
  }
  return out;
}

/// The entries of `after` that `before` does not have, one per line ("" when none).
inline std::string created(const Snapshot& before, const Snapshot& after) {
  std::string out;
  for (const auto& [path, what] : after)
    if (!before.count(path)) out += "created: " + path + "\n";
  return out;
}

/// Starts `tmlab args...` (argument vector, no shell) with the working directory `cwd`; output
/// (stdout and stderr) to `log`.
inline pid_t spawn_in(const std::vector<std::string>& args, const std::filesystem::path& log,
                      const std::filesystem::path& cwd) {
  ::setenv("TMLAB_ROOT", TMLAB_SOURCE_DIR, 1);
  std::vector<std::string> argv{TMLAB_CLI};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<char*> c;
  for (auto& a : argv) c.push_back(a.data());
  c.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  if (!cwd.empty()) posix_spawn_file_actions_addchdir_np(&fa, cwd.c_str());
  pid_t pid = -1;
  EXPECT_EQ(::posix_spawn(&pid, c[0], &fa, nullptr, c.data(), environ), 0);
  posix_spawn_file_actions_destroy(&fa);
  return pid;
}

/// Starts `tmlab args...` in the background (argument vector, no shell); output to `log`.
inline pid_t spawn(const std::vector<std::string>& args, const std::filesystem::path& log) {
  return spawn_in(args, log, {});
}

/// Waits up to `seconds` for `pid` to end: its exit status, -signal when a signal ended it, or
/// std::nullopt when it was still running (it is then killed with SIGKILL and reaped).
inline std::optional<int> wait_exit_within(pid_t pid, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  for (;;) {
    int status = 0;
    const pid_t r = ::waitpid(pid, &status, WNOHANG);
    if (r == pid) return WIFSIGNALED(status) ? -WTERMSIG(status) : WEXITSTATUS(status);
    if (r < 0) return std::nullopt;
    if (std::chrono::steady_clock::now() > end) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      return std::nullopt;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

/// Runs `tmlab args...` in `cwd` (argument vector) and waits for it (up to `seconds`; a driver
/// still running then is killed and reported with status -1000).
inline Result run_in(const std::vector<std::string>& args, const std::filesystem::path& log,
                     const std::filesystem::path& cwd, double seconds = 900) {
  const pid_t pid = spawn_in(args, log, cwd);
  Result r;
  const std::optional<int> st = wait_exit_within(pid, seconds);
  r.status = !st ? -1000 : *st < 0 ? -1 : *st;
  std::ifstream in(log, std::ios::binary);
  r.output.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return r;
}

/// True once `p` exists while `pid` is alive (checked every 50 ms, up to `seconds`); false when
/// the process ended first (it is not reaped: wait_exit_within still gets its status) or time ran out.
inline bool wait_for_while_running(pid_t pid, const std::filesystem::path& p, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    std::error_code ec;
    if (std::filesystem::exists(p, ec)) return true;
    siginfo_t info{};
    if (::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 &&
        info.si_pid == pid)
      return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

/// Sets an environment variable for the drivers started while it lives (restores the old value).
class ScopedEnv {
 public:
  ScopedEnv(std::string name, const std::string& value) : name_(std::move(name)) {
    if (const char* old = std::getenv(name_.c_str())) old_ = std::string(old);
    ::setenv(name_.c_str(), value.c_str(), 1);
  }
  ~ScopedEnv() {
    if (old_)
      ::setenv(name_.c_str(), old_->c_str(), 1);
    else
      ::unsetenv(name_.c_str());
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  std::string name_;
  std::optional<std::string> old_;
};

/// Moves this test process (and the drivers it starts later) into a mount namespace of its own
/// whose mounts do not propagate to the host: as root with unshare(CLONE_NEWNS), otherwise in a
/// user namespace mapping this user to root (only works while the process has one thread).
/// "" on success, else why not (the caller skips with that reason).
inline std::string enter_private_mount_namespace() {
  if (::unshare(CLONE_NEWNS) != 0) {
    const int first = errno;
    const uid_t uid = ::getuid();
    const gid_t gid = ::getgid();
    if (::unshare(CLONE_NEWUSER | CLONE_NEWNS) != 0)
      return std::string("cannot make a private mount namespace: unshare(CLONE_NEWNS): ") +
             std::strerror(first) + "; unshare(CLONE_NEWUSER|CLONE_NEWNS): " + std::strerror(errno);
    std::ofstream("/proc/self/setgroups") << "deny";
    std::ofstream("/proc/self/uid_map") << "0 " << uid << " 1";
    std::ofstream("/proc/self/gid_map") << "0 " << gid << " 1";
  }
  if (::mount(nullptr, "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0)
    return std::string("cannot make the mounts private: ") + std::strerror(errno);
  return "";
}

/// A tmpfs of `bytes` mounted on `where` (created) in a private mount namespace (above), unmounted
/// when this object goes. problem() is "" when it is mounted, else why not.
class PrivateTmpfs {
 public:
  PrivateTmpfs(const std::filesystem::path& where, std::size_t bytes) : where_(where) {
    std::filesystem::create_directories(where);
    problem_ = enter_private_mount_namespace();
    if (!problem_.empty()) return;
    const std::string opts = "size=" + std::to_string(bytes) + ",mode=0755";
    if (::mount("tmpfs", where.c_str(), "tmpfs", 0, opts.c_str()) != 0)
      problem_ = "cannot mount a tmpfs on " + where.string() + ": " + std::strerror(errno);
    else
      mounted_ = true;
  }
  ~PrivateTmpfs() {
    if (mounted_) ::umount2(where_.c_str(), MNT_DETACH);
  }
  PrivateTmpfs(const PrivateTmpfs&) = delete;
  PrivateTmpfs& operator=(const PrivateTmpfs&) = delete;
  const std::string& problem() const { return problem_; }

 private:
  std::filesystem::path where_;
  std::string problem_;
  bool mounted_ = false;
};

/// True when `a` and `b` (both existing) are on different file systems.
inline bool other_file_system(const std::filesystem::path& a, const std::filesystem::path& b) {
  struct stat sa {};
  struct stat sb {};
  return ::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0 && sa.st_dev != sb.st_dev;
}

/// Every file or directory called `name` under `root` (symlinks to directories followed), one per line.
inline std::string find_named(const std::filesystem::path& root, const std::string& name) {
  namespace fs = std::filesystem;
  std::string out;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(root, fs::directory_options::follow_directory_symlink, ec);
       !ec && it != fs::recursive_directory_iterator(); it.increment(ec))
    if (it->path().filename() == name) out += it->path().string() + "\n";
  return out;
}

/// A tiny measured data set (tmlab-measured/1): unconfined compression of a silicone-like cylinder
/// (R 25 mm, H 30 mm, frictionless platens) to 10 % strain in 40 samples, linear with E = 20 kPa and
/// a small deterministic ripple (+-0.5 %) so that the fit has a residual. Writes DIR/NAME.csv + .json.
inline std::filesystem::path write_tiny_data_set(const std::filesystem::path& dir, const std::string& name) {
  std::filesystem::create_directories(dir);
  std::ofstream(dir / (name + ".json"))
      << "{\"format\": \"tmlab-measured/1\", \"name\": \"" << name
      << "\", \"test\": \"unconfined_compression\",\n"
         " \"sample\": {\"shape\": \"cylinder\", \"radius_m\": 0.025, \"height_m\": 0.03,"
         " \"bottom\": \"frictionless\", \"platens\": \"frictionless\"},\n"
         " \"source\": \"written by the test\"}\n";
  std::ofstream csv(dir / (name + ".csv"));
  csv << "time_s,displacement_m,force_N\n";
  const double area = 3.141592653589793 * 0.025 * 0.025;
  for (int i = 0; i < 40; ++i) {
    const double d = 0.003 * i / 39.0;
    const double ripple = 1.0 + 0.005 * ((i * 7) % 5 - 2) / 2.0;
    char line[128];
    std::snprintf(line, sizeof line, "%.6f,%.9g,%.9g\n", 0.45 * i, d, 20000.0 * area * (d / 0.03) * ripple);
    csv << line;
  }
  return dir / (name + ".csv");
}

/// Fixture: a temporary directory per test and `tmlab(args)`, the driver run with an argument vector
/// whose output is kept in dir_/log.txt.
class CliTest : public tmlab::testing::TempDirTest {
 protected:
  Result tmlab(const std::vector<std::string>& args) const { return run_argv(args, dir_ / "log.txt"); }
};

}  // namespace tmlab::cli_test
