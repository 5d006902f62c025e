#include "core/config/config_reader.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <vector>

namespace tmlab {

ConfigReader::ConfigReader(const nlohmann::json& j, std::string where, std::string path)
    : j_(j), where_(std::move(where)), path_(std::move(path)) {
  if (!j_.is_object()) {
    throw Error(where_ + ": " + (path_.empty() ? std::string("the document") : "key '" + path_ + "'") +
                " must be a JSON object (got " + j_.type_name() + ")");
  }
}

namespace {
/// Tracks the keys of each open object during parsing to refuse duplicates, naming the key path.
class DuplicateKeyGuard {
 public:
  explicit DuplicateKeyGuard(std::string file) : file_(std::move(file)) {}
  /// Deeper nesting than any case or parameter file needs is refused as it is met, before the parser
  /// builds (and the guard copies key paths for) a pathologically deep document.
  static constexpr int kMaxDepth = 64;
  bool operator()(int depth, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using E = nlohmann::json::parse_event_t;
    if (depth > kMaxDepth)
      throw Error(file_ + ": nested deeper than " + std::to_string(kMaxDepth) + " levels (key '" +
                  current_key().substr(0, 200) + "...')");
    switch (event) {
      case E::object_start:
        frames_.push_back({true, {}, current_key()});
        break;
      case E::array_start:
        frames_.push_back({false, {}, current_key()});
        break;
      case E::object_end:
      case E::array_end:
        if (!frames_.empty()) frames_.pop_back();
        break;
      case E::key: {
        const std::string key = parsed.get<std::string>();
        Frame& f = frames_.back();
        if (!f.keys.insert(key).second)
          throw Error(
              file_ + ": key '" + join(f.path, key) +
              "' is given twice in the same object (JSON keeps only one of the values; remove the other)");
        last_key_ = key;
        break;
      }
      case E::value:
        break;
    }
    return true;
  }

 private:
  struct Frame {
    bool object;
    std::set<std::string> keys;
    std::string path;
  };
  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }
  std::string current_key() const {
    if (frames_.empty()) return "";
    const Frame& f = frames_.back();
    return f.object ? join(f.path, last_key_) : f.path + "[]";
  }
  std::string file_;
  std::vector<Frame> frames_;
  std::string last_key_;
};
}  // namespace

nlohmann::json ConfigReader::parse_file(const std::string& file) {
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec)) throw Error(file + ": is a directory, not a JSON file");
  if (std::filesystem::exists(file, ec) && !std::filesystem::is_regular_file(file, ec))
    throw Error(file + ": is not a regular file (a FIFO, socket or device), not a JSON file");
  std::ifstream in(file);
  if (!in) throw Error(file + ": cannot open file");
  std::stringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw Error(file + ": read error");
  DuplicateKeyGuard guard(file);
  try {
    return nlohmann::json::parse(ss.str(), std::ref(guard), true, /*ignore_comments=*/true);
  } catch (const nlohmann::json::parse_error& e) {
    // nlohmann reports "... at line L, column C: reason"; keep it, prefixed by the file.
    throw Error(file + ": invalid JSON: " + e.what());
  } catch (const nlohmann::json::out_of_range& e) {
    // "number overflow parsing '1e999'": a number no double can hold.
    throw Error(file + ": invalid number: " + e.what() + " (numbers must fit a double, |x| < 1.8e308)");
  } catch (const nlohmann::json::exception& e) {
    throw Error(file + ": invalid JSON: " + e.what());
  }
}

bool ConfigReader::has(const std::string& key) const { return j_.contains(key); }

const nlohmann::json& ConfigReader::raw(const std::string& key) {
  if (!has(key)) throw error(key, "is required");
  used_.insert(key);
  return j_.at(key);
}

ConfigReader ConfigReader::child(const std::string& key) {
  const nlohmann::json& c = raw(key);
  return ConfigReader(c, where_, key_path(key));
}

double ConfigReader::positive(const std::string& key, bool allow_zero) {
  const double v = require<double>(key);
  if (!std::isfinite(v) || v < 0.0 || (!allow_zero && v == 0.0))
    throw error(key,
                std::string("must be ") + (allow_zero ? ">= 0" : "> 0") + " (got " + j_.at(key).dump() + ")");
  return v;
}

double ConfigReader::positive(const std::string& key, double fallback, bool allow_zero) {
  return has(key) ? positive(key, allow_zero) : fallback;
}

Eigen::Vector3d ConfigReader::vec3(const std::string& key) {
  const auto v = require<std::vector<double>>(key);
  if (v.size() != 3) throw error(key, "must be a list of 3 numbers");
  for (double x : v)
    if (!std::isfinite(x)) throw error(key, "must be finite");
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

void ConfigReader::finish() const {
  std::string unknown;
  for (auto it = j_.begin(); it != j_.end(); ++it) {
    if (used_.count(it.key()) == 0) unknown += (unknown.empty() ? "'" : ", '") + key_path(it.key()) + "'";
  }
  if (!unknown.empty()) throw Error(where_ + ": unknown key " + unknown + " (misspelt, or not valid here)");
}

std::string ConfigReader::key_path(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

Error ConfigReader::error(const std::string& key, const std::string& reason) const {
  return Error(where_ + ": key '" + key_path(key) + "' " + reason);
}

}  // namespace tmlab
