#include "calibration/fit/model_spec.hpp"

#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/base/number.hpp"
#include "core/constitutive/law_catalogue.hpp"
#include "tensormass/materials/law_factory.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

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

/// Positive modulus: start at v, sample starts over a factor 10 either way.
Parameter modulus_parameter(const std::string& name, double v) {
  return param(name, "Pa", v, 0.0, kInf, v / 10.0, v * 10.0);
}

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
  const std::string law = head.substr(0, colon);
  const std::optional<MaterialLaw> kind = material_law_from_string(law);
  if (!kind) {
    std::string list;
    for (const auto& n : law_name_list()) list += (list.empty() ? "" : ", ") + n;
    throw Error(label(text) + ": unknown law '" + printable(law, 40) + "' (use " + list + ")");
  }
  spec.law = *kind;
  if (colon != std::string::npos) {
    if (!law_descriptor(spec.law).has_terms()) {
      std::string list;
      for (const LawDescriptor& d : law_catalogue())
        if (d.has_terms()) list += (list.empty() ? "" : ", ") + std::string(d.name);
      throw Error(label(text) + ": ':N' (number of terms) is for " + list + " only");
    }
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
  const LawDescriptor& d = law_descriptor(spec.law);
  const int n = spec.ogden_terms;
  std::vector<Parameter> p;
  // An N-term law's exponents first (its moduli start from them), then the parameters in order.
  std::vector<double> exponent;
  for (const LawParameterInfo& info : d.parameters)
    if (info.list && info.fit.start == FitStart::TermExponent)
      for (int k = 0; k < n; ++k) exponent.push_back(k % 2 == 0 ? 2.0 + 2.0 * k : -2.0 * k);
  auto add = [&](const LawParameterInfo& info, const std::string& name, int k) {
    const LawFit& f = info.fit;
    switch (f.start) {
      case FitStart::Decade: {
        const double v = f.scale * (f.of_young ? modulus : mu0);
        p.push_back(param(name, info.unit, v, f.lower, f.upper, v / 10.0, v * 10.0));
        break;
      }
      case FitStart::Spread: {
        const double v = f.scale * mu0, scale = f.spread * mu0;
        p.push_back(param(name, info.unit, v, f.lower, f.upper, v - scale, v + scale));
        break;
      }
      case FitStart::Absolute:
        p.push_back(param(name, info.unit, f.scale, f.lower, f.upper, f.start_low, f.start_high));
        break;
      case FitStart::TermExponent: {
        const double a = exponent[std::size_t(k)];
        p.push_back(param(name, info.unit, a, f.lower, f.upper, a - f.spread, a + f.spread));
        break;
      }
      case FitStart::TermModulus: {
        const double m = 2.0 * mu0 / (n * exponent[std::size_t(k)]);  // 1/2 sum mu_p alpha_p = mu0
        p.push_back(param(name, info.unit, m, f.lower, f.upper, m - std::abs(m), m + std::abs(m)));
        break;
      }
    }
  };
  for (const LawParameterInfo& info : d.parameters) {
    if (info.list)
      for (int k = 0; k < n; ++k) add(info, info.name + std::to_string(k + 1), k);
    else
      add(info, info.name, 0);
  }
  if (d.bulk == BulkResponse::KappaOrPoisson) add(poisson_parameter(), poisson_parameter().name, 0);
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

namespace {

/// The law's parameters at `x` (in the order of law_parameters()); kappa is left 0.
LawParameters law_values(const ModelSpec& spec, const std::vector<double>& x) {
  const LawDescriptor& d = law_descriptor(spec.law);
  LawParameters p;
  std::size_t i = 0;
  for (const LawParameterInfo& info : d.parameters) {
    if (info.list) {
      const std::size_t n = std::size_t(spec.ogden_terms);
      p.*info.values = std::vector<double>(x.begin() + long(i), x.begin() + long(i + n));
      i += n;
    } else {
      p.*info.scalar = x[i++];
    }
  }
  if (d.bulk == BulkResponse::KappaOrPoisson) p.poisson = x[i];
  return p;
}

/// The small-strain shear modulus at `x`. Ogden's sum 1/2 sum_p mu_p alpha_p is taken over `x` in
/// place, with the fit's own loop, not with the catalogue's shear_modulus (the form
/// small_strain_moduli has always used): under -O3 -march=native GCC vectorises this loop in blocks
/// and contracts the remaining terms into FMAs, the catalogue's loop it leaves unfused, and the two
/// round differently for N > 1 (last bit of E, hence kappa and every fit number). Keep it verbatim.
double shear_modulus_at(const ModelSpec& spec, const LawParameters& p, const std::vector<double>& x) {
  if (spec.law != MaterialLaw::Ogden) return law_descriptor(spec.law).shear_modulus(p);
  double mu0 = 0.0;
  for (int k = 0; k < spec.ogden_terms; ++k) mu0 += 0.5 * x[k] * x[spec.ogden_terms + k];
  return mu0;
}

}  // namespace

std::pair<double, double> small_strain_young_poisson(const ModelSpec& spec, const std::vector<double>& x) {
  const LawDescriptor& d = law_descriptor(spec.law);
  const LawParameters p = law_values(spec, x);
  const double nu = p.poisson;
  if (d.bulk == BulkResponse::YoungPoisson) return {p.young, nu};
  const double mu0 = shear_modulus_at(spec, p, x);
  if (!(mu0 > 0.0))
    throw Error("fit: the small-strain shear modulus of '" + to_string(spec.law) + "' is not positive here");
  return {2.0 * mu0 * (1.0 + nu), nu};
}

tm::Law build_law(const ModelSpec& spec, const std::vector<double>& x) {
  const auto [young, nu] = small_strain_young_poisson(spec, x);
  LawParameters p = law_values(spec, x);
  if (law_descriptor(spec.law).bulk == BulkResponse::KappaOrPoisson)
    p.kappa = bulk_from_poisson(young / (2.0 * (1.0 + nu)), nu);
  return tm::make_law(spec.law, p, "fit model '" + spec.text + "'");
}

std::pair<std::vector<double>, std::vector<double>> prony_terms(const ModelSpec& spec,
                                                                const std::vector<double>& x) {
  const std::size_t m = std::size_t(spec.prony_terms);
  const std::size_t first = x.size() - 2 * m;
  return {std::vector<double>(x.begin() + long(first), x.begin() + long(first + m)),
          std::vector<double>(x.begin() + long(first + m), x.end())};
}

}  // namespace tmlab::fit
