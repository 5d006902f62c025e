#include "apps/tmlab/options/option_help.hpp"

#include <cmath>
#include <sstream>
#include <vector>

namespace tmlab::cli {

namespace {

/// The range and default an option's help line ends with ("" when it has neither).
std::string detail(const OptionSpec& o) {
  std::vector<std::string> parts;
  if (o.kind == OptionKind::Whole || o.kind == OptionKind::WholeList)
    parts.push_back(std::to_string(o.whole_min) + ".." + std::to_string(o.whole_max));
  if (o.kind == OptionKind::Decimal && !o.range.text().empty())
    parts.push_back((std::isfinite(o.range.lo) && std::isfinite(o.range.hi) ? "in " : "") + o.range.text());
  if (o.fallback) parts.push_back("default " + *o.fallback);
  if (o.repeatable) parts.push_back("repeatable");
  std::string s;
  for (const std::string& p : parts) s += (s.empty() ? "" : ", ") + p;
  return s.empty() ? s : "(" + s + ")";
}

std::vector<std::string> lines(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

/// `head` then the `body` lines from column 28 (the first beside `head` when it fits).
void columns(std::string& out, const std::string& head, const std::vector<std::string>& body) {
  constexpr std::size_t kColumn = 28;
  std::size_t k = 0;
  if (head.size() + 1 < kColumn && !body.empty())
    out += head + std::string(kColumn - head.size(), ' ') + body[k++] + "\n";
  else
    out += head + "\n";
  for (; k < body.size(); ++k) out += std::string(kColumn, ' ') + body[k] + "\n";
}

}  // namespace

std::string command_help(const CommandSpec& spec) {
  std::string out;
  const std::string indent(2 + spec.name.size() + 1, ' ');
  const std::vector<std::string> summary = lines(spec.summary);
  for (std::size_t k = 0; k < spec.usage.size(); ++k) {
    const std::string head = (k == 0 ? "  " + spec.name + " " : indent) + spec.usage[k];
    columns(out, head, k + 1 == spec.usage.size() ? summary : std::vector<std::string>{});
  }
  if (spec.usage.empty()) columns(out, "  " + spec.name, summary);
  for (const OptionSpec& o : spec.options) {
    std::vector<std::string> help = lines(o.help);
    const std::string d = detail(o);
    if (!d.empty()) {
      if (help.empty())
        help.push_back(d);
      else if (help.back().size() + d.size() + 1 <= 82)
        help.back() += " " + d;
      else
        help.push_back(d);
    }
    columns(out, "      " + o.name + (o.value.empty() ? "" : " " + o.value), help);
  }
  return out;
}

}  // namespace tmlab::cli
