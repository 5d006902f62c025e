// Strict reading of JSON configuration (case files, parameter files).
//
// Every value is read through a ConfigReader, which remembers which keys were used; finish() then
// rejects any key that was not, so a misspelt key is an error rather than a silently ignored
// setting. Errors name the file and the full key path: "cases/x.json: key 'solver.dt': must be > 0".
#pragma once

#include "core/base/error.hpp"

#include <nlohmann/json.hpp>

#include <set>
#include <string>

namespace tmlab {

class ConfigReader {
 public:
  /// `where` is the file (or other origin) used in messages; `path` the key path of `j` ("" at root).
  ConfigReader(const nlohmann::json& j, std::string where, std::string path = "");

  /// Parses a JSON file; syntax errors name the file, line and column.
  static nlohmann::json parse_file(const std::string& file);

  bool has(const std::string& key) const;
  /// The raw value (marks the key used). Throws when missing.
  const nlohmann::json& raw(const std::string& key);
  /// Reader for a nested object (marks the key used). Throws when missing or not an object.
  ConfigReader child(const std::string& key);

  template <class T>
  T require(const std::string& key) {
    if (!has(key)) throw error(key, "is required");
    return convert<T>(key);
  }
  template <class T>
  T get(const std::string& key, const T& fallback) {
    if (!has(key)) return fallback;
    return convert<T>(key);
  }
  /// require<double> with a check that the value is > 0 (or >= 0 when allow_zero).
  double positive(const std::string& key, bool allow_zero = false);
  double positive(const std::string& key, double fallback, bool allow_zero = false);

  /// Throws naming every key present in the object that was never read.
  void finish() const;

  /// An error about `key` of this object, with file and full key path.
  Error error(const std::string& key, const std::string& reason) const;
  /// Full dotted path of a key of this object.
  std::string key_path(const std::string& key) const;
  const std::string& where() const { return where_; }
  const nlohmann::json& json() const { return j_; }

 private:
  template <class T>
  T convert(const std::string& key) {
    used_.insert(key);
    try {
      return j_.at(key).get<T>();
    } catch (const nlohmann::json::exception&) {
      throw error(key, "has the wrong type (got " + std::string(j_.at(key).type_name()) + ": " +
                           j_.at(key).dump() + ")");
    }
  }

  const nlohmann::json& j_;
  std::string where_;
  std::string path_;
  std::set<std::string> used_;
};

}  // namespace tmlab
