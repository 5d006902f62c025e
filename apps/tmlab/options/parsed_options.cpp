#include "apps/tmlab/options/parsed_options.hpp"

#include "core/base/format.hpp"

#include <stdexcept>

namespace tmlab::cli {

ParsedOptions::ParsedOptions(CommandSpec spec) : spec_(std::move(spec)) {}

const OptionSpec& ParsedOptions::declared(const std::string& name) const {
  const OptionSpec* o = spec_.find(name);
  if (o == nullptr)
    throw std::logic_error("tmlab " + spec_.name + " reads " + name + ", not in its option table");
  return *o;
}

void ParsedOptions::add(const std::string& name, std::string value) {
  given_[name].push_back(std::move(value));
}

bool ParsedOptions::given(const std::string& name) const {
  declared(name);
  return given_.count(name) != 0;
}

bool ParsedOptions::flag(const std::string& name) const {
  if (declared(name).kind != OptionKind::Flag) throw std::logic_error(name + " is not a flag");
  return given_.count(name) != 0;
}

std::optional<std::string> ParsedOptions::effective(const std::string& name) const {
  const OptionSpec& o = declared(name);
  if (const auto it = given_.find(name); it != given_.end()) return it->second.front();
  if (const auto it = defaults_.find(name); it != defaults_.end()) return it->second;
  return o.fallback;
}

std::string ParsedOptions::text(const std::string& name) const { return effective(name).value_or(""); }

long long ParsedOptions::whole(const std::string& name) const {
  const OptionSpec& o = declared(name);
  const std::optional<std::string> v = effective(name);
  if (o.kind != OptionKind::Whole || !v) throw std::logic_error(name + ": no whole number and no default");
  return parse_whole(name, *v, o.whole_min, o.whole_max);
}

double ParsedOptions::decimal(const std::string& name) const {
  const OptionSpec& o = declared(name);
  const std::optional<std::string> v = effective(name);
  if (o.kind != OptionKind::Decimal || !v) throw std::logic_error(name + ": no number and no default");
  return parse_double(name, *v);
}

std::vector<long long> ParsedOptions::whole_list(const std::string& name) const {
  const OptionSpec& o = declared(name);
  if (o.kind != OptionKind::WholeList) throw std::logic_error(name + " is not a list of whole numbers");
  std::vector<long long> out;
  for (const std::string& s : split_list(text(name)))
    out.push_back(parse_whole(name, s, o.whole_min, o.whole_max));
  return out;
}

std::vector<std::string> ParsedOptions::text_list(const std::string& name) const {
  if (declared(name).kind != OptionKind::TextList) throw std::logic_error(name + " is not a list");
  return split_list(text(name));
}

std::vector<double> ParsedOptions::numbers(const std::string& name) const {
  const OptionSpec& o = declared(name);
  if (o.kind != OptionKind::Numbers) throw std::logic_error(name + " is not a list of numbers");
  return effective(name) ? parse_numbers(name, *effective(name), o.count) : std::vector<double>{};
}

void ParsedOptions::assign_if_given(const std::string& name, int& out) const {
  if (given(name)) out = static_cast<int>(whole(name));
}

void ParsedOptions::assign_if_given(const std::string& name, double& out) const {
  if (given(name)) out = decimal(name);
}

std::vector<std::string> ParsedOptions::all(const std::string& name) const {
  declared(name);
  const auto it = given_.find(name);
  return it == given_.end() ? std::vector<std::string>{} : it->second;
}

void ParsedOptions::set_default(const std::string& name, const std::string& value) {
  check_value(declared(name), value);
  defaults_[name] = value;
}

nlohmann::json ParsedOptions::config(unsigned role) const {
  nlohmann::json j = nlohmann::json::object();
  for (const OptionSpec& o : spec_.options) {
    if ((o.roles & role) == 0) continue;
    nlohmann::json& v = j[o.key()];
    if (o.kind == OptionKind::Flag) {
      v = flag(o.name);
      continue;
    }
    if (o.repeatable) {
      v = all(o.name);
      continue;
    }
    if (!effective(o.name)) continue;  // null: neither given nor a default
    switch (o.kind) {
      case OptionKind::Whole:
        v = whole(o.name);
        break;
      case OptionKind::Decimal:
        v = decimal(o.name);
        break;
      case OptionKind::WholeList:
        v = whole_list(o.name);
        break;
      case OptionKind::TextList:
        v = text_list(o.name);
        break;
      case OptionKind::Numbers:
        v = numbers(o.name);
        break;
      default:
        v = text(o.name);
        break;
    }
  }
  return j;
}

ParsedOptions parse(const CommandSpec& spec, const std::vector<std::string>& args) {
  ParsedOptions p(spec);
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a.rfind("--", 0) != 0) {
      p.positional.push_back(a);
      continue;
    }
    const OptionSpec* o = spec.find(a);
    if (o == nullptr) throw UsageError("unknown option " + a);
    std::string value;
    if (o->kind != OptionKind::Flag) {
      if (i + 1 >= args.size()) throw UsageError("option " + a + " needs a value");
      value = args[++i];
      if (value.empty())
        throw UsageError("option " + a + " has an empty value" +
                         (a == "--out" || a == "--results"
                              ? std::string(": a result needs a folder of its own (e.g. results/NAME)")
                              : std::string()));
    }
    const std::vector<std::string> before = p.all(a);
    if (!before.empty() && !o->repeatable)
      throw UsageError("option " + a + " is given " + std::to_string(before.size() + 1) + " times" +
                       (o->kind == OptionKind::Flag ? std::string()
                                                    : " ('" + printable(before.front(), 60) + "' and '" +
                                                          printable(value, 60) + "')") +
                       ": give it once");
    check_value(*o, value);
    p.add(a, std::move(value));
  }
  return p;
}

}  // namespace tmlab::cli
