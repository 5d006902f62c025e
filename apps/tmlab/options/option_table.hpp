// A command's options declared once (option_table.cpp): name, kind, range, default, help and the
// records its value goes into. The one table of a command drives its parsing (every number under
// tmlab's one grammar, core/base/number.hpp, checked against the declared range), its `tmlab help`
// block, its manifest's effective options and its resume fingerprint: parsed_options.hpp reads a
// command line against it, option_help.hpp writes its help. Modelled on deal.II's ParameterHandler
// declarations and FEBio's ADD_PARAMETER ranges: a parameter is declared once, with its range, and
// read back typed.
#pragma once

#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace tmlab::cli {

/// A command line the user must correct (tmlab exits 2 and names the option).
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// What an option takes.
enum class OptionKind {
  Flag,       ///< no value
  Text,       ///< any non-empty text (checked by the command: a path, a SPEC, a JSON object)
  Choice,     ///< one of `choices`
  Whole,      ///< a whole number in [whole_min, whole_max]
  Decimal,    ///< a number in `range`
  WholeList,  ///< comma-separated whole numbers, each in [whole_min, whole_max], at least one
  TextList,   ///< comma-separated non-empty words, at least one (empty items are dropped)
  Numbers,    ///< exactly `count` comma-separated numbers ("X,Y,Z")
};

/// The records an option's effective value goes into (bits).
enum OptionRole : unsigned {
  kShown = 0,         ///< neither: where or how the result is shown (--out, --no-plots, --quiet)
  kManifest = 1u,     ///< manifest.json's effective configuration
  kFingerprint = 2u,  ///< the resume fingerprint: changes the result
  kResult = 3u,       ///< both
};

/// An interval of numbers; each end open or closed (infinite ends: no bound).
struct Interval {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;
  bool contains(double v) const;
  std::string text() const;  ///< "(0, 60]", "> 0", "[1, inf)" as the help shows it
};
Interval closed(double lo, double hi);
Interval open(double lo, double hi);
Interval open_closed(double lo, double hi);
/// (0, inf): a positive number.
Interval positive();

/// One option of one command.
struct OptionSpec {
  std::string name;  ///< "--starts"
  OptionKind kind = OptionKind::Flag;
  std::string value;  ///< the placeholder in the help ("N", "DIR"); a choice's is "a|b|c"
  std::string help;   ///< one line (or a few, '\n'-separated)
  std::vector<std::string> choices;
  long long whole_min = 0, whole_max = 0;
  Interval range;
  std::size_t count = 0;                ///< Numbers: how many
  std::optional<std::string> fallback;  ///< the default, as the user would write it
  bool repeatable = false;              ///< may be given more than once (read with all())
  unsigned roles = kShown;

  OptionSpec& def(std::string text);  ///< declares the default
  OptionSpec& role(unsigned r);       ///< declares the records the value goes into
  OptionSpec& repeat();               ///< declares it repeatable
  /// The key of the value in the manifest and the fingerprint: the name without "--", '-' -> '_'.
  std::string key() const;
};

OptionSpec flag(std::string name, std::string help);
OptionSpec text(std::string name, std::string value, std::string help);
OptionSpec choice(std::string name, std::vector<std::string> choices, std::string help);
OptionSpec whole(std::string name, std::string value, long long min, long long max, std::string help);
OptionSpec decimal(std::string name, std::string value, Interval range, std::string help);
OptionSpec whole_list(std::string name, std::string value, long long min, long long max, std::string help);
OptionSpec text_list(std::string name, std::string value, std::string help);
OptionSpec numbers(std::string name, std::string value, std::size_t count, std::string help);

/// One command (or sub-command: "data convert") with its options.
struct CommandSpec {
  std::string name;                ///< "fit", "data convert"
  std::vector<std::string> usage;  ///< synopsis lines after the name (positional arguments, key options)
  std::string summary;             ///< what it does ('\n'-separated lines)
  std::vector<OptionSpec> options;
  const OptionSpec* find(const std::string& option) const;  ///< nullptr if not declared
};

/// Checks one value of `o` (UsageError naming the option otherwise).
void check_value(const OptionSpec& o, const std::string& value);

/// A number for option `key` under tmlab's one number grammar; UsageError naming the key otherwise.
double parse_double(const std::string& key, const std::string& s);
/// A whole number for option `key` within [min, max]; UsageError naming the key and the range.
long long parse_whole(const std::string& key, const std::string& s, long long min, long long max);
/// "a,b,c": exactly `n` numbers for option `key`; UsageError naming the key otherwise.
std::vector<double> parse_numbers(const std::string& key, const std::string& s, std::size_t n);
/// The non-empty items of a comma-separated value ("a,b,,c" -> a, b, c).
std::vector<std::string> split_list(const std::string& s);

}  // namespace tmlab::cli
