// The options of one command line checked against the command's table (option_table.hpp), read
// back typed, and the effective values of the options of a role (the manifest's, the fingerprint's).
#pragma once

#include "apps/tmlab/options/option_table.hpp"

#include <nlohmann/json.hpp>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace tmlab::cli {

/// The checked options of one command line. Every getter takes a declared name (std::logic_error
/// otherwise: a command reading an option outside its table is a bug, never a user's error) and
/// returns the value given or the declared default.
class ParsedOptions {
 public:
  explicit ParsedOptions(CommandSpec spec);

  std::vector<std::string> positional;

  const CommandSpec& spec() const { return spec_; }
  /// Whether the user gave the option.
  bool given(const std::string& name) const;
  /// A flag: given or not.
  bool flag(const std::string& name) const;
  /// Text, Choice, or a list's text: the value given, else the default, else "".
  std::string text(const std::string& name) const;
  long long whole(const std::string& name) const;
  double decimal(const std::string& name) const;
  std::vector<long long> whole_list(const std::string& name) const;
  std::vector<std::string> text_list(const std::string& name) const;
  std::vector<double> numbers(const std::string& name) const;
  /// `out` = the value when the option was given; unchanged otherwise (a default of the caller's).
  void assign_if_given(const std::string& name, int& out) const;
  void assign_if_given(const std::string& name, double& out) const;
  /// Every value given for a repeatable option, in order.
  std::vector<std::string> all(const std::string& name) const;
  /// A default known only at run time (e.g. one that depends on --quick), checked like a value.
  void set_default(const std::string& name, const std::string& value);

  /// The effective value of every option with `role`: {key: value}, typed (a flag a bool, a number
  /// a number, a list an array, a repeatable option the array of its values); null when an option
  /// is neither given nor has a default.
  nlohmann::json config(unsigned role) const;

  /// Records a checked value (parse()).
  void add(const std::string& name, std::string value);

 private:
  const OptionSpec& declared(const std::string& name) const;
  std::optional<std::string> effective(const std::string& name) const;

  CommandSpec spec_;
  std::map<std::string, std::vector<std::string>> given_;
  std::map<std::string, std::string> defaults_;
};

/// Parses `args` against `spec`: an unknown option, a missing or empty value, an option given twice
/// (unless repeatable), a value outside its range or choices is a UsageError naming the option.
ParsedOptions parse(const CommandSpec& spec, const std::vector<std::string>& args);

}  // namespace tmlab::cli
