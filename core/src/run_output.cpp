// Result-directory protocol and manifest: see run_output.hpp.
#include "tmlab/core/run_output.hpp"

#include "tmlab/build_info.hpp"
#include "tmlab/core/atomic_file.hpp"
#include "tmlab/core/error.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <ctime>
#include <exception>
#include <fstream>

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

namespace {

bool looks_like_result_dir(const fs::path& dir) {
  for (const char* marker :
       {RunOutput::kStaging, RunOutput::kRunning, RunOutput::kFailed, RunOutput::kSummary, "manifest.json"}) {
    if (fs::exists(dir / marker)) return true;
  }
  return false;
}

}  // namespace

RunOutput::RunOutput(fs::path dir)
    : dir_(std::move(dir)),
      started_(std::chrono::system_clock::now()),
      started_steady_(std::chrono::steady_clock::now()),
      uncaught_at_start_(std::uncaught_exceptions()) {
  std::error_code ec;
  if (fs::exists(dir_, ec)) {
    if (!fs::is_directory(dir_)) throw Error(dir_.string() + ": result path exists and is not a directory");
    if (!fs::is_empty(dir_) && !looks_like_result_dir(dir_)) {
      throw Error(dir_.string() + ": refusing to reuse a non-empty directory that is not a tmlab result " +
                  "directory (no summary.json, manifest.json, RUNNING, FAILED or .incomplete)");
    }
    // The previous run no longer describes this directory: drop its completeness mark first.
    fs::remove(dir_ / kSummary, ec);
    if (ec) throw Error(dir_.string() + ": cannot remove old " + kSummary + ": " + ec.message());
    for (const auto& entry : fs::directory_iterator(dir_)) {
      fs::remove_all(entry.path(), ec);
      if (ec) throw Error(entry.path().string() + ": cannot remove previous result: " + ec.message());
    }
  }
  fs::create_directories(staging_dir(), ec);
  if (ec) throw Error(dir_.string() + ": cannot create result directory: " + ec.message());
  const nlohmann::json running = {{"pid", static_cast<long>(::getpid())},
                                  {"hostname", host_name()},
                                  {"started_utc", utc_iso8601(started_)}};
  write_file_atomically(dir_ / kRunning, running.dump(2) + "\n");
}

RunOutput::~RunOutput() {
  if (state_ != State::Running) return;
  const bool unwinding = std::uncaught_exceptions() > uncaught_at_start_;
  fail(unwinding ? "run aborted by an exception before finalize()" : "run ended without finalize()");
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
    std::vector<std::string> files;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(staging_dir())) {
      const fs::path target = dir_ / entry.path().filename();
      fs::remove_all(target, ec);  // a stale entry of the same name (never expected after the ctor)
      fs::rename(entry.path(), target, ec);
      if (ec) throw Error(target.string() + ": cannot move result into place: " + ec.message());
      files.push_back(entry.path().filename().string());
    }
    std::sort(files.begin(), files.end());
    fs::remove_all(staging_dir(), ec);
    if (ec) throw Error(staging_dir().string() + ": cannot remove staging directory: " + ec.message());
    fs::remove(dir_ / kRunning, ec);

    nlohmann::json s = summary;
    const auto now = std::chrono::system_clock::now();
    s["status"] = "complete";
    s["started_utc"] = utc_iso8601(started_);
    s["finished_utc"] = utc_iso8601(now);
    s["wall_seconds"] =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started_steady_).count();
    s["files"] = files;
    write_file_atomically(dir_ / kSummary, s.dump(2) + "\n");  // last: marks the run complete
  } catch (const std::exception& e) {
    fail(std::string("finalize() failed: ") + e.what());
    throw;
  }
  state_ = State::Finalized;
}

void RunOutput::fail(const std::string& message) noexcept {
  if (state_ != State::Running) return;
  state_ = State::Failed;
  try {
    std::error_code ec;
    fs::remove(dir_ / kSummary, ec);
    const std::string text =
        "failed_utc: " + utc_iso8601(std::chrono::system_clock::now()) + "\n" + "error: " + message + "\n";
    write_file_atomically(dir_ / kFailed, text);
    fs::remove(dir_ / kRunning, ec);
  } catch (...) {
    // Nothing more can be done: the missing summary.json still marks the run incomplete.
  }
}

}  // namespace tmlab
