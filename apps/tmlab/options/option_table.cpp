#include "apps/tmlab/options/option_table.hpp"

#include "core/base/format.hpp"
#include "core/base/number.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>

namespace tmlab::cli {

namespace {

std::string number_text(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

OptionSpec make(std::string name, OptionKind kind, std::string value, std::string help) {
  OptionSpec o;
  o.name = std::move(name);
  o.kind = kind;
  o.value = std::move(value);
  o.help = std::move(help);
  return o;
}

}  // namespace

bool Interval::contains(double v) const {
  return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
}

std::string Interval::text() const {
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  if (has_lo && has_hi)
    return std::string(lo_open ? "(" : "[") + number_text(lo) + ", " + number_text(hi) +
           (hi_open ? ")" : "]");
  if (has_lo) return std::string(lo_open ? "> " : ">= ") + number_text(lo);
  if (has_hi) return std::string(hi_open ? "< " : "<= ") + number_text(hi);
  return "";
}

Interval closed(double lo, double hi) { return {lo, hi, false, false}; }
Interval open(double lo, double hi) { return {lo, hi, true, true}; }
Interval open_closed(double lo, double hi) { return {lo, hi, true, false}; }
Interval positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }

OptionSpec& OptionSpec::def(std::string text) {
  check_value(*this, text);  // a default outside its own range is a bug of the table
  fallback = std::move(text);
  return *this;
}

OptionSpec& OptionSpec::role(unsigned r) {
  roles = r;
  return *this;
}

OptionSpec& OptionSpec::repeat() {
  repeatable = true;
  return *this;
}

std::string OptionSpec::key() const {
  std::string k = name.substr(name.rfind("--", 0) == 0 ? 2 : 0);
  std::replace(k.begin(), k.end(), '-', '_');
  return k;
}

OptionSpec flag(std::string name, std::string help) {
  return make(std::move(name), OptionKind::Flag, "", std::move(help));
}

OptionSpec text(std::string name, std::string value, std::string help) {
  return make(std::move(name), OptionKind::Text, std::move(value), std::move(help));
}

OptionSpec choice(std::string name, std::vector<std::string> choices, std::string help) {
  std::string value;
  for (const std::string& c : choices) value += (value.empty() ? "" : "|") + c;
  OptionSpec o = make(std::move(name), OptionKind::Choice, value, std::move(help));
  o.choices = std::move(choices);
  return o;
}

OptionSpec whole(std::string name, std::string value, long long min, long long max, std::string help) {
  OptionSpec o = make(std::move(name), OptionKind::Whole, std::move(value), std::move(help));
  o.whole_min = min;
  o.whole_max = max;
  return o;
}

OptionSpec decimal(std::string name, std::string value, Interval range, std::string help) {
  OptionSpec o = make(std::move(name), OptionKind::Decimal, std::move(value), std::move(help));
  o.range = range;
  return o;
}

OptionSpec whole_list(std::string name, std::string value, long long min, long long max, std::string help) {
  OptionSpec o = whole(std::move(name), std::move(value), min, max, std::move(help));
  o.kind = OptionKind::WholeList;
  return o;
}

OptionSpec text_list(std::string name, std::string value, std::string help) {
  return make(std::move(name), OptionKind::TextList, std::move(value), std::move(help));
}

OptionSpec numbers(std::string name, std::string value, std::size_t count, std::string help) {
  OptionSpec o = make(std::move(name), OptionKind::Numbers, std::move(value), std::move(help));
  o.count = count;
  return o;
}

const OptionSpec* CommandSpec::find(const std::string& option) const {
  for (const OptionSpec& o : options)
    if (o.name == option) return &o;
  return nullptr;
}

double parse_double(const std::string& key, const std::string& s) {
  double v = 0.0;
  std::string why;
  if (!tmlab::parse_decimal(s, v, why)) throw UsageError(key + " needs a number: " + why);
  return v;
}

long long parse_whole(const std::string& key, const std::string& s, long long min, long long max) {
  std::int64_t v = 0;
  std::string why;
  if (!tmlab::parse_whole(s, min, max, v, why)) throw UsageError(key + " needs a whole number: " + why);
  return static_cast<long long>(v);
}

std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string w; std::getline(in, w, ',');)
    if (!w.empty()) out.push_back(w);
  return out;
}

void check_value(const OptionSpec& o, const std::string& value) {
  switch (o.kind) {
    case OptionKind::Flag:
    case OptionKind::Text:
      return;
    case OptionKind::Choice:
      if (std::find(o.choices.begin(), o.choices.end(), value) == o.choices.end())
        throw UsageError(o.name + " must be " + choice_list(o.choices, "") + " (got '" +
                         printable(value, 60) + "')");
      return;
    case OptionKind::Whole:
      parse_whole(o.name, value, o.whole_min, o.whole_max);
      return;
    case OptionKind::Decimal:
      if (!o.range.contains(parse_double(o.name, value)))
        throw UsageError(o.name + " must be " +
                         (std::isfinite(o.range.lo) && std::isfinite(o.range.hi) ? "in " : "") +
                         o.range.text() + " (got '" + printable(value, 60) + "')");
      return;
    case OptionKind::WholeList:
      if (split_list(value).empty())
        throw UsageError(o.name + " needs a comma-separated list of whole numbers");
      for (const std::string& v : split_list(value)) parse_whole(o.name, v, o.whole_min, o.whole_max);
      return;
    case OptionKind::TextList:
      if (split_list(value).empty()) throw UsageError(o.name + " needs a comma-separated list");
      return;
    case OptionKind::Numbers:
      parse_numbers(o.name, value, o.count);
      return;
  }
}

std::vector<double> parse_numbers(const std::string& key, const std::string& s, std::size_t n) {
  std::vector<double> v;
  for (std::size_t from = 0;;) {  // an empty item is no number
    const std::size_t comma = s.find(',', from);
    v.push_back(
        parse_double(key, s.substr(from, comma == std::string::npos ? std::string::npos : comma - from)));
    if (comma == std::string::npos) break;
    from = comma + 1;
  }
  if (v.size() != n) throw UsageError(key + " needs " + std::to_string(n) + " comma-separated numbers");
  return v;
}

}  // namespace tmlab::cli
