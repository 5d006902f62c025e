#include "calibration/fit/model_spec.hpp"

#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/base/number.hpp"
#include "tensormass/materials/law_factory.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>

namespace tmlab::fit {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::size_t a = 0;
  for (;;) {
    const std::size_t b = s.find(sep, a);
    out.push_back(s.substr(a, b == std::string::npos ? std::string::npos : b - a));
    if (b == std::string::npos) return out;
    a = b + 1;
  }
}

/// "--model 'SPEC'" with the SPEC shown safely (control characters escaped, long text cut).
std::string label(const std::string& spec) { return "--model '" + printable(spec, 80) + "'"; }

int small_count(const std::string& spec, const std::string& what, const std::string& s) {
  std::int64_t n = 0;
  std::string why;
  if (!parse_whole(s, 1, 9, n, why))
    throw Error(label(spec) + ": " + what + " must be a whole number 1..9: " + why);
  return int(n);
}

Parameter param(std::string name, std::string unit, double value, double lo, double hi, double s_lo,
                double s_hi) {
  Parameter p;
  p.name = std::move(name);
  p.unit = std::move(unit);
  p.value = value;
  p.lower = lo;
  p.upper = hi;
  p.start_low = s_lo;
  p.start_high = s_hi;
  return p;
}

Parameter poisson_parameter() { return param("poisson", "1", 0.45, 0.0, 0.4999, 0.05, 0.495); }

/// Positive modulus: start at v, sample starts over a factor 10 either way.
Parameter modulus_parameter(const std::string& name, double v) {
  return param(name, "Pa", v, 0.0, kInf, v / 10.0, v * 10.0);
}
/// Signed modulus (unbounded): start at v, sample starts in v +- scale.
Parameter signed_parameter(const std::string& name, double v, double scale) {
  return param(name, "Pa", v, -kInf, kInf, v - scale, v + scale);
}

double kappa_from(double mu0, double nu) { return 2.0 * mu0 * (1.0 + nu) / (3.0 * (1.0 - 2.0 * nu)); }

}  // namespace

std::string shortest(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

ModelSpec parse_model_spec(const std::string& text) {
  ModelSpec spec;
  spec.text = text;
  const std::vector<std::string> parts = split(text, ',');
  std::string head = parts[0];
  const std::size_t plus = head.find('+');
  if (plus != std::string::npos) {
    const std::string tail = head.substr(plus + 1);
    head = head.substr(0, plus);
    if (tail.rfind("prony:", 0) != 0)
      throw Error(label(text) + ": after '+' only 'prony:M' is known, got '" + printable(tail, 40) + "'");
    spec.prony_terms = small_count(text, "the number of Prony terms", tail.substr(6));
  }
  const std::size_t colon = head.find(':');
  spec.law = head.substr(0, colon);
  const auto& names = tm::law_names();
  if (std::find(names.begin(), names.end(), spec.law) == names.end()) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw Error(label(text) + ": unknown law '" + printable(spec.law, 40) + "' (use " + list + ")");
  }
  if (colon != std::string::npos) {
    if (spec.law != "ogden") throw Error(label(text) + ": ':N' (number of terms) is for ogden only");
    spec.ogden_terms = small_count(text, "the number of Ogden terms", head.substr(colon + 1));
  }
  for (std::size_t i = 1; i < parts.size(); ++i) {
    const std::size_t eq = parts[i].find('=');
    if (eq == std::string::npos || eq == 0)
      throw Error(label(text) + ": '" + printable(parts[i], 40) + "' is not NAME=VALUE");
    const std::string name = parts[i].substr(0, eq), value = parts[i].substr(eq + 1);
    double v = 0.0;
    std::string why;
    if (!parse_decimal(value, v, why))
      throw Error(label(text) + ": the value of '" + printable(name, 40) + "': " + why);
    for (const auto& [other, w] : spec.fixed)
      if (other == name)
        throw Error(label(text) + ": '" + printable(name, 40) + "' is fixed twice (" + shortest(w) + " and " +
                    shortest(v) + "): give it once");
    spec.fixed.emplace_back(name, v);
  }
  return spec;
}

std::vector<Parameter> law_parameters(const ModelSpec& spec, double modulus, double duration) {
  if (!(modulus > 0.0) || !std::isfinite(modulus))
    throw Error("fit: no positive modulus estimate from the data");
  const double mu0 = modulus / 3.0;  // nearly incompressible start
  std::vector<Parameter> p;
  if (spec.law == "stvk" || spec.law == "neo_hookean") {
    p.push_back(modulus_parameter("young", modulus));
  } else if (spec.law == "mooney_rivlin") {
    p.push_back(signed_parameter("c10", 0.35 * mu0, 0.5 * mu0));
    p.push_back(signed_parameter("c01", 0.15 * mu0, 0.5 * mu0));
  } else if (spec.law == "yeoh") {
    p.push_back(modulus_parameter("c10", 0.5 * mu0));
    p.push_back(signed_parameter("c20", 0.0, 0.1 * mu0));
    p.push_back(signed_parameter("c30", 0.0, 0.02 * mu0));
  } else if (spec.law == "ogden") {
    const int n = spec.ogden_terms;
    std::vector<double> alpha;
    for (int k = 0; k < n; ++k) alpha.push_back(k % 2 == 0 ? 2.0 + 2.0 * k : -2.0 * k);
    for (int k = 0; k < n; ++k) {
      const double m = 2.0 * mu0 / (n * alpha[k]);  // 1/2 sum mu_p alpha_p = mu0
      p.push_back(signed_parameter("mu" + std::to_string(k + 1), m, std::abs(m)));
    }
    for (int k = 0; k < n; ++k) {
      Parameter a =
          param("alpha" + std::to_string(k + 1), "1", alpha[k], -40.0, 40.0, alpha[k] - 1.5, alpha[k] + 1.5);
      p.push_back(a);
    }
  } else if (spec.law == "veronda_westmann") {
    p.push_back(modulus_parameter("c1", mu0));
    p.push_back(param("c2", "1", 1.0, 0.0, kInf, 0.1, 10.0));
  } else {
    throw Error("fit: law '" + spec.law + "' has no fit parameters defined");
  }
  p.push_back(poisson_parameter());
  const double t = duration > 0.0 ? duration : 1.0;
  for (int i = 0; i < spec.prony_terms; ++i)
    p.push_back(modulus_parameter("e" + std::to_string(i + 1), 0.5 * modulus / spec.prony_terms));
  for (int i = 0; i < spec.prony_terms; ++i) {
    // Relaxation times spread over the test's duration, a decade apart.
    const double tau = t * std::pow(10.0, -1.0 - i);
    p.push_back(param("tau" + std::to_string(i + 1), "s", tau, 0.0, kInf, tau / 10.0, tau * 10.0));
  }
  return p;
}

std::pair<double, double> small_strain_young_poisson(const ModelSpec& spec, const std::vector<double>& x) {
  const double nu = x[spec.law == "stvk" || spec.law == "neo_hookean" ? 1
                      : spec.law == "mooney_rivlin"                   ? 2
                      : spec.law == "yeoh"                            ? 3
                      : spec.law == "ogden"                           ? std::size_t(2 * spec.ogden_terms)
                                                                      : 2];
  double mu0 = 0.0;
  if (spec.law == "stvk" || spec.law == "neo_hookean") return {x[0], nu};
  if (spec.law == "mooney_rivlin") mu0 = 2.0 * (x[0] + x[1]);
  if (spec.law == "yeoh") mu0 = 2.0 * x[0];
  if (spec.law == "ogden")
    for (int k = 0; k < spec.ogden_terms; ++k) mu0 += 0.5 * x[k] * x[spec.ogden_terms + k];
  if (spec.law == "veronda_westmann") mu0 = x[0] * x[1];
  if (!(mu0 > 0.0))
    throw Error("fit: the small-strain shear modulus of '" + spec.law + "' is not positive here");
  return {2.0 * mu0 * (1.0 + nu), nu};
}

tm::Law build_law(const ModelSpec& spec, const std::vector<double>& x) {
  using nlohmann::json;
  const auto [young, nu] = small_strain_young_poisson(spec, x);
  const double kappa = kappa_from(young / (2.0 * (1.0 + nu)), nu);
  json j;
  if (spec.law == "stvk" || spec.law == "neo_hookean") {
    j = {{"young", young}, {"poisson", nu}};
  } else if (spec.law == "mooney_rivlin") {
    j = {{"c10", x[0]}, {"c01", x[1]}, {"kappa", kappa}};
  } else if (spec.law == "yeoh") {
    j = {{"c10", x[0]}, {"c20", x[1]}, {"c30", x[2]}, {"kappa", kappa}};
  } else if (spec.law == "ogden") {
    const int n = spec.ogden_terms;
    j = {{"mu", std::vector<double>(x.begin(), x.begin() + n)},
         {"alpha", std::vector<double>(x.begin() + n, x.begin() + 2 * n)},
         {"kappa", kappa}};
  } else {
    j = {{"c1", x[0]}, {"c2", x[1]}, {"kappa", kappa}};
  }
  return tm::make_law(spec.law, j, "fit model '" + spec.text + "'");
}

std::pair<std::vector<double>, std::vector<double>> prony_terms(const ModelSpec& spec,
                                                                const std::vector<double>& x) {
  const std::size_t m = std::size_t(spec.prony_terms);
  const std::size_t first = x.size() - 2 * m;
  return {std::vector<double>(x.begin() + long(first), x.begin() + long(first + m)),
          std::vector<double>(x.begin() + long(first + m), x.end())};
}

}  // namespace tmlab::fit
