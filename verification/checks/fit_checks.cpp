// The identification checks (issue 14, docs/identification.md, label `fit`):
//   fit.coverage     recovery as a coverage test: synthetic data from a forward model (closed form or
//                    FE rig) at known parameters plus Gaussian noise, refitted from the data's own
//                    estimate with a multi-start (or annealing) global stage, `trials` times with a
//                    fixed seed; the rate at which each true parameter lies in its reported 95 %
//                    interval, and the bias of the estimates in standard errors.
//   fit.confounding  E and nu from indentation alone: the reported |corr(E, nu)|, whether the pair
//                    is named as confounded, and whether a precise nu is claimed.
#include "calibration/fit/fitter.hpp"
#include "calibration/fit/rig_forward_model.hpp"
#include "calibration/fit/surrogates.hpp"
#include "calibration/fit/synthetic_data.hpp"
#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "verification/checks/builtin_checks.hpp"
#include "verification/checks/check_support.hpp"

#include <cmath>
#include <ostream>
#include <random>

namespace tmlab::verify {

namespace {

namespace ms = tmlab::measured;

struct Setup {
  ms::DataSet data;
  fit::ModelSpec spec;
  std::vector<std::pair<std::string, double>> truth;
  std::string forward = "closed_form";
  fit::RigForwardModelOptions fe;
};

Setup read_setup(ConfigReader& r) {
  Setup s;
  const std::string data = r.require<std::string>("data");
  if (data == "indentation") {
    s.data = fit::synthetic::indentation_data(r.require<std::vector<double>>("depths"), r.positive("t_end"),
                                              r.get<double>("thickness", 0.0));
    for (auto& t : s.data.tests)
      for (double& f : t.force_N) f = 1.0;
  } else if (data == "block_compression") {
    s.data =
        fit::synthetic::block_compression_data(r.require<std::vector<double>>("strains"), r.positive("t_end"),
                                               r.get<std::string>("platens", "frictionless") == "bonded");
  } else {
    throw r.error("data", "must be indentation or block_compression");
  }
  s.spec = fit::parse_model_spec(r.require<std::string>("spec"));
  const nlohmann::json& truth = r.raw("truth");
  for (auto it = truth.begin(); it != truth.end(); ++it)
    s.truth.emplace_back(it.key(), it.value().get<double>());
  s.forward = r.get<std::string>("forward", "closed_form");
  if (s.forward != "closed_form" && s.forward != "fe_rig")
    throw r.error("forward", "must be closed_form or fe_rig");
  if (r.has("mesh")) {
    const auto m = r.require<std::vector<int>>("mesh");
    if (m.size() != 2) throw r.error("mesh", "must be [cells, layers]");
    s.fe.mesh.cells = m[0];
    s.fe.mesh.layers = m[1];
  }
  return s;
}

fit::Problem make_problem(const Setup& s, const ms::DataSet& d,
                          const std::vector<std::pair<std::string, double>>& fixes = {}) {
  return s.forward == "fe_rig" ? fit::make_rig_forward_problem(d, s.spec, fixes, {}, s.fe)
                               : fit::make_surrogate_problem(d, s.spec, fixes);
}

/// The forces of the forward model at the true parameters.
std::vector<double> truth_forces(const Setup& s) {
  const fit::Problem p = make_problem(s, s.data, s.truth);
  std::vector<double> x;
  for (const auto& q : p.parameters) x.push_back(q.value);
  return p.model->predict(x);
}

fit::FitOptions fit_options(ConfigReader& r) {
  fit::FitOptions o;
  o.starts = r.get<int>("starts", o.starts);
  o.local_runs = r.get<int>("local_runs", o.local_runs);
  const std::string g = r.get<std::string>("global", "multistart");
  if (g == "siman")
    o.global = fit::GlobalStage::Siman;
  else if (g != "multistart")
    throw r.error("global", "must be multistart or siman");
  o.siman_evaluations = r.get<int>("siman_evaluations", o.siman_evaluations);
  o.profile = false;
  o.threads = 2;
  return o;
}

Measurements coverage(const CheckContext& ctx) {
  ConfigReader r = parameters(ctx);
  Setup s = read_setup(r);
  const double noise = r.positive("noise_fraction");
  const int trials = r.get<int>("trials", 50);
  const unsigned long seed = r.get<unsigned long>("seed", 20261125);
  fit::FitOptions o = fit_options(r);
  r.finish();
  if (trials < 1) throw Error(ctx.vcase.spec_file().string() + ": key 'parameters.trials': must be >= 1");

  const std::vector<double> clean = truth_forces(s);
  double peak = 0.0;
  for (const double v : clean) peak = std::max(peak, std::abs(v));
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss(0.0, noise * peak);
  const std::size_t m = s.truth.size();
  std::vector<int> covered(m, 0);
  std::vector<double> sum_est(m, 0.0), sum_se(m, 0.0);
  long solves = 0, surrogate_solves = 0;
  int failed = 0, fits = 0;
  std::string model_name;
  for (int trial = 0; trial < trials; ++trial) {
    std::vector<double> f = clean;
    for (double& v : f) v += gauss(rng);
    ms::DataSet d = s.data;
    fit::synthetic::set_forces(d, f);
    o.seed = seed + 1000 + unsigned(trial);
    fit::FitResult res;
    try {
      res = fit::fit(make_problem(s, d), o);
    } catch (const Error& e) {
      ++failed;
      ctx.log << "  trial " << trial << " failed: " << e.what() << "\n";
      continue;
    }
    ++fits;
    model_name = res.model_name;
    solves += res.forward_solves;
    surrogate_solves += res.global_solves;
    for (std::size_t k = 0; k < m; ++k)
      for (const auto& q : res.parameters)
        if (q.name == s.truth[k].first) {
          if (q.fixed)
            throw Error(ctx.vcase.spec_file().string() + ": key 'parameters.truth." + q.name +
                        "': the SPEC fixes this parameter");
          if (s.truth[k].second >= q.lower95 && s.truth[k].second <= q.upper95) ++covered[k];
          sum_est[k] += q.value;
          sum_se[k] += q.standard_error;
        }
    if ((trial + 1) % 10 == 0) ctx.log << "  " << trial + 1 << "/" << trials << " fits\n";
  }
  Measurements out;
  double min_rate = 1.0, max_bias = 0.0;
  for (std::size_t k = 0; k < m; ++k) {
    // Failed fits count as not covered: a fit that gives no interval covers nothing.
    const double rate = double(covered[k]) / trials;
    out.set("coverage_" + s.truth[k].first, rate);
    min_rate = std::min(min_rate, rate);
    if (fits > 0) {
      const double bias = std::abs(sum_est[k] / fits - s.truth[k].second) / (sum_se[k] / fits);
      out.set("bias_in_se_" + s.truth[k].first, bias);
      max_bias = std::max(max_bias, bias);
    }
    out.notes.push_back(s.truth[k].first + ": " + std::to_string(covered[k]) + "/" + std::to_string(trials) +
                        " inside the 95 % interval; mean estimate " +
                        significant(sum_est[k] / std::max(fits, 1), 5) + " (truth " +
                        significant(s.truth[k].second, 5) + "), mean SE " +
                        significant(sum_se[k] / std::max(fits, 1), 3));
  }
  out.set("min_coverage", min_rate);
  out.set("max_bias_in_se", max_bias);
  out.set("failed_fits", failed);
  out.set("forward_solves_per_fit", fits ? double(solves) / fits : 0.0);
  out.set("surrogate_solves_per_fit", fits ? double(surrogate_solves) / fits : 0.0);
  out.notes.push_back("forward model of the final numbers: " + model_name + "; " + std::to_string(trials) +
                      " trials, noise " + significant(100.0 * noise, 3) + " % of the peak force, seed " +
                      std::to_string(seed));
  return out;
}

Measurements confounding(const CheckContext& ctx) {
  ConfigReader r = parameters(ctx);
  Setup s = read_setup(r);
  const double noise = r.positive("noise_fraction");
  const unsigned long seed = r.get<unsigned long>("seed", 7);
  fit::FitOptions o = fit_options(r);
  o.profile = true;
  r.finish();
  std::vector<double> f = truth_forces(s);
  double peak = 0.0;
  for (const double v : f) peak = std::max(peak, std::abs(v));
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss(0.0, noise * peak);
  for (double& v : f) v += gauss(rng);
  fit::synthetic::set_forces(s.data, f);
  const fit::FitResult res = fit::fit(make_problem(s, s.data), o);
  std::size_t ie = res.free_names.size(), inu = ie;
  for (std::size_t j = 0; j < res.free_names.size(); ++j) {
    if (res.free_names[j] == "young") ie = j;
    if (res.free_names[j] == "poisson") inu = j;
  }
  if (ie == res.free_names.size() || inu == res.free_names.size())
    throw Error(ctx.vcase.spec_file().string() +
                ": key 'parameters.spec': young and poisson must both be free");
  Measurements out;
  out.set("abs_corr_young_poisson", std::abs(res.correlation[ie][inu]));
  bool named = false;
  for (const auto& c : res.confounded)
    named = named || ((c.a == "young" && c.b == "poisson") || (c.a == "poisson" && c.b == "young"));
  out.set("pair_named_confounded", named ? 1.0 : 0.0);
  for (const auto& q : res.parameters)
    if (q.name == "poisson") {
      // "Precise" = identifiable with a 95 % interval narrower than 0.1 (a fifth of nu's range).
      const bool precise = q.identifiable && std::isfinite(q.standard_error) && q.upper95 - q.lower95 < 0.1;
      out.set("precise_poisson_claimed", precise ? 1.0 : 0.0);
      out.set("poisson_interval_width",
              q.identifiable && std::isfinite(q.upper95 - q.lower95) ? q.upper95 - q.lower95 : 0.5);
      out.notes.push_back("poisson = " + significant(q.value, 4) + ", 95 % interval [" +
                          significant(q.lower95, 4) + ", " + significant(q.upper95, 4) + "], identifiable " +
                          (q.identifiable ? "yes" : "no"));
    }
  for (const auto& c : res.confounded) out.notes.push_back("confounded " + c.a + "/" + c.b + ": " + c.note);
  out.notes.push_back("forward model: " + res.model_name);
  return out;
}

}  // namespace

void register_fit_checks(CheckRegistry& registry) {
  registry.add("fit.coverage", coverage);
  registry.add("fit.confounding", confounding);
}

}  // namespace tmlab::verify
