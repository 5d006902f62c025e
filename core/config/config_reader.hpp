// Strict reading of JSON configuration (case files, parameter files).
//
// Every value is read through a ConfigReader, which remembers which keys were used; finish() then
// rejects any key that was not, so a misspelt key is an error rather than a silently ignored
// setting. Errors name the file and the full key path: "cases/x.json: key 'solver.dt': must be > 0".
#pragma once

#include "core/base/error.hpp"

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <string>
#include <type_traits>

namespace tmlab {

class ConfigReader {
 public:
  /// `where` is the file (or other origin) used in messages; `path` the key path of `j` ("" at root).
  ConfigReader(const nlohmann::json& j, std::string where, std::string path = "");

  /// Parses a JSON file; syntax errors name the file, line and column. Also refused, naming the
  /// file: a directory, a number that does not fit a double (1e999), a key given twice in one
  /// object (JSON parsers keep one silently).
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
  /// A required list of 3 finite numbers (a point, direction, force, ...).
  Eigen::Vector3d vec3(const std::string& key);

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
    if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
      // nlohmann converts 2.5 to 2 silently: integers must be written as whole numbers in range.
      const nlohmann::json& v = j_.at(key);
      if (v.is_number_float()) {
        const double d = v.get<double>();
        if (d != std::floor(d) || d < double(std::numeric_limits<T>::min()) ||
            d > double(std::numeric_limits<T>::max()))
          throw error(key, "must be a whole number (got " + v.dump() + ")");
        return static_cast<T>(d);
      }
      if (v.is_number_unsigned() && v.get<std::uint64_t>() > std::uint64_t(std::numeric_limits<T>::max()))
        throw error(key, "is out of range (got " + v.dump() + ")");
      if (v.is_number_integer() && !v.is_number_unsigned() &&
          (v.get<std::int64_t>() < std::int64_t(std::numeric_limits<T>::min()) ||
           v.get<std::int64_t>() > std::int64_t(std::numeric_limits<T>::max())))
        throw error(key, "is out of range (got " + v.dump() + ")");
    }
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
