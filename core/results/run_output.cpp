// Result-directory protocol and manifest: see run_output.hpp.
#include "core/results/run_output.hpp"

#include "core/base/error.hpp"
#include "core/base/interrupt.hpp"
#include "core/io/atomic_file.hpp"
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

bool looks_like_result_dir(const fs::path& dir) {
  for (const char* marker : {RunOutput::kStaging, RunOutput::kRunning, RunOutput::kFailed,
                             RunOutput::kInterrupted, RunOutput::kSummary, "manifest.json"}) {
    if (fs::exists(dir / marker)) return true;
  }
  return false;
}

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

}  // namespace

RunOutput::RunOutput(fs::path dir, std::ostream* log) : RunOutput(std::move(dir), log, Previous::Discard) {}

RunOutput::RunOutput(fs::path dir, std::ostream* log, Previous previous)
    : dir_(std::move(dir)),
      started_(std::chrono::system_clock::now()),
      started_steady_(std::chrono::steady_clock::now()),
      uncaught_at_start_(std::uncaught_exceptions()) {
  std::error_code ec;
  if (dir_.filename().empty()) dir_ = dir_.parent_path();  // "results/x/" -> "results/x"
  if (fs::exists(dir_, ec)) {
    if (!fs::is_directory(dir_)) throw Error(dir_.string() + ": result path exists and is not a directory");
    if (!fs::is_empty(dir_) && !looks_like_result_dir(dir_)) {
      throw Error(dir_.string() + ": refusing to reuse a non-empty directory that is not a tmlab result " +
                  "directory (no summary.json, manifest.json, RUNNING, FAILED or .incomplete)");
    }
  }
  // ---- One writer per directory: an exclusive, non-blocking flock on the directory itself. ----
  const fs::path parent = dir_.has_parent_path() ? dir_.parent_path() : fs::path(".");
  fs::create_directories(dir_, ec);
  if (ec) throw Error(dir_.string() + ": cannot create result directory: " + ec.message());
  lock_fd_ = ::open(dir_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (lock_fd_ < 0)
    throw Error(dir_.string() + ": cannot open the result directory (" + std::strerror(errno) + ")");
  if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    ::close(lock_fd_);
    lock_fd_ = -1;
    if (err != EWOULDBLOCK)
      throw Error(dir_.string() + ": cannot lock the result directory (" + std::strerror(err) + ")");
    const std::string who = describe_writer(dir_ / kRunning);
    throw Error(dir_.string() + ": another tmlab run is writing this result directory" +
                (who.empty() ? std::string() : " (" + who + ")") +
                "; wait for it to finish, or write elsewhere with --results DIR");
  }
  const nlohmann::json me = {{"pid", static_cast<long>(::getpid())},
                             {"hostname", host_name()},
                             {"started_utc", utc_iso8601(started_)}};

  // ---- Clear the previous result (we hold the lock: any RUNNING marker is stale). ----
  {
    const bool keep_staging = previous == Previous::ResumeInterrupted;
    const bool stale = fs::exists(dir_ / kRunning);
    if (stale) {
      if (log) {
        const std::string who = describe_writer(dir_ / kRunning);
        *log << "tmlab: " << dir_.string() << ": a stale RUNNING marker"
             << (who.empty() ? std::string() : " (" + who + ")")
             << " was left by a run whose process is gone; "
             << (keep_staging ? "resuming from its staged files" : "its partial output is discarded") << "\n";
      }
    }
    // Resumable: a run stopped by a signal (INTERRUPTED), or one whose process died (a stale
    // RUNNING: SIGKILL, a crash), with its staged files; the command then finds its checkpoint there.
    if (keep_staging && (!(fs::exists(dir_ / kInterrupted) || stale) || !fs::is_directory(staging_dir()))) {
      ::close(lock_fd_);
      lock_fd_ = -1;
      throw Error(dir_.string() +
                  ": --resume: nothing to resume (no INTERRUPTED marker with staged files: the " +
                  "last run finished, failed, or never started); run without --resume");
    }
    // The previous run no longer describes this directory: drop its completeness mark first.
    fs::remove(dir_ / kSummary, ec);
    if (ec) throw Error(dir_.string() + ": cannot remove old " + kSummary + ": " + ec.message());
    for (const auto& entry : fs::directory_iterator(dir_)) {
      if (keep_staging && entry.path().filename() == kStaging) continue;
      fs::remove_all(entry.path(), ec);
      if (ec) throw Error(entry.path().string() + ": cannot remove previous result: " + ec.message());
    }
  }
  fs::remove_all(parent / ("." + dir_.filename().string() + ".final"), ec);  // a crash mid-finalize
  fs::create_directories(staging_dir(), ec);
  if (ec) throw Error(dir_.string() + ": cannot create result directory: " + ec.message());
  write_file_atomically(dir_ / kRunning, me.dump(2) + "\n");
}

RunOutput::~RunOutput() {
  if (state_ == State::Running) {
    const bool unwinding = std::uncaught_exceptions() > uncaught_at_start_;
    fail(unwinding ? "run aborted by an exception before finalize()" : "run ended without finalize()");
  }
  if (lock_fd_ >= 0) ::close(lock_fd_);  // releases the flock
}

fs::path RunOutput::file(const std::string& name) const {
  const fs::path rel = fs::path(name).lexically_normal();
  if (name.empty() || rel.is_absolute() || rel.empty() || *rel.begin() == "..") {
    throw Error(dir_.string() + ": result file name '" + name +
                "' must be relative and inside the directory");
  }
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
    // 1. The complete tree is built beside the directory: <parent>/.<name>.final = staged files +
    //    summary.json (written last, with the file list), then synced.
    const fs::path parent = dir_.has_parent_path() ? dir_.parent_path() : fs::path(".");
    const fs::path final_tree = parent / ("." + dir_.filename().string() + ".final");
    std::error_code ec;
    fs::remove_all(final_tree, ec);
    fs::rename(staging_dir(), final_tree, ec);
    if (ec) throw Error(final_tree.string() + ": cannot stage the finished result: " + ec.message());
    std::vector<std::string> files;
    for (const auto& entry : fs::directory_iterator(final_tree))
      files.push_back(entry.path().filename().string());
    std::sort(files.begin(), files.end());

    nlohmann::json s = summary;
    const auto now = std::chrono::system_clock::now();
    s["status"] = "complete";
    s["started_utc"] = utc_iso8601(started_);
    s["finished_utc"] = utc_iso8601(now);
    s["wall_seconds"] =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started_steady_).count();
    s["files"] = files;
    write_file_atomically(final_tree / kSummary, s.dump(2) + "\n");
    sync_tree(final_tree);

    // 2. One rename makes it the result: exchange it with <dir> (which holds only RUNNING now),
    //    then remove what was swapped out.
    if (::renameat2(AT_FDCWD, final_tree.c_str(), AT_FDCWD, dir_.c_str(), RENAME_EXCHANGE) != 0) {
      // A file system without RENAME_EXCHANGE: move the old directory aside, then rename.
      const fs::path aside = parent / ("." + dir_.filename().string() + ".old");
      fs::remove_all(aside, ec);
      fs::rename(dir_, aside, ec);
      if (ec) throw Error(dir_.string() + ": cannot move the old directory aside: " + ec.message());
      fs::rename(final_tree, dir_, ec);
      if (ec) throw Error(dir_.string() + ": cannot move the result into place: " + ec.message());
      fs::remove_all(aside, ec);
    } else {
      fs::remove_all(final_tree, ec);
    }
    sync_directory(parent);
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
    fs::create_directories(dir_, ec);
    // A crash between the two renames of finalize() could leave the staged tree beside the
    // directory; bring it back where the user looks for it.
    const fs::path parent = dir_.has_parent_path() ? dir_.parent_path() : fs::path(".");
    const fs::path final_tree = parent / ("." + dir_.filename().string() + ".final");
    if (!fs::exists(staging_dir()) && fs::exists(final_tree)) fs::rename(final_tree, staging_dir(), ec);
    const std::string stamp = state == State::Interrupted ? "interrupted_utc: " : "failed_utc: ";
    const std::string text = stamp + utc_iso8601(std::chrono::system_clock::now()) + "\n" +
                             (state == State::Interrupted ? "reason: " : "error: ") + message + "\n";
    write_file_atomically(dir_ / marker, text);
    fs::remove(dir_ / kRunning, ec);
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
