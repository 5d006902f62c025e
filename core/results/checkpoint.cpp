// Checkpoint files of long commands: see checkpoint.hpp.
#include "core/results/checkpoint.hpp"

#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/base/interrupt.hpp"
#include "core/base/number.hpp"
#include "core/io/hdf5_file.hpp"
#include "core/results/run_output.hpp"

#include <cmath>
#include <cstring>
#include <sstream>

#include <fcntl.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace tmlab {

namespace {

constexpr const char* kFormat = "tmlab-checkpoint/1";

void check_name(const std::string& name) {
  bool ok = !name.empty() && name.size() <= 64;
  for (const char c : name)
    ok = ok && ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
                c == '.' || c == '-');
  if (!ok)
    throw Error("checkpoint entry name '" + name +
                "' must be 1-64 characters of letters, digits, '_', '.' and '-'");
}

/// Text as int64 words (8 bytes each, the last one zero-padded): HDF5 stores them exactly.
std::vector<std::int64_t> pack(const std::string& s) {
  std::vector<std::int64_t> words((s.size() + 7) / 8, 0);
  if (!s.empty()) std::memcpy(words.data(), s.data(), s.size());
  return words;
}

std::string unpack(const std::vector<std::int64_t>& words, std::size_t bytes) {
  if (bytes > 8 * words.size()) throw Error("text entry shorter than its recorded length");
  std::string s(bytes, '\0');
  if (bytes > 0) std::memcpy(s.data(), words.data(), bytes);
  return s;
}

void write_text(H5File& f, const std::string& dataset, const std::string& text) {
  const std::vector<std::int64_t> words = pack(text);
  f.write(dataset, words, {words.size()});
  f.set_attribute(dataset, "bytes", static_cast<std::int64_t>(text.size()));
}

std::string read_text(const H5File& f, const std::string& dataset) {
  return unpack(f.read_int64(dataset), static_cast<std::size_t>(f.int_attribute(dataset, "bytes")));
}

void fsync_path(const fs::path& p, bool directory) {
  const int fd = ::open(p.c_str(), (directory ? O_RDONLY | O_DIRECTORY : O_RDONLY) | O_CLOEXEC);
  if (fd < 0) return;  // best effort for directories; a file we just wrote always opens
  ::fsync(fd);
  ::close(fd);
}

/// "a.b[2].c" from the JSON pointer "/a/b/2/c".
std::string dotted(const std::string& pointer) {
  std::string out;
  std::stringstream in(pointer);
  std::string part;
  std::getline(in, part, '/');  // the empty piece before the leading '/'
  while (std::getline(in, part, '/')) {
    const bool index = !part.empty() && part.find_first_not_of("0123456789") == std::string::npos;
    if (index)
      out += "[" + part + "]";
    else
      out += (out.empty() ? "" : ".") + part;
  }
  return out.empty() ? "(the whole configuration)" : out;
}

std::string shown(const nlohmann::json& j) {
  std::string s = j.dump();
  if (s.size() > 80) s = s.substr(0, 77) + "...";
  return s;
}

}  // namespace

// --- CheckpointData --------------------------------------------------------------------------------

void CheckpointData::put(const std::string& name, std::vector<double> values) {
  check_name(name);
  doubles_[name] = std::move(values);
}

void CheckpointData::put(const std::string& name, std::vector<std::int64_t> values) {
  check_name(name);
  ints_[name] = std::move(values);
}

void CheckpointData::put_text(const std::string& name, const std::string& text) {
  check_name(name);
  texts_[name] = text;
}

bool CheckpointData::has(const std::string& name) const {
  return doubles_.count(name) || ints_.count(name) || texts_.count(name);
}

void CheckpointData::missing(const std::string& name, const char* what) const {
  throw Error((source_.empty() ? std::string("checkpoint") : source_) + ": no " + what + " entry '" + name +
              "' (a checkpoint of another tmlab version?); run without --resume");
}

const std::vector<double>& CheckpointData::doubles(const std::string& name) const {
  const auto it = doubles_.find(name);
  if (it == doubles_.end()) missing(name, "float64");
  return it->second;
}

const std::vector<std::int64_t>& CheckpointData::ints(const std::string& name) const {
  const auto it = ints_.find(name);
  if (it == ints_.end()) missing(name, "int64");
  return it->second;
}

double CheckpointData::scalar(const std::string& name) const {
  const auto& v = doubles(name);
  if (v.size() != 1) missing(name, "scalar float64");
  return v[0];
}

std::int64_t CheckpointData::integer(const std::string& name) const {
  const auto& v = ints(name);
  if (v.size() != 1) missing(name, "scalar int64");
  return v[0];
}

const std::string& CheckpointData::text(const std::string& name) const {
  const auto it = texts_.find(name);
  if (it == texts_.end()) missing(name, "text");
  return it->second;
}

// --- files -----------------------------------------------------------------------------------------

void write_checkpoint(const fs::path& path, const std::string& kind, const nlohmann::json& fingerprint,
                      const CheckpointData& data) {
  fs::path tmp = path;
  tmp += ".tmp";
  try {
    H5File f = H5File::create(tmp.string());
    f.set_attribute("/", "format", kFormat);
    f.set_attribute("/", "kind", kind);
    f.set_attribute("/", "written_utc", utc_iso8601(std::chrono::system_clock::now()));
    write_text(f, "/fingerprint", fingerprint.dump());
    f.create_group("/double");
    f.create_group("/int");
    f.create_group("/text");
    for (const auto& [name, v] : data.all_doubles()) f.write("/double/" + name, v, {v.size()});
    for (const auto& [name, v] : data.all_ints()) f.write("/int/" + name, v, {v.size()});
    for (const auto& [name, s] : data.all_texts()) write_text(f, "/text/" + name, s);
    f.close();
    fsync_path(tmp, false);  // the data is on disk before the name points at it
  } catch (const Error& e) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw Error(path.string() + ": cannot write the checkpoint: " + e.what());
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw Error(path.string() + ": cannot move the checkpoint into place: " + ec.message());
  }
  fsync_path(path.has_parent_path() ? path.parent_path() : fs::path("."), true);
  note_progress_point();  // a unit of resumable progress (the deterministic stop point of tests)
}

CheckpointData read_checkpoint(const fs::path& path, const std::string& kind,
                               const nlohmann::json& fingerprint) {
  if (!fs::exists(path))
    throw Error(path.string() + ": --resume: no checkpoint (the interrupted run stopped before writing " +
                "one); run without --resume");
  CheckpointData data;
  data.set_source(path.string());
  nlohmann::json stored;
  try {
    const H5File f = H5File::open_read(path.string());
    if (!f.has_attribute("/", "format") || f.string_attribute("/", "format") != kFormat)
      throw Error("not a " + std::string(kFormat) + " file");
    const std::string k = f.string_attribute("/", "kind");
    if (k != kind) throw Error("a checkpoint of '" + k + "', not of '" + kind + "'; run without --resume");
    stored = nlohmann::json::parse(read_text(f, "/fingerprint"));
    for (const auto& name : f.list("/double")) data.put(name, f.read_double("/double/" + name));
    for (const auto& name : f.list("/int")) data.put(name, f.read_int64("/int/" + name));
    for (const auto& name : f.list("/text")) data.put_text(name, read_text(f, "/text/" + name));
  } catch (const nlohmann::json::exception& e) {
    throw Error(path.string() + ": unreadable checkpoint fingerprint (" + e.what() +
                "); run without --resume");
  } catch (const Error& e) {
    const std::string what = e.what();
    if (what.rfind(path.string(), 0) == 0) throw;
    throw Error(path.string() + ": unreadable checkpoint: " + what);
  }
  const std::string diff = fingerprint_mismatch(stored, fingerprint);
  if (!diff.empty())
    throw Error(path.string() + ": --resume: the checkpoint is of another configuration (" + diff +
                "); resume with the same case and options, or run without --resume");
  return data;
}

void remove_checkpoint(const fs::path& path) noexcept {
  std::error_code ignored;
  fs::remove(path, ignored);
  fs::path tmp = path;
  tmp += ".tmp";
  fs::remove(tmp, ignored);
}

std::string fingerprint_mismatch(const nlohmann::json& stored, const nlohmann::json& current) {
  if (stored == current) return "";
  const nlohmann::json patch = nlohmann::json::diff(stored, current);
  std::string out;
  int n = 0;
  for (const auto& op : patch) {
    if (n == 5) {
      out += "; ...";
      break;
    }
    const std::string ptr = op.at("path").get<std::string>();
    const nlohmann::json::json_pointer jp(ptr);
    const std::string was = stored.contains(jp) ? shown(stored.at(jp)) : "nothing";
    const std::string now = current.contains(jp) ? shown(current.at(jp)) : "nothing";
    out += (n ? "; " : "") + dotted(ptr) + ": the checkpoint has " + was + ", this run " + now;
    ++n;
  }
  return out;
}

// --- schedule --------------------------------------------------------------------------------------

CheckpointSchedule CheckpointSchedule::parse(const std::string& text) {
  const std::string bad = "--checkpoint-every '" + printable(text, 60) +
                          "': give a number of steps (100), a wall time (30s, 5min) or 'off'";
  if (text == "off") return {0, 0.0};
  // The number under tmlab's one grammar (core/base/number.hpp), then the unit.
  std::string unit;
  if (text.size() > 3 && text.compare(text.size() - 3, 3, "min") == 0)
    unit = "min";
  else if (text.size() > 1 && text.back() == 's')
    unit = "s";
  const std::string number = text.substr(0, text.size() - unit.size());
  std::string why;
  if (unit.empty()) {
    std::int64_t n = 0;
    if (!parse_whole(number, 1, 1000000000000LL, n, why)) throw Error(bad + " (" + why + ")");
    return {static_cast<long>(n), 0.0};
  }
  double v = 0.0;
  if (!parse_decimal(number, v, why)) throw Error(bad + " (" + why + ")");
  if (!(v > 0.0)) throw Error(bad + " (the time must be positive)");
  return {0, unit == "min" ? 60.0 * v : v};
}

std::string CheckpointSchedule::describe() const {
  std::string s;
  if (every_steps > 0) s = "every " + std::to_string(every_steps) + " steps";
  if (every_seconds > 0.0) {
    std::ostringstream o;
    o << every_seconds;
    s += (s.empty() ? "every " : " and every ") + o.str() + " s";
  }
  return s.empty() ? "only on a stop request" : s;
}

CheckpointClock::CheckpointClock(CheckpointSchedule schedule)
    : schedule_(schedule), last_(std::chrono::steady_clock::now()) {}

bool CheckpointClock::due(long step) const {
  if (schedule_.every_steps > 0 && step % schedule_.every_steps == 0) return true;
  if (schedule_.every_seconds > 0.0) {
    const double since = std::chrono::duration<double>(std::chrono::steady_clock::now() - last_).count();
    if (since >= schedule_.every_seconds) return true;
  }
  return false;
}

void CheckpointClock::mark() { last_ = std::chrono::steady_clock::now(); }

}  // namespace tmlab
