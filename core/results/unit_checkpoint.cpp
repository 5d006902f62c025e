// The checkpoint file of a command that finishes in units: see unit_checkpoint.hpp.
#include "core/results/unit_checkpoint.hpp"

#include "core/base/error.hpp"
#include "core/results/run_output.hpp"

#include <cstdio>
#include <utility>

namespace tmlab {

namespace fs = std::filesystem;

void refuse_resume_of_complete(const fs::path& dir, const std::string& what) {
  std::error_code ec;
  if (fs::exists(dir / "summary.json", ec))
    throw Error("nothing to resume: " + dir.string() + " holds a complete " + what +
                " (summary.json); run without --resume to redo it");
}

std::string file_hash(const fs::path& path) {
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(fnv1a64_file(path)));
  return hex;
}

std::string unit_text(const nlohmann::json& j) {
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

nlohmann::json read_unit_text(const CheckpointData& d, const std::string& name) {
  try {
    return nlohmann::json::parse(d.text(name));
  } catch (const nlohmann::json::exception& e) {
    throw unreadable_entry(d, name, e.what());
  }
}

Error unreadable_entry(const CheckpointData& d, const std::string& name, const std::string& why) {
  return Error(d.source() + ": unreadable entry '" + name + "' (" + why + "); run without --resume");
}

void require_consistent(bool ok, const CheckpointData& d, const std::string& name) {
  if (!ok) throw Error(d.source() + ": inconsistent entry '" + name + "'; run without --resume");
}

UnitCheckpoint::UnitCheckpoint(fs::path path, std::string kind, nlohmann::json fingerprint,
                               CheckpointSchedule schedule, std::function<CheckpointData()> snapshot)
    : path_(std::move(path)),
      kind_(std::move(kind)),
      fingerprint_(std::move(fingerprint)),
      clock_(schedule),
      snapshot_(std::move(snapshot)) {}

CheckpointData UnitCheckpoint::read() const { return read_checkpoint(path_, kind_, fingerprint_); }

void UnitCheckpoint::unit_finished(const std::string& what) {
  ++units_;
  pending_ = true;
  latest_ = what;
  if (pending_interrupt() != 0 || clock_.due(units_)) write();
}

void UnitCheckpoint::write() {
  write_checkpoint(path_, kind_, fingerprint_, snapshot_());
  clock_.mark();
  pending_ = false;
  written_ = latest_;
}

Interrupted UnitCheckpoint::stopped(const Interrupted& e) {
  std::string failed;
  if (pending_) try {
      write();
    } catch (const Error& w) {
      failed = " (the checkpoint of the latest units could not be written: " + std::string(w.what()) + ")";
    }
  if (written_.empty())
    return Interrupted(e.signal(), std::string(e.what()) +
                                       "; no checkpoint was written (nothing had finished)" + failed +
                                       ": run again without --resume");
  return Interrupted(e.signal(), std::string(e.what()) + "; checkpoint after " + written_ + " in " +
                                     path_.string() + failed +
                                     ": continue with the same command and --resume");
}

}  // namespace tmlab
