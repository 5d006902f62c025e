#include "tensormass/materials/law_factory.hpp"

#include "core/base/error.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <optional>

namespace tmlab::tm {

namespace {

using nlohmann::json;

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + ("\"" + v[i] + "\"");
  return s;
}

/// Reads the keys of one law from the parameter object, naming each in its errors.
class Reader {
 public:
  Reader(const json& p, std::string where, std::string law)
      : p_(p), where_(std::move(where)), law_(std::move(law)) {}

  bool has(const std::string& key) const { return p_.contains(key); }

  double number(const std::string& key) {
    accepted_.push_back(key);
    if (!p_.contains(key)) fail(key, "is missing (law '" + law_ + "' needs it)");
    return to_number(p_.at(key), key);
  }
  double number_or(const std::string& key, double fallback) {
    accepted_.push_back(key);
    return p_.contains(key) ? to_number(p_.at(key), key) : fallback;
  }
  std::vector<double> numbers(const std::string& key) {
    accepted_.push_back(key);
    if (!p_.contains(key)) fail(key, "is missing (law '" + law_ + "' needs it)");
    const json& a = p_.at(key);
    if (!a.is_array() || a.empty()) fail(key, "must be a non-empty array of numbers");
    std::vector<double> out;
    for (std::size_t i = 0; i < a.size(); ++i)
      out.push_back(to_number(a[i], key + "[" + std::to_string(i) + "]"));
    return out;
  }
  void accept(const std::string& key) { accepted_.push_back(key); }

  /// Refuses keys that are neither read nor ignored.
  void check_unknown(const std::vector<std::string>& ignored) const {
    for (auto it = p_.begin(); it != p_.end(); ++it) {
      const std::string& k = it.key();
      if (std::find(accepted_.begin(), accepted_.end(), k) != accepted_.end()) continue;
      if (std::find(ignored.begin(), ignored.end(), k) != ignored.end()) continue;
      fail(k, "is not a parameter of law '" + law_ + "' (accepted: " + join(accepted_) + ")");
    }
  }

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw Error(where_ + "." + key + " " + what);
  }

 private:
  double to_number(const json& v, const std::string& key) const {
    if (!v.is_number()) fail(key, "must be a number, got " + v.dump());
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail(key, "must be finite");
    return x;
  }

  const json& p_;
  std::string where_, law_;
  std::vector<std::string> accepted_;
};

/// Runs the law's constructor, prefixing its refusal with the location and the keys involved.
template <class F>
Law construct(const std::string& where, const std::string& law, const std::string& keys, F&& f) {
  try {
    return f();
  } catch (const Error& e) {
    throw Error(where + " (law '" + law + "', keys " + keys + "): " + e.what());
  }
}

/// St VK and neo-Hookean: (young, poisson) or (lambda, mu), not both.
LameConstants lame(Reader& r, const std::string& where, const std::string& law) {
  const bool ep = r.has("young") || r.has("poisson"), lm = r.has("lambda") || r.has("mu");
  if (ep && lm)
    throw Error(where + ": law '" + law +
                "' takes either \"young\" and \"poisson\" or \"lambda\" and \"mu\", not both");
  if (lm) {
    const double l = r.number("lambda"), m = r.number("mu");
    r.accept("young");
    r.accept("poisson");
    return {l, m};
  }
  const double E = r.number("young"), nu = r.number("poisson");
  r.accept("lambda");
  r.accept("mu");
  const auto m = construct(where, law, "\"young\", \"poisson\"",
                           [&] { return Law(StVenantKirchhoff::from_young_poisson(E, nu)); });
  return m.small_strain();
}

}  // namespace

std::vector<std::string> law_names() {
  return {"stvk", "neo_hookean", "mooney_rivlin", "yeoh", "ogden", "veronda_westmann"};
}

Law make_law(const std::string& name, const nlohmann::json& params, const std::string& where,
             const std::vector<std::string>& ignored) {
  const auto& names = law_names();
  if (std::find(names.begin(), names.end(), name) == names.end())
    throw Error(where + ".law '" + name + "' is unknown (use " + join(names) + ")");
  if (!params.is_object())
    throw Error(where + " must be a JSON object of law parameters, got " + params.dump());
  Reader r(params, where, name);
  std::optional<Law> law;
  if (name == "stvk") {
    const LameConstants l = lame(r, where, name);
    if (!(l.mu > 0.0) || !(l.lambda + 2.0 * l.mu / 3.0 > 0.0))
      throw Error(where +
                  " (law 'stvk', keys \"lambda\", \"mu\"): St Venant-Kirchhoff material needs mu > 0 and "
                  "lambda + 2 mu/3 > 0, got lambda = " +
                  std::to_string(l.lambda) + ", mu = " + std::to_string(l.mu));
    law = StVenantKirchhoff{l.lambda, l.mu};
  } else if (name == "neo_hookean") {
    const LameConstants l = lame(r, where, name);
    law = construct(where, name, "\"lambda\", \"mu\"", [&] { return Law(NeoHookean(l.lambda, l.mu)); });
  } else if (name == "mooney_rivlin") {
    const double c10 = r.number("c10"), c01 = r.number("c01"), kappa = r.number("kappa");
    law = construct(where, name, "\"c10\", \"c01\", \"kappa\"",
                    [&] { return Law(MooneyRivlin(c10, c01, kappa)); });
  } else if (name == "yeoh") {
    const double c10 = r.number("c10"), c20 = r.number_or("c20", 0.0), c30 = r.number_or("c30", 0.0);
    const double kappa = r.number("kappa");
    law = construct(where, name, "\"c10\", \"c20\", \"c30\", \"kappa\"",
                    [&] { return Law(Yeoh(c10, c20, c30, kappa)); });
  } else if (name == "ogden") {
    std::vector<double> mu = r.numbers("mu"), alpha = r.numbers("alpha");
    const double kappa = r.number("kappa");
    law = construct(where, name, "\"mu\", \"alpha\", \"kappa\"",
                    [&] { return Law(Ogden(std::move(mu), std::move(alpha), kappa)); });
  } else {  // veronda_westmann
    const double c1 = r.number("c1"), c2 = r.number("c2"), kappa = r.number("kappa");
    law = construct(where, name, "\"c1\", \"c2\", \"kappa\"",
                    [&] { return Law(VerondaWestmann(c1, c2, kappa)); });
  }
  r.check_unknown(ignored);
  return *law;
}

Law make_law(MaterialLaw law, const LawParameters& p, const std::string& where) {
  json params;
  switch (law) {
    case MaterialLaw::StVK:
    case MaterialLaw::NeoHookean:
      params = {{"young", p.young}, {"poisson", p.poisson}};
      break;
    case MaterialLaw::MooneyRivlin:
      params = {{"c10", p.c10}, {"c01", p.c01}, {"kappa", p.kappa}};
      break;
    case MaterialLaw::Yeoh:
      params = {{"c10", p.c10}, {"c20", p.c20}, {"c30", p.c30}, {"kappa", p.kappa}};
      break;
    case MaterialLaw::Ogden:
      params = {{"mu", p.mu}, {"alpha", p.alpha}, {"kappa", p.kappa}};
      break;
    case MaterialLaw::VerondaWestmann:
      params = {{"c1", p.c1}, {"c2", p.c2}, {"kappa", p.kappa}};
      break;
  }
  return make_law(to_string(law), params, where);
}

}  // namespace tmlab::tm
