#include "tensormass/materials/law_factory.hpp"

#include "core/base/error.hpp"
#include "core/constitutive/law_catalogue.hpp"

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

/// The keys of a decoupled law as its refusals quote them: "\"c10\", \"c01\", \"kappa\"".
std::string keys_of(const LawDescriptor& d) {
  std::string s;
  for (const LawParameterInfo& info : d.parameters)
    s += (s.empty() ? "\"" : ", \"") + std::string(info.name) + "\"";
  return s + ", \"" + bulk_modulus_parameter().name + "\"";
}

}  // namespace

std::vector<std::string> law_names() { return law_name_list(); }

Law make_law(const std::string& name, const nlohmann::json& params, const std::string& where,
             const std::vector<std::string>& ignored) {
  const std::optional<MaterialLaw> kind = material_law_from_string(name);
  if (!kind) throw Error(where + ".law '" + name + "' is unknown (use " + join(law_names()) + ")");
  if (!params.is_object())
    throw Error(where + " must be a JSON object of law parameters, got " + params.dump());
  const LawDescriptor& d = law_descriptor(*kind);
  Reader r(params, where, name);
  std::optional<Law> law;
  if (d.bulk == BulkResponse::YoungPoisson) {
    const LameConstants l = lame(r, where, name);
    law = construct(where, name, "\"lambda\", \"mu\"", [&] { return Law::of(*kind, {}, l); });
  } else {
    LawParameters p;
    for (const LawParameterInfo& info : d.parameters) {
      if (info.list)
        p.*info.values = r.numbers(info.name);
      else
        p.*info.scalar = info.has_default ? r.number_or(info.name, info.default_value) : r.number(info.name);
    }
    p.kappa = r.number(bulk_modulus_parameter().name);
    law = construct(where, name, keys_of(d), [&] { return Law::of(*kind, p, {}); });
  }
  r.check_unknown(ignored);
  return *law;
}

Law make_law(MaterialLaw law, const LawParameters& p, const std::string& where) {
  const LawDescriptor& d = law_descriptor(law);
  json params = json::object();
  for (const LawParameterInfo& info : d.parameters) {
    if (info.list)
      params[info.name] = p.*info.values;
    else
      params[info.name] = p.*info.scalar;
  }
  if (d.bulk == BulkResponse::KappaOrPoisson) params[bulk_modulus_parameter().name] = p.kappa;
  return make_law(to_string(law), params, where);
}

}  // namespace tmlab::tm
