#include "core/config/config_reader.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

namespace tmlab {

ConfigReader::ConfigReader(const nlohmann::json& j, std::string where, std::string path)
    : j_(j), where_(std::move(where)), path_(std::move(path)) {
  if (!j_.is_object()) {
    throw Error(where_ + ": " + (path_.empty() ? std::string("the document") : "key '" + path_ + "'") +
                " must be a JSON object (got " + j_.type_name() + ")");
  }
}

nlohmann::json ConfigReader::parse_file(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw Error(file + ": cannot open file");
  std::stringstream ss;
  ss << in.rdbuf();
  try {
    return nlohmann::json::parse(ss.str(), nullptr, true, /*ignore_comments=*/true);
  } catch (const nlohmann::json::parse_error& e) {
    // nlohmann reports "... at line L, column C: reason"; keep it, prefixed by the file.
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
