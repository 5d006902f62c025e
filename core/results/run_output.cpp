// Result-directory protocol and manifest: see run_output.hpp.
#include "core/results/run_output.hpp"

#include "core/base/error.hpp"
#include "core/base/interrupt.hpp"
#include "core/io/atomic_file.hpp"
#include "core/results/result_dir.hpp"
#include "tmlab/build_info.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <ctime>
#include <exception>
#include <fstream>

#include <cerrno>
#include <cstring>
#include <iterator>

#include <fcntl.h>
#include <stdio.h>
#include <sys/file.h>
#include <unistd.h>

#ifndef TMLAB_VERSION_STRING
#define TMLAB_VERSION_STRING "unknown"
#endif

namespace fs = std::filesystem;

namespace tmlab {

// --- manifest helpers ----------------------------------------------------------------------------

std::uint64_t fnv1a64(const void* data, std::size_t size, std::uint64_t seed) {
  const auto* p = static_cast<const unsigned char*>(data);
  std::uint64_t h = seed;
  for (std::size_t i = 0; i < size; ++i) {
    h ^= p[i];
    h *= 0x100000001b3ULL;
  }
  return h;
}

std::uint64_t fnv1a64_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path.string() + ": cannot read file to hash it");
  std::vector<char> buf(1 << 16);
  std::uint64_t h = 0xcbf29ce484222325ULL;
  while (in) {
    in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    h = fnv1a64(buf.data(), static_cast<std::size_t>(in.gcount()), h);
  }
  if (in.bad()) throw Error(path.string() + ": read error while hashing");
  return h;
}

std::string utc_iso8601(std::chrono::system_clock::time_point t) {
  const std::time_t tt = std::chrono::system_clock::to_time_t(t);
  std::tm tm{};
  gmtime_r(&tt, &tm);
  std::array<char, 32> buf{};
  std::strftime(buf.data(), buf.size(), "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf.data();
}

std::string host_name() {
  std::array<char, 256> buf{};
  if (::gethostname(buf.data(), buf.size() - 1) != 0 || buf[0] == '\0') return "unknown";
  return buf.data();
}

std::vector<std::string> command_line(int argc, const char* const* argv) {
  std::vector<std::string> out;
  for (int i = 0; i < argc; ++i) out.emplace_back(argv[i] ? argv[i] : "");
  return out;
}

nlohmann::json make_manifest(const ManifestInput& input) {
  nlohmann::json inputs = nlohmann::json::array();
  for (const fs::path& p : input.input_files) {
    std::error_code ec;
    const auto size = fs::file_size(p, ec);
    if (ec) throw Error(p.string() + ": input file for the manifest: " + ec.message());
    char hex[17];
    std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(fnv1a64_file(p)));
    inputs.push_back(
        {{"path", fs::absolute(p).lexically_normal().string()}, {"size", size}, {"fnv1a64", hex}});
  }
  nlohmann::json m;
  m["tmlab_version"] = TMLAB_VERSION_STRING;
  m["git"] = {{"sha", build_info::git_sha}, {"dirty", build_info::git_dirty}};
  m["build"] = {
      {"type", build_info::build_type}, {"compiler", build_info::compiler}, {"flags", build_info::flags}};
  m["command_line"] = input.command_line;
  m["config"] = input.config;
  m["started_utc"] = utc_iso8601(input.started);
  m["written_utc"] = utc_iso8601(std::chrono::system_clock::now());
  m["hostname"] = host_name();
  m["inputs"] = inputs;
  return m;
}

// --- RunOutput -----------------------------------------------------------------------------------

std::string result_name_problem(const std::string& name) {
  if (name.empty()) return "is empty";
  if (name.size() > 100) return "is longer than 100 characters";
  if (name[0] == '.' || name[0] == '-') return "starts with '" + std::string(1, name[0]) + "'";
  for (const char ch : name) {
    const bool ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') ||
                    ch == '.' || ch == '_' || ch == '-' || ch == '+';
    if (!ok) {
      const auto code = static_cast<unsigned>(static_cast<unsigned char>(ch));
      std::string shown =
          (code >= 0x20 && code < 0x7f) ? "'" + std::string(1, ch) + "'" : "byte " + std::to_string(code);
      return "contains " + shown + " (allowed: letters, digits, '.', '_', '-', '+')";
    }
  }
  return {};
}

namespace {

std::string read_small_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return text.substr(0, 4096);
}

/// "pid 123 on host, started 2026-..." from a RUNNING marker or lock file ("" when unreadable).
std::string describe_writer(const fs::path& marker) {
  try {
    const auto j = nlohmann::json::parse(read_small_file(marker));
    std::string s = "pid " + std::to_string(j.value("pid", -1L)) + " on " + j.value("hostname", "?");
    if (j.contains("started_utc")) s += ", started " + j.value("started_utc", "");
    if (j.contains("command_line")) s += ": " + j.value("command_line", "");
    return s;
  } catch (const std::exception&) {
    return "";
  }
}

/// fsync a directory so the renames inside it are on disk (best effort: some file systems refuse).
void sync_directory(const fs::path& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

/// fsync every regular file and directory of a tree (the staged result before it is swapped in).
void sync_tree(const fs::path& root) {
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(root, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    if (it->is_directory(ec)) {
      sync_directory(it->path());
    } else if (it->is_regular_file(ec)) {
      const int fd = ::open(it->path().c_str(), O_RDONLY | O_CLOEXEC);
      if (fd >= 0) {
        ::fsync(fd);
        ::close(fd);
      }
    }
  }
  sync_directory(root);
}

/// Removes every folder below `root` that holds no file (deepest first); `root` itself stays.
void remove_empty_folders(const fs::path& root) {
  std::vector<fs::path> folders;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(root, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec))
    if (it->is_directory(ec) && !it->is_symlink(ec)) folders.push_back(it->path());
  for (auto f = folders.rbegin(); f != folders.rend(); ++f)
    if (fs::is_empty(*f, ec)) fs::remove(*f, ec);
}

/// Room reserved in the RUNNING marker: on a full disk it becomes FAILED or INTERRUPTED by a rename
/// and is rewritten in place, in blocks it already owns.
constexpr std::size_t kMarkerRoom = 4096;

/// Rewrites the existing file `p` in place with `text` (cut to kMarkerRoom) and truncates it: needs no
/// new disk blocks when the file already held kMarkerRoom bytes. False when that did not work.
bool rewrite_in_place(const fs::path& p, std::string text) {
  if (text.size() > kMarkerRoom) text = text.substr(0, kMarkerRoom - 4) + "...\n";
  const int fd = ::open(p.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) return false;
  bool ok = ::pwrite(fd, text.data(), text.size(), 0) == static_cast<ssize_t>(text.size());
  ok = ok && ::ftruncate(fd, static_cast<off_t>(text.size())) == 0;
  ok = ::fsync(fd) == 0 && ok;
  ok = ::close(fd) == 0 && ok;
  return ok;
}

}  // namespace

RunOutput::RunOutput(fs::path dir, std::ostream* log) : RunOutput(std::move(dir), log, Previous::Discard) {}

RunOutput::RunOutput(fs::path dir, std::ostream* log, Previous previous)
    : dir_(result_dir::resolve(dir)),
      started_(std::chrono::system_clock::now()),
      started_steady_(std::chrono::steady_clock::now()),
      uncaught_at_start_(std::uncaught_exceptions()) {
  // ---- May tmlab write here? Checked before anything is created (and again under the lock). ----
  result_dir::check_may_take(dir_, result_dir::inspect(dir_));
  // ---- One writer per directory: an exclusive, non-blocking flock on the directory itself. ----
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec) throw Error(dir_.string() + ": cannot create result directory: " + ec.message());
  lock_fd_ = ::open(dir_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (lock_fd_ < 0)
    throw Error(dir_.string() + ": cannot open the result directory (" + std::strerror(errno) + ")");
  if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    release_lock();
    if (err != EWOULDBLOCK)
      throw Error(dir_.string() + ": cannot lock the result directory (" + std::strerror(err) + ")");
    const std::string who = describe_writer(dir_ / kRunning);
    throw Error(dir_.string() + ": another tmlab run is writing this result directory" +
                (who.empty() ? std::string() : " (" + who + ")") +
                "; wait for it to finish, or write elsewhere with --results DIR");
  }
  try {
    take(log, previous);
  } catch (...) {
    release_lock();
    throw;
  }
}

void RunOutput::take(std::ostream* log, Previous previous) {
  const bool keep_staging = previous != Previous::Discard;
  // We hold the lock: any RUNNING marker is stale. Look again: the folder may have changed.
  const result_dir::Inventory inv = result_dir::inspect(dir_);
  result_dir::check_may_take(dir_, inv);
  const bool stale = inv.has_marker && fs::exists(dir_ / kRunning);
  if (stale && log) {
    const std::string who = describe_writer(dir_ / kRunning);
    *log << "tmlab: " << dir_.string() << ": a stale RUNNING marker"
         << (who.empty() ? std::string() : " (" + who + ")") << " was left by a run whose process is gone; "
         << (keep_staging ? "resuming from its staged files" : "its partial output is discarded") << "\n";
  }
  // Resumable: a run stopped by a signal (INTERRUPTED), or one whose process died (a stale RUNNING:
  // SIGKILL, a crash), with its staged files; the command then finds its checkpoint there.
  // ResumeStopped: also a run that FAILED.
  const bool stopped = fs::exists(dir_ / kInterrupted) || stale ||
                       (previous == Previous::ResumeStopped && fs::exists(dir_ / kFailed));
  const bool resumable = inv.has_marker && stopped && fs::is_directory(staging_dir());
  if (keep_staging && !resumable) {
    if (inv.has_marker && fs::exists(dir_ / kSummary))
      throw Error(dir_.string() +
                  ": --resume: nothing to resume: it holds a complete result (summary.json); " +
                  "run without --resume to compute it again");
    throw Error(dir_.string() + ": --resume: nothing to resume (no INTERRUPTED" +
                (previous == Previous::ResumeStopped ? " or FAILED" : "") +
                " marker with staged files: the last run " +
                (previous == Previous::ResumeStopped ? "finished" : "finished, failed,") +
                " or never started); run without --resume");
  }
  result_dir::clear_previous(dir_, inv, keep_staging);
  run_id_ = result_dir::write_marker(dir_, "", {});
  std::error_code ec;
  fs::create_directories(staging_dir(), ec);
  if (ec) throw Error(dir_.string() + ": cannot create result directory: " + ec.message());
  const nlohmann::json me = {{"pid", static_cast<long>(::getpid())},
                             {"hostname", host_name()},
                             {"started_utc", utc_iso8601(started_)},
                             {"run_id", run_id_}};
  std::string running = me.dump(2) + "\n";
  if (running.size() < kMarkerRoom) running += std::string(kMarkerRoom - running.size() - 1, ' ') + "\n";
  write_file_atomically(dir_ / kRunning, running);
}

void RunOutput::release_lock() noexcept {
  if (lock_fd_ >= 0) ::close(lock_fd_);  // releases the flock
  lock_fd_ = -1;
}

RunOutput::~RunOutput() {
  if (state_ == State::Running) {
    const bool unwinding = std::uncaught_exceptions() > uncaught_at_start_;
    fail(unwinding ? "run aborted by an exception before finalize()" : "run ended without finalize()");
  }
  release_lock();
}

fs::path RunOutput::file(const std::string& name) const {
  const fs::path rel = fs::path(name).lexically_normal();
  if (name.empty() || rel.is_absolute() || rel.empty() || *rel.begin() == ".." || *rel.begin() == ".") {
    throw Error(dir_.string() + ": result file name '" + name +
                "' must be relative and inside the directory");
  }
  for (const char* own : {kStaging, kRunning, kFailed, kInterrupted, kSummary, result_dir::kMarker})
    if (*rel.begin() == own)
      throw Error(dir_.string() + ": result file name '" + name +
                  "' is a name of the result protocol itself");
  const fs::path p = staging_dir() / rel;
  std::error_code ec;
  fs::create_directories(p.parent_path(), ec);
  if (ec) throw Error(p.parent_path().string() + ": cannot create directory: " + ec.message());
  return p;
}

void RunOutput::write_json(const std::string& name, const nlohmann::json& value) const {
  write_file_atomically(file(name), value.dump(2) + "\n");
}

void RunOutput::finalize(const nlohmann::json& summary) {
  if (state_ != State::Running) {
    throw Error(dir_.string() + ": finalize() on a run that is already " +
                (state_ == State::Finalized ? "finalized" : "failed"));
  }
  if (!summary.is_object()) throw Error(dir_.string() + ": the run summary must be a JSON object");
  try {
    // 1. What the result holds: every staged file, and summary.json. The marker lists them before
    //    any is moved, so that a crash from here on leaves nothing a later run cannot clear. Empty
    //    folders are dropped: the marker lists files, and a result needs no empty folder.
    remove_empty_folders(staging_dir());
    std::vector<std::string> top;
    for (const auto& entry : fs::directory_iterator(staging_dir())) {
      const std::string name = entry.path().filename().string();
      if (fs::exists(fs::symlink_status(dir_ / name)))
        throw Error((dir_ / name).string() + ": exists already beside the staged result: nothing was moved");
      top.push_back(name);
    }
    std::sort(top.begin(), top.end());
    std::vector<std::string> files = result_dir::list_files(staging_dir());
    files.push_back(kSummary);
    std::sort(files.begin(), files.end());
    result_dir::write_marker(dir_, run_id_, files);
    sync_tree(staging_dir());

    // 2. Move them in, each with one rename inside the same folder (so the same file system: a
    //    result folder reached through a link onto another file system finishes like any other).
    std::error_code ec;
    for (const std::string& name : top) {
      fs::rename(staging_dir() / name, dir_ / name, ec);
      if (ec)
        throw Error((dir_ / name).string() + ": cannot move the finished file into place: " + ec.message());
    }
    fs::remove(staging_dir(), ec);
    if (ec) throw Error(staging_dir().string() + ": cannot remove the empty staging area: " + ec.message());

    // 3. summary.json last: from now on the folder is a complete result.
    nlohmann::json s = summary;
    const auto now = std::chrono::system_clock::now();
    s["status"] = "complete";
    s["started_utc"] = utc_iso8601(started_);
    s["finished_utc"] = utc_iso8601(now);
    s["wall_seconds"] =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started_steady_).count();
    s["files"] = top;
    write_file_atomically(dir_ / kSummary, s.dump(2) + "\n");
    fs::remove(dir_ / kRunning, ec);
    sync_directory(dir_);
  } catch (const std::exception& e) {
    fail(std::string("finalize() failed: ") + e.what());
    throw;
  }
  state_ = State::Finalized;
}

void RunOutput::mark_stopped(State state, const char* marker, const std::string& message) noexcept {
  if (state_ != State::Running) return;
  state_ = state;
  try {
    std::error_code ec;
    fs::remove(dir_ / kSummary, ec);
    const std::string stamp = state == State::Interrupted ? "interrupted_utc: " : "failed_utc: ";
    const std::string text = stamp + utc_iso8601(std::chrono::system_clock::now()) + "\n" +
                             (state == State::Interrupted ? "reason: " : "error: ") + message + "\n";
    // The RUNNING marker becomes this one by a rename and is rewritten in the room it reserved, so
    // that a full disk still ends in FAILED with the reason, never in a stale RUNNING.
    bool done = false;
    if (fs::exists(dir_ / kRunning)) {
      fs::rename(dir_ / kRunning, dir_ / marker, ec);
      done = !ec && rewrite_in_place(dir_ / marker, text);
    }
    if (!done) {
      write_file_atomically(dir_ / marker, text);
      fs::remove(dir_ / kRunning, ec);
    }
  } catch (...) {
    // Nothing more can be done: the missing summary.json still marks the run incomplete.
  }
}

void RunOutput::fail(const std::string& message) noexcept { mark_stopped(State::Failed, kFailed, message); }

void RunOutput::interrupt(const std::string& message) noexcept {
  mark_stopped(State::Interrupted, kInterrupted, message);
}

void RunOutput::abandon(const std::exception& e) noexcept {
  if (dynamic_cast<const Interrupted*>(&e) != nullptr)
    interrupt(e.what());
  else
    fail(e.what());
}

}  // namespace tmlab
