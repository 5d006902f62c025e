#include "calibration/discover/effects.hpp"

#include "calibration/closed_forms/homogeneous.hpp"
#include "calibration/closed_forms/indentation.hpp"
#include "calibration/discover/bulk_shear.hpp"
#include "calibration/fit/model_spec.hpp"
#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/constitutive/law_catalogue.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <optional>

namespace tmlab::discover {

namespace {

using namespace tmlab::measured;
constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();

fit::Parameter param(std::string name, std::string unit, double value, double lo, double hi, double s_lo,
                     double s_hi) {
  fit::Parameter p;
  p.name = std::move(name);
  p.unit = std::move(unit);
  p.value = value;
  p.lower = lo;
  p.upper = hi;
  p.start_low = s_lo;
  p.start_high = s_hi;
  return p;
}

fit::ModelSpec spec_of(const Structure& s) {
  fit::ModelSpec spec;
  spec.law = s.law;
  spec.ogden_terms = 1;
  spec.prony_terms = s.prony_terms;
  spec.text = to_string(s.law) + (s.prony_terms ? "+prony:" + std::to_string(s.prony_terms) : "");
  return spec;
}

/// Number of parameters of each non-law effect, in the order they are appended.
std::vector<std::string> effect_parameter_names(const std::string& e) {
  if (e == "strain_dependent_relaxation") return {"relax_strain_slope"};
  if (e == "poroelastic_relaxation") return {"e_poro", "diffusivity"};
  if (e == "separate_bulk_shear_relaxation") return {"drained_poisson", "tau_bulk"};
  if (e == "contact_offset") return {"contact_offset"};
  if (e == "force_offset") return {"force_offset"};
  if (e == "force_drift") return {"force_drift"};
  if (e == "displacement_drift") return {"displacement_drift"};
  if (e == "instrument_compliance") return {"compliance"};
  if (e == "platen_friction") return {"friction_fraction"};
  if (e == "finite_layer_thickness") return {"layer_thickness"};
  throw Error("discover: effect '" + e + "' has no parameters defined");
}

/// Relaxation-time range the data can resolve: from two sampling steps to the longest test.
std::pair<double, double> tau_range(const Prepared& p) {
  const double a = std::max(2.0 * p.min_dt, 1e-6), b = std::max(p.duration, 4.0 * a);
  return {a, b};
}

/// The poroelastic length of test k: the contact radius at the test's deepest point (sphere), the
/// punch radius, or for platens the sample's half-width (unconfined) or height (confined).
double poro_length(const Prepared& p, std::size_t k) {
  if (p.rig == Rig::sphere) {
    double dm = 0.0;
    for (const double d : p.series[k].d) dm = std::max(dm, d);
    return std::sqrt(p.radius * std::max(dm, 1e-12));
  }
  if (p.rig == Rig::punch) return p.radius;
  return p.rig == Rig::platen_confined ? p.height : 2.0 * p.shape_factor * p.height;
}

}  // namespace

bool pinned_at_bound(const fit::Parameter& q, double x) {
  switch (q.transform()) {
    case fit::Transform::Logit:
      return std::abs(q.to_internal(x)) > 12.0;
    case fit::Transform::Log: {
      const bool low = std::isfinite(q.lower);
      const double gap = low ? x - q.lower : q.upper - x,
                   reach = low ? q.start_high - q.lower : q.upper - q.start_low;
      return gap < 1e-9 * reach;
    }
    case fit::Transform::Identity:
      return false;
  }
  return false;
}

std::string to_string(EffectKind k) {
  switch (k) {
    case EffectKind::material:
      return "material";
    case EffectKind::experiment:
      return "experiment";
    case EffectKind::geometry:
      return "geometry";
  }
  return "?";
}

std::string to_string(Rig r) {
  switch (r) {
    case Rig::platen_unconfined:
      return "platen_unconfined";
    case Rig::platen_confined:
      return "platen_confined";
    case Rig::tension:
      return "platen_tension";
    case Rig::sphere:
      return "sphere_indentation";
    case Rig::punch:
      return "punch_indentation";
  }
  return "?";
}

std::vector<EffectInfo> effect_library() {
  return [] {
    std::vector<EffectInfo> v;
    const auto m = EffectKind::material, x = EffectKind::experiment, g = EffectKind::geometry;
    v.push_back(
        {"extra_prony_term", m, "one more term e_j exp(-t/tau_j) of the relaxation function",
         "a decaying residual in the holds and a rate-dependent one in the ramps, at one time scale"});
    // Every law of the catalogue but St VK, the library's starting law (N-term laws with one term).
    for (const LawDescriptor& d : law_catalogue()) {
      if (d.law == MaterialLaw::StVK) continue;
      const std::string law = d.name, w = std::string(d.energy) + (d.has_terms() ? " (one term)" : "");
      v.push_back({law + "_hyperelastic", m, "the elastic law replaced by " + law + ": " + w,
                   "a residual that grows with strain, of one sign at large strain (stiffening or softening "
                   "the current law lacks), the same in every phase and test"});
    }
    v.push_back(
        {"strain_dependent_relaxation", m,
         "Prony weights alpha_j (1 + a eps) with eps the strain (depth over radius for indentation)",
         "a relaxation residual (holds, rate dependence) whose size grows with the strain of the hold"});
    v.push_back(
        {"poroelastic_relaxation", m,
         "a relaxation term alpha_p exp(-t/tau_p) with tau_p = L^2/D, L the contact radius of each test",
         "relaxation whose time scale grows with the contact size: slower at deeper indentation"});
    v.push_back(
        {"separate_bulk_shear_relaxation", m,
         "the bulk modulus relaxes beyond the shear modulus, to the drained Poisson ratio nu_inf with its "
         "own "
         "time tau_b (G = G0 g(t), K = K0 g(t) - (K0 - K_inf)(1 - exp(-t/tau_b))); the rig modulus by the "
         "correspondence principle",
         "a relaxation whose size depends on the rig (large in confined compression, small in unconfined, "
         "between for indentation) and a lateral strain that relaxes in a hold (apparent Poisson ratio "
         "falling); on force data of one rig it looks like one more Prony term"});
    v.push_back({"contact_offset", x, "contact starts at d0: d_sample = d - d0, zero force before",
                 "a residual at the start of loading (toe region) and a strain-shaped error at small depth"});
    v.push_back({"force_offset", x, "the load cell reads F + F0",
                 "a constant residual, visible where the force is zero (before contact, after unloading)"});
    v.push_back({"force_drift", x, "the load cell reads F + r t",
                 "a residual linear in time within each test, present where the force is zero too"});
    v.push_back({"displacement_drift", x, "the sample sees d + v t while d is recorded",
                 "a residual proportional to the stiffness times t: largest in long holds at high force"});
    v.push_back(
        {"instrument_compliance", x, "the frame deflects c F: d_sample + c F(d_sample) = d",
         "the model too stiff where the force is high: residual growing with force, softer-looking curve"});
    v.push_back(
        {"platen_friction", g,
         "bonded fraction phi of the platens: force x (1 + 2 phi S^2), S = current loaded / free area",
         "a compression residual growing faster than the strain (barrelling stiffens at large strain)"});
    v.push_back(
        {"finite_layer_thickness", g,
         "the half-space is a bonded layer of thickness h: Hertz force x the Dimitriadis factor",
         "an indentation residual growing with depth beyond d^{3/2}: the support stiffens deep indents"});
    return v;
  }();
}

EffectInfo effect_info(const std::string& name) {
  const std::vector<EffectInfo> lib = effect_library();
  for (const auto& e : lib)
    if (e.name == name) return e;
  std::vector<std::string> names;
  for (const auto& e : lib) names.push_back(e.name);
  throw Error("discover: unknown effect '" + name + "' (known: " + choice_list(names) + ")");
}

std::optional<MaterialLaw> effect_law(const std::string& effect) {
  const std::string suffix = "_hyperelastic";
  if (effect.size() > suffix.size() &&
      effect.compare(effect.size() - suffix.size(), suffix.size(), suffix) == 0)
    return material_law_from_string(effect.substr(0, effect.size() - suffix.size()));
  return std::nullopt;
}

std::size_t Prepared::size() const {
  std::size_t n = 0;
  for (const auto& s : series) n += s.t.size();
  return n;
}

Prepared prepare(const DataSet& data, std::size_t max_samples) {
  Prepared p;
  const Metadata& m = data.meta;
  p.name = m.name;
  if (data.tests.empty()) throw Error(m.name + ": the data set has no tests");
  if (m.test == TestType::indentation) {
    if (!m.indenter) throw Error(m.name + ": indentation data without an indenter");
    if (m.indenter->shape == IndenterShape::cylinder)
      throw Error(m.name + ": no forward model for a cylinder indenter on its side (sphere or flat punch)");
    p.rig = m.indenter->shape == IndenterShape::sphere ? Rig::sphere : Rig::punch;
    p.radius = m.indenter->radius_m;
    if (m.sample.shape != SampleShape::half_space && p.rig == Rig::sphere) {
      p.layer = m.sample.shape == SampleShape::block ? m.sample.size_m[2] : m.sample.height_m;
      p.layer_bonded = m.sample.bottom != Interface::frictionless;
    }
    p.strain_scale = 1.0 / p.radius;
  } else {
    p.rig = m.test == TestType::confined_compression ? Rig::platen_confined
            : m.test == TestType::uniaxial_tension   ? Rig::tension
                                                     : Rig::platen_unconfined;
    p.sign = m.test == TestType::uniaxial_tension ? -1.0 : 1.0;
    const Sample& s = m.sample;
    double perimeter = 0.0;
    if (s.shape == SampleShape::cylinder) {
      p.height = s.height_m;
      p.area = kPi * s.radius_m * s.radius_m;
      perimeter = 2.0 * kPi * s.radius_m;
    } else if (s.shape == SampleShape::block) {
      p.height = s.size_m[2];
      p.area = s.size_m[0] * s.size_m[1];
      perimeter = 2.0 * (s.size_m[0] + s.size_m[1]);
    } else {
      throw Error(m.name + ": a " + to_string(m.test) + " test needs a block or cylinder sample");
    }
    if (!(p.height > 0.0) || !(p.area > 0.0))
      throw Error(m.name + ": sample height and area must be positive");
    p.shape_factor = p.area / (perimeter * p.height);
    p.strain_scale = 1.0 / p.height;
  }
  std::size_t total = 0;
  for (const auto& t : data.tests) total += t.size();
  p.stride = std::max<std::size_t>(1, (total + max_samples - 1) / std::max<std::size_t>(1, max_samples));
  p.min_dt = kInf;
  for (std::size_t k = 0; k < data.tests.size(); ++k) {
    const Test& t = data.tests[k];
    if (t.size() < 2) throw Error(m.name + ": test " + std::to_string(k + 1) + " has fewer than 2 samples");
    Series s;
    s.id = t.id.empty() ? std::to_string(k + 1) : t.id;
    for (std::size_t i = 0; i < t.size(); ++i) {
      if (i % p.stride != 0 && i + 1 != t.size()) continue;
      if (p.height > 0.0 && p.sign * t.displacement_m[i] >= p.height)
        throw Error(m.name + ": test '" + s.id + "' sample " + std::to_string(i + 1) +
                    ": the platen displacement reaches the sample height");
      s.t.push_back(t.time_s[i] - t.time_s.front());
      s.d.push_back(t.displacement_m[i]);
      s.f.push_back(t.force_N[i]);
      p.peak_force = std::max(p.peak_force, std::abs(t.force_N[i]));
      p.max_depth = std::max(p.max_depth, std::abs(t.displacement_m[i]));
    }
    for (std::size_t i = 1; i < s.t.size(); ++i) p.min_dt = std::min(p.min_dt, s.t[i] - s.t[i - 1]);
    p.duration = std::max(p.duration, s.t.back());
    p.series.push_back(std::move(s));
  }
  if (!(p.peak_force > 0.0)) throw Error(m.name + ": the force is zero everywhere (nothing to discover)");
  if (!(p.max_depth > 0.0)) throw Error(m.name + ": the displacement is zero everywhere");
  if (p.layer > 0.0 && std::sqrt(p.radius * p.max_depth) > p.layer)
    throw Error(m.name + ": contact radius sqrt(R d) exceeds the layer thickness: outside the closed form");
  return p;
}

bool Structure::has(const std::string& e) const {
  return std::find(effects.begin(), effects.end(), e) != effects.end();
}

std::string Structure::label() const {
  std::string s = to_string(law) + (prony_terms ? "+prony:" + std::to_string(prony_terms) : "");
  for (const auto& e : effects) s += " + " + e;
  return s;
}

fit::ModelSpec model_spec(const Structure& s) { return spec_of(s); }

std::vector<std::string> effects_in(const Structure& s, const Structure& baseline) {
  std::vector<std::string> out;
  if (s.law != baseline.law) out.push_back(to_string(s.law) + "_hyperelastic");
  for (int i = baseline.prony_terms; i < s.prony_terms; ++i) out.push_back("extra_prony_term");
  for (const auto& e : s.effects)
    if (!baseline.has(e)) out.push_back(e);
  return out;
}

Structure with_effect(const Structure& s, const std::string& effect) {
  Structure out = s;
  if (const std::optional<MaterialLaw> law = effect_law(effect))
    out.law = *law;
  else if (effect == "extra_prony_term")
    out.prony_terms += 1;
  else
    out.effects.push_back(effect);
  return out;
}

std::string not_applicable(const std::string& effect, const Structure& s, const Prepared& p) {
  effect_info(effect);
  const bool platen =
      p.rig == Rig::platen_unconfined || p.rig == Rig::platen_confined || p.rig == Rig::tension;
  if (const std::optional<MaterialLaw> law = effect_law(effect)) {
    if (!platen) return "the indentation closed forms see only the small-strain modulus (needs the FE rig)";
    if (*law == s.law) return "already the law";
    return "";
  }
  if (effect == "extra_prony_term") return s.prony_terms >= 4 ? "four Prony terms already" : "";
  if (s.has(effect)) return "already added";
  if (effect == "strain_dependent_relaxation" && s.prony_terms == 0)
    return "no Prony terms to make strain-dependent";
  if (effect == "separate_bulk_shear_relaxation")
    return "on force data of one rig, bulk relaxation is one more exponential of the rig modulus "
           "(correspondence principle): confounded with extra_prony_term; separating them needs the lateral "
           "strain of an unconfined test or two rigs on one sample, which the loop does not read";
  if (effect == "poroelastic_relaxation" && platen)
    return "one sample size on platen data: tau = L^2/D is one more Prony term (indentation only)";
  if (effect == "platen_friction" && p.rig != Rig::platen_unconfined)
    return "barrelling needs unconfined compression";
  if (effect == "finite_layer_thickness" && (p.rig != Rig::sphere || p.layer > 0.0))
    return p.rig != Rig::sphere ? "sphere indentation only" : "the metadata already gives the layer";
  return "";
}

std::vector<fit::Parameter> structure_parameters(const Structure& s, const Prepared& p, double poisson,
                                                 bool fix_poisson, const Structure* previous,
                                                 const std::vector<double>* previous_values) {
  // The starting modulus: the previous model's small-strain modulus, else an estimate from the data.
  double modulus = 0.0;
  if (previous && previous_values)
    modulus = fit::small_strain_young_poisson(spec_of(*previous), *previous_values).first;
  if (!(modulus > 0.0)) {
    if (p.rig == Rig::sphere || p.rig == Rig::punch) {
      for (const auto& se : p.series) {
        std::size_t k = 0;
        for (std::size_t i = 0; i < se.f.size(); ++i)
          if (se.f[i] >= se.f[k]) k = i;
        const double dp = se.d[k], fp = se.f[k];
        if (dp > 0.0 && fp > 0.0)
          modulus = std::max(
              modulus, (p.rig == Rig::sphere ? 3.0 * fp / (4.0 * std::sqrt(p.radius) * dp * std::sqrt(dp))
                                             : fp / (2.0 * p.radius * dp)) *
                           (1.0 - poisson * poisson));
      }
    } else {
      double ss = 0.0, se2 = 0.0;
      const double emax = p.max_depth / p.height;
      for (const auto& se : p.series)
        for (std::size_t i = 0; i < se.d.size(); ++i) {
          const double e = se.d[i] / p.height;
          if (std::abs(e) <= 0.3 * emax) {
            ss += e * se.f[i] / p.area;
            se2 += e * e;
          }
        }
      modulus = se2 > 0.0 ? ss / se2 : 0.0;
      if (!(modulus > 0.0)) modulus = p.peak_force / p.area / emax;
    }
    // The relaxing part makes the measured stiffness larger than E_inf.
    if (s.prony_terms > 0) modulus *= 0.7;
  }
  if (!(modulus > 0.0) || !std::isfinite(modulus))
    throw Error(p.name + ": no positive modulus estimate (is the force positive when the sample is loaded?)");
  const auto [ta, tb] = tau_range(p);
  std::vector<fit::Parameter> v = fit::law_parameters(spec_of(s), modulus, p.duration);
  // Relaxation times spread log-uniformly over what the data resolve; starts over the whole range.
  // A relaxation time is bounded by the longest test: a term that has not decayed by the end of
  // the data is elastic stiffness, confounded with E_inf (without the bound a St VK baseline on
  // stiffening data put its stiffness into a term at tau ~ 1e13 s with E_inf ~ 0.01 Pa, and a law
  // swapped in from there started at that E_inf and could not leave: docs/discover.md section 1).
  const std::size_t m = std::size_t(s.prony_terms), first = v.size() - 2 * m;
  for (std::size_t j = 0; j < m; ++j) {
    fit::Parameter& e = v[first + j];
    e.value = 0.3 * modulus / double(m);
    e.start_low = 0.01 * modulus;
    e.start_high = 2.0 * modulus;
    fit::Parameter& tau = v[first + m + j];
    tau.value = std::exp(std::log(ta) + (double(j) + 0.5) / double(m) * (std::log(tb) - std::log(ta)));
    tau.upper = tb;
    tau.start_low = ta;
    tau.start_high = 0.999 * tb;
  }
  const double fpk = p.peak_force, dmx = p.max_depth, T = std::max(p.duration, 1e-9);
  double emax = p.max_depth * p.strain_scale;
  for (const auto& e : s.effects) {
    if (e == "strain_dependent_relaxation") {
      v.push_back(param("relax_strain_slope", "1", 0.0, -0.99 / emax, 50.0 / emax, -0.5 / emax, 2.0 / emax));
    } else if (e == "poroelastic_relaxation") {
      v.push_back(param("e_poro", "Pa", 0.2 * modulus, 0.0, kInf, 0.02 * modulus, 2.0 * modulus));
      const double l = poro_length(p, 0);
      v.push_back(
          param("diffusivity", "m2/s", l * l / std::sqrt(ta * tb), 0.0, kInf, l * l / tb, l * l / ta));
    } else if (e == "separate_bulk_shear_relaxation") {
      const double nu0 = std::min(poisson, 0.499);
      v.push_back(param("drained_poisson", "1", 0.5 * nu0, 0.0, nu0, 0.1 * nu0, 0.9 * nu0));
      const double mid = std::sqrt(ta * tb);
      v.push_back(param("tau_bulk", "s", mid, ta, tb, ta, tb));
    } else if (e == "contact_offset") {
      v.push_back(param("contact_offset", "m", 0.0, -0.3 * dmx, 0.5 * dmx, -0.05 * dmx, 0.05 * dmx));
    } else if (e == "force_offset") {
      v.push_back(param("force_offset", "N", 0.0, -kInf, kInf, -0.02 * fpk, 0.02 * fpk));
    } else if (e == "force_drift") {
      v.push_back(param("force_drift", "N/s", 0.0, -kInf, kInf, -0.02 * fpk / T, 0.02 * fpk / T));
    } else if (e == "displacement_drift") {
      v.push_back(param("displacement_drift", "m/s", 0.0, -kInf, kInf, -0.02 * dmx / T, 0.02 * dmx / T));
    } else if (e == "instrument_compliance") {
      const double c = dmx / fpk;
      v.push_back(param("compliance", "m/N", 0.01 * c, 0.0, 2.0 * c, 1e-3 * c, 0.2 * c));
    } else if (e == "platen_friction") {
      v.push_back(param("friction_fraction", "1", 0.1, 0.0, 1.0, 0.01, 0.9));
    } else if (e == "finite_layer_thickness") {
      const double a = std::sqrt(p.radius * dmx);
      v.push_back(param("layer_thickness", "m", 3.0 * a, 1.001 * a, kInf, 1.2 * a, 20.0 * a));
    }
  }
  // A new Prony term starts in the widest gap (in log tau) the other terms leave.
  if (previous && previous_values && s.prony_terms > previous->prony_terms && s.law == previous->law) {
    std::vector<double> taus = {ta, tb};
    const std::vector<fit::Parameter> prev = structure_parameters(*previous, p, poisson, fix_poisson);
    for (std::size_t i = 0; i < prev.size(); ++i) {
      const double t = (*previous_values)[i];
      if (prev[i].name.rfind("tau", 0) == 0 && t > ta && t < tb) taus.push_back(t);  // live terms only
    }
    std::sort(taus.begin(), taus.end());
    double best = -1.0, mid = std::sqrt(ta * tb);
    for (std::size_t i = 1; i < taus.size(); ++i)
      if (taus[i] > 0.0 && taus[i - 1] > 0.0 && std::log(taus[i] / taus[i - 1]) > best) {
        best = std::log(taus[i] / taus[i - 1]);
        mid = std::sqrt(taus[i] * taus[i - 1]);
      }
    const std::string tn = "tau" + std::to_string(s.prony_terms), en = "e" + std::to_string(s.prony_terms);
    for (auto& q : v) {
      if (q.name == tn) q.value = std::clamp(mid, ta * 1.0001, tb * 0.9999);
      if (q.name == en) q.value = 0.1 * modulus;
    }
  }
  // Values carried over by name from the previous model (a model with one more Prony term keeps
  // the old terms under their names; the new one keeps the gap start above). A value pinned at a
  // bound is not carried over (pinned_at_bound): the fit could not move it from there.
  if (previous && previous_values) {
    const std::vector<fit::Parameter> prev = structure_parameters(*previous, p, poisson, fix_poisson);
    for (auto& q : v)
      for (std::size_t i = 0; i < prev.size(); ++i) {
        const double x = (*previous_values)[i];
        if (prev[i].name == q.name && x > q.lower && x < q.upper && !pinned_at_bound(q, x)) q.value = x;
      }
  }
  for (auto& q : v) {
    if (q.name == "poisson") {
      q.value = poisson;
      q.fixed = fix_poisson;
    }
    q.start_low = std::min(q.start_low, q.value);
    q.start_high = std::max(q.start_high, q.value);
    if (q.start_low <= q.lower) q.start_low = q.value;
    if (q.start_high >= q.upper) q.start_high = q.value;
  }
  fit::validate(v);
  return v;
}

DiscoverModel::DiscoverModel(const Prepared& p, Structure s, std::vector<char> mask)
    : p_(&p), s_(std::move(s)), mask_(std::move(mask)) {
  if (!mask_.empty() && mask_.size() != p.size()) throw Error("discover: mask size does not match the data");
}

std::string DiscoverModel::name() const { return "qlv_" + to_string(p_->rig); }

std::string DiscoverModel::description() const {
  return s_.label() + ": the long-term elastic force of " + to_string(p_->rig) +
         " run through the Prony hereditary integral (exact-linear steps), then the experiment effects";
}

std::string exactness(const Prepared& p) {
  switch (p.rig) {
    case Rig::platen_unconfined:
    case Rig::tension:
      return "homogeneous state of the law (closed_forms::platen_state): exact for frictionless platens; "
             "bonded platens barrel, which only the platen_friction effect approximates (Gent-Lindley shape "
             "factor); the hereditary integral acts on the platen force (nu fixed), as in the tensor-mass "
             "Prony model (docs/theory/viscoelasticity.md section 2)";
    case Rig::platen_confined:
      return "homogeneous confined state of the law: exact for frictionless walls and platens; hereditary "
             "integral on the platen force";
    case Rig::sphere:
      return "Hertz (x the Dimitriadis layer factor) through the hereditary integral = Lee-Radok: exact for "
             "shallow indentation of a linear (visco)elastic half-space while the depth does not decrease; "
             "unloading and deep indentation need the FE rig";
    case Rig::punch:
      return "Sneddon through the hereditary integral = Lee-Radok punch: exact for a linear (visco)elastic "
             "half-space in full contact";
  }
  return "";
}

namespace {

/// The root of g(xs) = xs + c F(xs) - d1 (strictly increasing) by secant iterations from `start`:
/// the sample displacement under instrument compliance c. `scale` sets the tolerance.
double compliance_root(const std::function<double(double)>& g, double start, double scale, double t) {
  double a = start, ga = g(a);
  double b = a - ga, gb = g(b);
  int it = 0;
  while (std::abs(gb) > 1e-12 * scale && it < 60) {
    const double den = gb - ga;
    const double nb = den != 0.0 ? b - gb * (b - a) / den : b - gb;
    a = b;
    ga = gb;
    b = nb;
    gb = g(b);
    ++it;
  }
  if (!(std::abs(gb) <= 1e-9 * scale))
    throw Error("discover: instrument compliance: no sample displacement found at t = " + significant(t, 6));
  return b;
}

}  // namespace

std::vector<std::vector<double>> DiscoverModel::predict_series(const std::vector<double>& x) const {
  const Prepared& p = *p_;
  const fit::ModelSpec spec = spec_of(s_);
  const auto [young, nu] = fit::small_strain_young_poisson(spec, x);
  const bool platen =
      p.rig == Rig::platen_unconfined || p.rig == Rig::platen_confined || p.rig == Rig::tension;
  std::optional<tm::Law> law;
  if (platen) law = fit::build_law(spec, x);
  const closed_forms::PlatenTest test = p.rig == Rig::platen_confined ? closed_forms::PlatenTest::Confined
                                                                      : closed_forms::PlatenTest::Unconfined;
  // Parameter offsets: the law's parameters, poisson, e_1..e_M, tau_1..tau_M, then each effect's.
  const std::size_t m = std::size_t(s_.prony_terms);
  std::size_t pos = fit::law_parameters(spec, 1.0, 1.0).size();
  const std::size_t first = pos - 2 * m;
  std::vector<double> alpha(m), tau(m);
  for (std::size_t j = 0; j < m; ++j) {
    alpha[j] = x[first + j] / young;
    tau[j] = x[first + m + j];
  }
  double slope = 0.0, alpha_p = 0.0, diff = 0.0, d0 = 0.0, f0 = 0.0, fr = 0.0, dv = 0.0, c = 0.0, phi = 0.0,
         layer = p.layer;
  double nu_drained = nu, tau_bulk = 1.0;
  bool poro = false, bulk = false, layer_bonded = p.layer_bonded;
  for (const auto& e : s_.effects) {
    const double v = x[pos];
    if (e == "strain_dependent_relaxation") slope = v;
    if (e == "poroelastic_relaxation") {
      poro = true;
      alpha_p = v / young;
      diff = x[pos + 1];
    }
    if (e == "separate_bulk_shear_relaxation") {
      bulk = true;
      nu_drained = v;
      tau_bulk = x[pos + 1];
    }
    if (e == "contact_offset") d0 = v;
    if (e == "force_offset") f0 = v;
    if (e == "force_drift") fr = v;
    if (e == "displacement_drift") dv = v;
    if (e == "instrument_compliance") c = v;
    if (e == "platen_friction") phi = v;
    if (e == "finite_layer_thickness") {
      layer = v;
      layer_bonded = true;
    }
    pos += effect_parameter_names(e).size();
  }
  const auto elastic = [&](double xs) -> double {
    if (p.sign * xs <= 0.0) return 0.0;  // no contact (compression) or slack (tension)
    if (platen) {
      const closed_forms::PlatenState st = closed_forms::platen_state(*law, test, p.height, p.area, xs);
      double f = st.force;
      if (phi > 0.0) {
        const double sf = p.shape_factor * st.lateral_stretch / st.stretch;
        f *= 1.0 + 2.0 * phi * sf * sf;
      }
      return f;
    }
    if (p.rig == Rig::punch) return closed_forms::sneddon_force(young, nu, p.radius, xs);
    double f = closed_forms::hertz_force(young, nu, p.radius, xs);
    if (layer > 0.0)
      f *= closed_forms::finite_layer_factor(
          nu, p.radius, xs, layer,
          layer_bonded ? closed_forms::LayerSupport::Bonded : closed_forms::LayerSupport::Frictionless);
    return f;
  };
  if (bulk && slope != 0.0)
    throw Error("discover: separate_bulk_shear_relaxation with strain_dependent_relaxation is not modelled");
  const BulkShearRig bulk_rig = p.rig == Rig::platen_confined ? BulkShearRig::confined
                                : platen                      ? BulkShearRig::uniaxial_stress
                                                              : BulkShearRig::indentation;
  std::vector<std::vector<double>> out;
  for (std::size_t k = 0; k < p.series.size(); ++k) {
    const Series& se = p.series[k];
    // Separate bulk and shear relaxation replaces the Prony sum (bulk_shear.hpp).
    std::optional<BulkShearRelaxation> bs;
    if (bulk) bs.emplace(bulk_rig, alpha, tau, nu, nu_drained, tau_bulk);
    const double tau_p = poro ? std::pow(poro_length(p, k), 2) / diff : 1.0;
    std::vector<double> h(m, 0.0);
    double hp = 0.0, xe_prev = 0.0, xs_prev = 0.0, d1_prev = 0.0;
    std::vector<double> f(se.t.size());
    for (std::size_t i = 0; i < se.t.size(); ++i) {
      const double t = se.t[i];
      const double dt = i > 0 ? t - se.t[i - 1] : 0.0;
      std::vector<double> decay(m, 0.0), beta(m, 1.0);
      for (std::size_t j = 0; j < m; ++j)
        if (i > 0) {
          const double r = dt / tau[j];
          decay[j] = std::exp(-r);
          beta[j] = r > 1e-8 ? (1.0 - decay[j]) / r : 1.0 - 0.5 * r;
        }
      double pdecay = 0.0, pbeta = 1.0;
      if (poro && i > 0) {
        const double r = dt / tau_p;
        pdecay = std::exp(-r);
        pbeta = r > 1e-8 ? (1.0 - pdecay) / r : 1.0 - 0.5 * r;
      }
      // Force of the sample at displacement xs given the state at the previous sample.
      const auto force = [&](double xs, double& xe, std::vector<double>& hn, double& hpn) {
        xe = elastic(xs);
        const double dxe = i > 0 ? xe - xe_prev : xe;  // a start with a jump: h = X_e(0+)
        const double w = 1.0 + slope * std::abs(xs) * p.strain_scale;
        double fv = xe;
        for (std::size_t j = 0; j < m; ++j) {
          hn[j] = decay[j] * h[j] + beta[j] * dxe;
          fv += alpha[j] * w * hn[j];
        }
        if (bs) fv = bs->step(dt, xe);
        hpn = pdecay * hp + pbeta * dxe;
        fv += alpha_p * hpn;
        return fv;
      };
      const double d1 = se.d[i] - d0 + dv * t;
      double xe = 0.0, hpn = 0.0, fs = 0.0, xs = d1;
      std::vector<double> hn(m);
      if (c > 0.0) {
        // d1 = xs + c F(xs): the sample's share of the measured displacement.
        const auto g = [&](double v) { return v + c * force(v, xe, hn, hpn) - d1; };
        xs = compliance_root(g, i > 0 ? xs_prev + (d1 - d1_prev) : d1, std::max(p.max_depth, 1e-12), t);
      }
      fs = force(xs, xe, hn, hpn);
      if (bs) bs->commit();
      h = hn;
      hp = hpn;
      xe_prev = xe;
      xs_prev = xs;
      d1_prev = d1;
      f[i] = fs + f0 + fr * t;
      if (!std::isfinite(f[i])) throw Error("discover: the forward model is not finite here");
    }
    out.push_back(std::move(f));
  }
  return out;
}

std::vector<double> DiscoverModel::predict(const std::vector<double>& x) const {
  const auto all = predict_series(x);
  std::vector<double> out;
  std::size_t idx = 0;
  for (const auto& f : all)
    for (const double v : f) {
      if (mask_.empty() || mask_[idx]) out.push_back(v);
      ++idx;
    }
  return out;
}

fit::Observations observations(const Prepared& p, const std::vector<char>& mask) {
  fit::Observations o;
  std::size_t idx = 0;
  for (std::size_t k = 0; k < p.series.size(); ++k) {
    o.test_ids.push_back(p.series[k].id);
    o.weights.push_back(1.0);
    for (const double f : p.series[k].f) {
      if (mask.empty() || mask[idx]) {
        o.force.push_back(f);
        o.test.push_back(k);
        o.peak_force = std::max(o.peak_force, std::abs(f));
      }
      ++idx;
    }
  }
  return o;
}

std::vector<double> canonical(const Structure& s, const std::vector<fit::Parameter>& params,
                              std::vector<double> x) {
  const std::size_t m = std::size_t(s.prony_terms);
  if (m < 2) return x;
  std::size_t first = 0;
  for (std::size_t i = 0; i < params.size(); ++i)
    if (params[i].name == "e1") first = i;
  for (std::size_t i = first; i < first + 2 * m; ++i)
    if (params[i].fixed) return x;
  std::vector<std::size_t> o(m);
  std::iota(o.begin(), o.end(), 0);
  std::stable_sort(o.begin(), o.end(),
                   [&](std::size_t a, std::size_t b) { return x[first + m + a] < x[first + m + b]; });
  std::vector<double> e(m), t(m);
  for (std::size_t j = 0; j < m; ++j) {
    e[j] = x[first + o[j]];
    t[j] = x[first + m + o[j]];
  }
  for (std::size_t j = 0; j < m; ++j) {
    x[first + j] = e[j];
    x[first + m + j] = t[j];
  }
  return x;
}

}  // namespace tmlab::discover
