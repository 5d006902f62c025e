#include "calibration/fit/surrogates.hpp"

#include "calibration/closed_forms/homogeneous.hpp"
#include "calibration/closed_forms/indentation.hpp"
#include "calibration/data/sign_convention.hpp"
#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/constitutive/law_catalogue.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

namespace tmlab::fit {

namespace {

using namespace tmlab::measured;
constexpr double kPi = 3.14159265358979323846;

std::string test_name(const DataSet& d, std::size_t k) {
  const Test& t = d.tests[k];
  return d.meta.name + ": test " + (t.id.empty() ? std::to_string(k + 1) : "'" + t.id + "'");
}
std::string sample_where(const DataSet& d, std::size_t k, std::size_t i) {
  const Test& t = d.tests[k];
  std::string s = test_name(d, k) + ", sample " + std::to_string(i + 1);
  if (t.first_line > 0) s += " (line " + std::to_string(t.first_line + long(i)) + ")";
  return s;
}

/// Indentation by a sphere or a flat punch: Hertz/Sneddon, or Lee-Radok with Prony terms.
class IndentationModel final : public ForwardModel {
 public:
  IndentationModel(const DataSet& d, ModelSpec spec) : spec_(std::move(spec)) {
    const Indenter& ind = *d.meta.indenter;
    sphere_ = ind.shape == IndenterShape::sphere;
    radius_ = ind.radius_m;
    const Sample& s = d.meta.sample;
    if (sphere_ && s.shape != SampleShape::half_space) {
      thickness_ = s.shape == SampleShape::block ? s.size_m[2] : s.height_m;
      support_ = s.bottom == Interface::frictionless ? closed_forms::LayerSupport::Frictionless
                                                     : closed_forms::LayerSupport::Bonded;
    }
    for (const Test& t : d.tests) {
      closed_forms::DepthHistory h;
      for (std::size_t i = 0; i < t.size(); ++i) {
        h.t.push_back(t.time_s[i] - t.time_s.front());
        h.d.push_back(t.displacement_m[i]);
      }
      histories_.push_back(std::move(h));
    }
  }
  std::string name() const override {
    return std::string(spec_.prony_terms ? "lee_radok_" : (sphere_ ? "hertz_" : "sneddon_")) +
           (sphere_ ? "sphere" : "punch");
  }
  std::string description() const override {
    std::string s =
        sphere_ ? (spec_.prony_terms ? "Lee-Radok sphere indentation (exact hereditary integral)"
                                     : "Hertz sphere indentation")
                : (spec_.prony_terms ? "Lee-Radok flat-punch indentation" : "Sneddon flat-punch indentation");
    if (thickness_ > 0.0)
      s += " times the Dimitriadis finite-layer factor (" +
           std::string(support_ == closed_forms::LayerSupport::Bonded ? "bonded" : "frictionless") +
           " layer" + (spec_.prony_terms ? ", evaluated at the current depth: an approximation" : "") + ")";
    return s + "; linear elastic: exact for shallow indentation, sees only the small-strain modulus";
  }
  std::vector<double> predict(const std::vector<double>& x) const override {
    const auto [young, nu] = small_strain_young_poisson(spec_, x);
    closed_forms::RelaxationModulus e;
    e.e_inf = young;
    std::tie(e.moduli, e.taus) = prony_terms(spec_, x);
    std::vector<double> out;
    for (const auto& h : histories_) {
      std::vector<double> f;
      if (spec_.prony_terms == 0) {
        for (const double d : h.d)
          f.push_back(sphere_ ? closed_forms::hertz_force(young, nu, radius_, d)
                              : closed_forms::sneddon_force(young, nu, radius_, d));
      } else {
        f = sphere_ ? closed_forms::lee_radok_sphere(e, nu, radius_, h)
                    : closed_forms::lee_radok_punch(e, nu, radius_, h);
      }
      if (thickness_ > 0.0)
        for (std::size_t i = 0; i < f.size(); ++i)
          if (h.d[i] > 0.0)
            f[i] *= closed_forms::finite_layer_factor(nu, radius_, h.d[i], thickness_, support_);
      out.insert(out.end(), f.begin(), f.end());
    }
    return out;
  }

 private:
  ModelSpec spec_;
  bool sphere_ = true;
  double radius_ = 0.0, thickness_ = 0.0;
  closed_forms::LayerSupport support_ = closed_forms::LayerSupport::Bonded;
  std::vector<closed_forms::DepthHistory> histories_;
};

/// Homogeneous platen test of the hyperelastic law.
class PlatenModel final : public ForwardModel {
 public:
  PlatenModel(const DataSet& d, ModelSpec spec, double height, double area)
      : spec_(std::move(spec)), height_(height), area_(area) {
    test_ = d.meta.test == TestType::confined_compression ? closed_forms::PlatenTest::Confined
                                                          : closed_forms::PlatenTest::Unconfined;
    bonded_ = d.meta.sample.platens == Interface::bonded;
    for (const Test& t : d.tests)
      displacement_.insert(displacement_.end(), t.displacement_m.begin(), t.displacement_m.end());
  }
  std::string name() const override {
    return test_ == closed_forms::PlatenTest::Confined ? "platen_confined" : "platen_unconfined";
  }
  std::string description() const override {
    return std::string("homogeneous ") +
           (test_ == closed_forms::PlatenTest::Confined ? "confined compression"
                                                        : "uniaxial compression/tension") +
           " of the hyperelastic law (exact for frictionless platens" +
           (bonded_ ? "; the data's platens are bonded, so this is only the frictionless bound" : "") + ")";
  }
  std::vector<double> predict(const std::vector<double>& x) const override {
    const tm::Law law = build_law(spec_, x);
    std::vector<double> out;
    out.reserve(displacement_.size());
    for (const double d : displacement_)
      out.push_back(closed_forms::platen_state(law, test_, height_, area_, d).force);
    return out;
  }

 private:
  ModelSpec spec_;
  double height_, area_;
  closed_forms::PlatenTest test_ = closed_forms::PlatenTest::Unconfined;
  bool bonded_ = false;
  std::vector<double> displacement_;
};

/// Prony terms (e_i, tau_i) sorted by tau, Ogden terms (mu_p, alpha_p) by alpha: each set of terms
/// is exchangeable, so the same fit could be reported in any order. Terms are only reordered when
/// none of them is fixed (a fixed value belongs to its position).
std::function<std::vector<double>(std::vector<double>)> canonical_order(
    const ModelSpec& spec, const std::vector<Parameter>& params) {
  struct Pairs {
    std::size_t first_a, first_b, count;
  };
  std::vector<Pairs> groups;
  const auto any_fixed = [&](std::size_t a, std::size_t n) {
    for (std::size_t i = a; i < a + n; ++i)
      if (params[i].fixed) return true;
    return false;
  };
  const std::size_t m = std::size_t(spec.prony_terms);
  if (m > 1) {
    const std::size_t a = params.size() - 2 * m;
    if (!any_fixed(a, 2 * m)) groups.push_back({a + m, a, m});  // sort key tau, partner e
  }
  if (law_descriptor(spec.law).has_terms() && spec.ogden_terms > 1) {  // ogden: sorted by alpha
    const std::size_t n = std::size_t(spec.ogden_terms);
    if (!any_fixed(0, 2 * n)) groups.push_back({n, 0, n});  // sort key alpha, partner mu
  }
  if (groups.empty()) return {};
  return [groups](std::vector<double> x) {
    for (const Pairs& g : groups) {
      std::vector<std::size_t> order(g.count);
      for (std::size_t i = 0; i < g.count; ++i) order[i] = i;
      std::stable_sort(order.begin(), order.end(),
                       [&](std::size_t a, std::size_t b) { return x[g.first_a + a] < x[g.first_a + b]; });
      std::vector<double> key, partner;
      for (const std::size_t i : order) {
        key.push_back(x[g.first_a + i]);
        partner.push_back(x[g.first_b + i]);
      }
      for (std::size_t i = 0; i < g.count; ++i) {
        x[g.first_a + i] = key[i];
        x[g.first_b + i] = partner[i];
      }
    }
    return x;
  };
}

/// The height and cross-section of a platen test's sample (cylinder or block); tmlab::Error naming
/// the data set `name` for a half-space.
std::pair<double, double> platen_sample(const Metadata& m, const std::string& name) {
  const Sample& s = m.sample;
  if (s.shape == SampleShape::cylinder) return {s.height_m, kPi * s.radius_m * s.radius_m};
  if (s.shape == SampleShape::block) return {s.size_m[2], s.size_m[0] * s.size_m[1]};
  throw Error(name + ": a " + to_string(m.test) +
              " test needs a finite sample (block or cylinder), not a half-space");
}

/// A parameter fixed twice, in the SPEC and by --fix or twice by --fix, is refused with both values
/// (the last one would silently win otherwise). The SPEC refuses its own repeats when it is parsed.
void refuse_fixed_twice(const ModelSpec& spec, const std::vector<std::pair<std::string, double>>& fixes) {
  for (std::size_t a = 0; a < fixes.size(); ++a) {
    const auto& [name, v] = fixes[a];
    for (const auto& [k, w] : spec.fixed)
      if (k == name)
        throw Error("'" + printable(name, 40) + "' is fixed twice: " + shortest(w) + " in --model '" +
                    printable(spec.text, 80) + "' and " + shortest(v) + " by --fix: give it once");
    for (std::size_t b = 0; b < a; ++b)
      if (fixes[b].first == name)
        throw Error("--fix " + printable(name, 40) + " is given twice (" + shortest(fixes[b].second) +
                    " and " + shortest(v) + "): give it once");
  }
}

}  // namespace

Problem make_data_problem(const DataSet& d, const ModelSpec& spec,
                          const std::vector<std::pair<std::string, double>>& fixes,
                          const std::vector<std::pair<std::string, double>>& weights) {
  const std::string& name = d.meta.name;
  if (d.tests.empty()) throw Error(name + ": the data set has no tests");
  // The sign convention first: a flipped force would otherwise be fitted, to a modulus near zero.
  check_force_sign(d, "");
  Problem pr;
  // Observations, and the checks that apply to every rig.
  double duration = 0.0;
  for (std::size_t k = 0; k < d.tests.size(); ++k) {
    const Test& t = d.tests[k];
    if (t.size() < 2) throw Error(test_name(d, k) + " has fewer than 2 samples");
    for (std::size_t i = 0; i < t.size(); ++i) {
      if (!std::isfinite(t.force_N[i]) || !std::isfinite(t.displacement_m[i]) || !std::isfinite(t.time_s[i]))
        throw Error(sample_where(d, k, i) + ": not a finite number");
      pr.data.force.push_back(t.force_N[i]);
      pr.data.test.push_back(k);
      pr.data.peak_force = std::max(pr.data.peak_force, std::abs(t.force_N[i]));
    }
    if (std::all_of(t.force_N.begin(), t.force_N.end(), [](double f) { return f == 0.0; }))
      throw Error(test_name(d, k) + ": the force is zero at every sample (nothing to fit)");
    if (std::all_of(t.displacement_m.begin(), t.displacement_m.end(), [](double u) { return u == 0.0; }))
      throw Error(test_name(d, k) + ": the displacement is zero at every sample (nothing to fit)");
    pr.data.test_ids.push_back(t.id);
    pr.data.weights.push_back(1.0);
    duration = std::max(duration, t.time_s.back() - t.time_s.front());
  }
  for (std::size_t a = 0; a < weights.size(); ++a)
    for (std::size_t b = 0; b < a; ++b)
      if (weights[b].first == weights[a].first)
        throw Error(name + ": --weight names test '" + printable(weights[a].first, 60) + "' twice (" +
                    shortest(weights[b].second) + " and " + shortest(weights[a].second) + "): give it once");
  for (const auto& [id, w] : weights) {
    const auto it = std::find(pr.data.test_ids.begin(), pr.data.test_ids.end(), id);
    if (it == pr.data.test_ids.end())
      throw Error(name + ": --weight names test '" + id + "', which the data does not have");
    if (!(w > 0.0) || !std::isfinite(w))
      throw Error(name + ": the weight of test '" + id + "' must be positive");
    pr.data.weights[std::size_t(it - pr.data.test_ids.begin())] = w;
  }

  double modulus = 0.0;
  const Metadata& m = d.meta;
  if (m.test == TestType::indentation) {
    if (!m.indenter) throw Error(name + ": indentation data without an indenter");
    if (m.indenter->shape == IndenterShape::cylinder)
      throw Error(
          name +
          ": no closed form or rig for a cylinder indenter on its side (use a sphere or a flat punch)");
    const bool sphere = m.indenter->shape == IndenterShape::sphere;
    const double r = m.indenter->radius_m;
    for (std::size_t k = 0; k < d.tests.size(); ++k) {
      const Test& t = d.tests[k];
      // The largest force (the deepest sample among equal ones).
      std::size_t peak = 0;
      for (std::size_t i = 0; i < t.size(); ++i)
        if (t.force_N[i] >= t.force_N[peak]) peak = i;
      const double dp = t.displacement_m[peak], fp = t.force_N[peak];
      if (!(dp > 0.0) || !(fp > 0.0))
        throw Error(test_name(d, k) +
                    ": the largest force is not at a positive depth (is the sign convention "
                    "'displacement positive into the sample, force positive pushing back'?)");
      const double estar =
          sphere ? 3.0 * fp / (4.0 * std::sqrt(r) * dp * std::sqrt(dp)) : fp / (2.0 * r * dp);
      modulus = std::max(modulus, estar * (1.0 - 0.45 * 0.45));
    }
  } else {
    const auto [height, area] = platen_sample(m, name);
    if (!(height > 0.0) || !(area > 0.0))
      throw Error(name + ": the sample's height and cross-section must be positive");
    double ss = 0.0, se = 0.0, emax = 0.0;
    for (std::size_t k = 0; k < d.tests.size(); ++k) {
      const Test& t = d.tests[k];
      for (std::size_t i = 0; i < t.size(); ++i) {
        if (t.displacement_m[i] >= height)
          throw Error(sample_where(d, k, i) + ": the platen displacement " +
                      significant(t.displacement_m[i] * 1e3, 5) + " mm reaches the sample height " +
                      significant(height * 1e3, 5) + " mm");
        emax = std::max(emax, std::abs(t.displacement_m[i] / height));
      }
    }
    // Small-strain slope of nominal stress against engineering strain (the first tenth of the strain range).
    for (std::size_t k = 0; k < d.tests.size(); ++k) {
      const Test& t = d.tests[k];
      for (std::size_t i = 0; i < t.size(); ++i) {
        const double e = t.displacement_m[i] / height;
        if (std::abs(e) <= 0.1 * emax) {
          ss += e * t.force_N[i] / area;
          se += e * e;
        }
      }
    }
    modulus = se > 0.0 ? ss / se : 0.0;
    if (!(modulus > 0.0)) modulus = pr.data.peak_force / area / std::max(emax, 1e-12);
    if (!(modulus > 0.0))
      throw Error(name + ": the force does not rise with the displacement (check the sign convention)");
  }
  pr.parameters = law_parameters(spec, modulus, duration);
  refuse_fixed_twice(spec, fixes);
  for (const auto& [k, v] : spec.fixed) fix(pr.parameters, k, v);
  for (const auto& [k, v] : fixes) fix(pr.parameters, k, v);
  validate(pr.parameters);
  pr.canonical = canonical_order(spec, pr.parameters);
  std::size_t free = 0;
  for (const auto& p : pr.parameters) free += p.fixed ? 0 : 1;
  if (pr.data.size() <= free)
    throw Error(name + ": " + std::to_string(pr.data.size()) + " samples for " + std::to_string(free) +
                " free parameters: more samples than parameters are needed");
  return pr;
}

std::unique_ptr<ForwardModel> make_surrogate_model(const DataSet& d, const ModelSpec& spec) {
  const std::string& name = d.meta.name;
  const Metadata& m = d.meta;
  if (m.test == TestType::indentation) {
    if (!m.indenter) throw Error(name + ": indentation data without an indenter");
    if (m.indenter->shape == IndenterShape::cylinder)
      throw Error(name +
                  ": no closed form for a cylinder indenter on its side (use a sphere or a flat punch)");
    if (law_descriptor(spec.law).bulk != BulkResponse::YoungPoisson)
      throw Error(name +
                  ": the closed-form indentation models are linear elastic and see only the small-strain "
                  "modulus; fit 'stvk' or 'neo_hookean' (E, nu and Prony terms) to indentation data with "
                  "the closed forms, or law '" +
                  to_string(spec.law) + "' with the FE rig (--forward fe_rig)");
    const bool sphere = m.indenter->shape == IndenterShape::sphere;
    const double r = m.indenter->radius_m;
    for (std::size_t k = 0; k < d.tests.size(); ++k) {
      const Test& t = d.tests[k];
      if (spec.prony_terms > 0)
        for (std::size_t i = 1; i < t.size(); ++i)
          if (t.displacement_m[i] < t.displacement_m[i - 1] && t.displacement_m[i - 1] > 0.0)
            throw Error(sample_where(d, k, i) +
                        ": the depth decreases while in contact; the Lee-Radok closed form needs loading and "
                        "hold only (drop the unloading samples, fit without Prony terms, or use the FE rig)");
      if (sphere && m.sample.shape != SampleShape::half_space) {
        const double h = m.sample.shape == SampleShape::block ? m.sample.size_m[2] : m.sample.height_m;
        const double dmax = *std::max_element(t.displacement_m.begin(), t.displacement_m.end());
        if (std::sqrt(r * dmax) > h)
          throw Error(test_name(d, k) +
                      ": contact radius sqrt(R d) = " + significant(std::sqrt(r * dmax) * 1e3, 4) +
                      " mm exceeds the layer thickness " + significant(h * 1e3, 4) +
                      " mm: outside the finite-layer closed form (shallower data or the FE rig)");
      }
    }
    return std::make_unique<IndentationModel>(d, spec);
  }
  if (spec.prony_terms > 0)
    throw Error(
        name + ": Prony terms on " + to_string(m.test) +
        " data need the FE rig forward model (--forward fe_rig); the homogeneous closed form is elastic");
  const auto [height, area] = platen_sample(m, name);
  return std::make_unique<PlatenModel>(d, spec, height, area);
}

Problem make_surrogate_problem(const DataSet& d, const ModelSpec& spec,
                               const std::vector<std::pair<std::string, double>>& fixes,
                               const std::vector<std::pair<std::string, double>>& weights) {
  Problem pr = make_data_problem(d, spec, fixes, weights);
  pr.model = make_surrogate_model(d, spec);
  return pr;
}

}  // namespace tmlab::fit
