#include "cli_args.hpp"

#include "commands.hpp"

#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/base/number.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <stdexcept>

namespace tmlab::cli {

std::string Parsed::get(const std::string& key, const std::string& fallback) const {
  const std::vector<std::string> given = all(key);
  if (given.size() > 1)
    throw UsageError("option " + key + " is given " + std::to_string(given.size()) + " times ('" +
                     printable(given[0], 60) + "' and '" + printable(given[1], 60) + "'): give it once");
  return given.empty() ? fallback : given.front();
}

bool Parsed::has(const std::string& key) const {
  return std::any_of(options.begin(), options.end(), [&](const auto& o) { return o.first == key; });
}

std::vector<std::string> Parsed::all(const std::string& key) const {
  std::vector<std::string> out;
  for (const auto& o : options)
    if (o.first == key) out.push_back(o.second);
  return out;
}

Parsed parse(const std::vector<std::string>& args, const std::vector<std::string>& with_value,
             const std::vector<std::string>& flags) {
  Parsed p;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a.rfind("--", 0) == 0) {
      if (std::find(with_value.begin(), with_value.end(), a) != with_value.end()) {
        if (i + 1 >= args.size()) throw UsageError("option " + a + " needs a value");
        if (args[i + 1].empty())
          throw UsageError("option " + a + " has an empty value" +
                           (a == "--out" || a == "--results"
                                ? std::string(": a result needs a folder of its own (e.g. results/NAME)")
                                : std::string()));
        p.options.emplace_back(a, args[++i]);
      } else if (std::find(flags.begin(), flags.end(), a) != flags.end()) {
        p.options.emplace_back(a, "");
      } else {
        throw UsageError("unknown option " + a);
      }
    } else {
      p.positional.push_back(a);
    }
  }
  return p;
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

std::vector<std::string> split_words(const std::string& s) {
  std::istringstream in(s);
  std::vector<std::string> w;
  for (std::string x; in >> x;) w.push_back(x);
  return w;
}

std::pair<int, int> parse_cells_layers(const std::string& m) {
  const std::size_t comma = m.find(',');
  if (comma == std::string::npos) throw UsageError("--mesh needs CELLS,LAYERS, got '" + m + "'");
  return {int(parse_whole("--mesh CELLS", m.substr(0, comma), 2, 400)),
          int(parse_whole("--mesh LAYERS", m.substr(comma + 1), 1, 400))};
}

CheckpointSchedule checkpoint_schedule(const Parsed& p) {
  try {
    return p.has("--checkpoint-every") ? CheckpointSchedule::parse(p.get("--checkpoint-every"))
                                       : CheckpointSchedule{};
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
}

}  // namespace tmlab::cli
