#include "calibration/discover/discover.hpp"

#include "calibration/data/sign_convention.hpp"
#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/base/interrupt.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>

namespace tmlab::discover {

namespace {

nlohmann::json num(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json nums(const std::vector<double>& v) {
  nlohmann::json a = nlohmann::json::array();
  for (const double x : v) a.push_back(num(x));
  return a;
}

void say(const Options& o, const std::string& s) {
  if (o.progress) o.progress(s);
}

std::string list_text(const std::vector<double>& v) {
  std::string out;
  for (const double x : v) out += (out.empty() ? "" : ", ") + significant(x, 4);
  return "[" + out + "]";
}

std::vector<SeriesView> views(const Prepared& p, const std::vector<std::vector<double>>& pred) {
  std::vector<SeriesView> v;
  for (std::size_t k = 0; k < p.series.size(); ++k) {
    SeriesView s;
    s.id = p.series[k].id;
    s.t = p.series[k].t;
    s.d = p.series[k].d;
    s.force = p.series[k].f;
    for (std::size_t i = 0; i < s.t.size(); ++i) s.residual.push_back(pred[k][i] - s.force[i]);
    v.push_back(std::move(s));
  }
  return v;
}

fit::Problem problem(const Prepared& p, const Structure& s, std::vector<fit::Parameter> params,
                     const std::vector<char>& mask) {
  fit::Problem pr;
  pr.data = observations(p, mask);
  pr.model = std::make_unique<DiscoverModel>(p, s, mask);
  pr.parameters = params;
  pr.canonical = [s, params](std::vector<double> x) { return canonical(s, params, std::move(x)); };
  return pr;
}

fit::FitOptions fit_options(const Options& o, int starts) {
  fit::FitOptions f;
  f.starts = std::max(1, starts);
  f.local_runs = std::min(f.starts, starts > 8 ? 3 : 2);
  f.threads = o.threads;
  f.seed = o.seed;
  f.max_iterations = 150;
  f.profile = false;
  return f;
}

std::vector<double> values_of(const fit::FitResult& r) {
  std::vector<double> x;
  for (const auto& q : r.parameters) x.push_back(q.value);
  return x;
}

}  // namespace

fit::FitResult fit_logged(const fit::Problem& pr, const fit::FitOptions& fo, const Options& o) {
  FitLog* log = o.fit_log;
  if (!log) return fit::fit(pr, fo);
  if (log->next < log->restored.size()) {
    const FitOutcome& r = log->restored[log->next++];
    if (r.failed) throw Error(r.error);
    return r.result;
  }
  FitOutcome out;
  try {
    out.result = fit::fit(pr, fo);
  } catch (const Interrupted&) {
    throw;
  } catch (const std::exception& e) {
    out.failed = true;
    out.error = e.what();
    ++log->next;
    if (log->finished) log->finished(out);
    throw;
  }
  ++log->next;
  if (log->finished) log->finished(out);
  return out.result;
}

std::vector<std::vector<char>> held_out_folds(const Prepared& p, std::string* scheme) {
  const std::size_t n = p.size();
  std::vector<std::vector<char>> folds;
  if (p.series.size() >= 2) {
    const std::size_t nf = std::min<std::size_t>(3, p.series.size());
    for (std::size_t f = 0; f < nf; ++f) {
      std::vector<char> m;
      for (std::size_t k = 0; k < p.series.size(); ++k)
        m.insert(m.end(), p.series[k].t.size(), char(k % nf != f));
      folds.push_back(std::move(m));
    }
    if (scheme)
      *scheme = "tests left out: " + std::to_string(nf) + " folds (test k held out in fold k mod " +
                std::to_string(nf) + ")";
  } else {
    for (int f = 0; f < 2; ++f) {
      std::vector<char> m(n);
      for (std::size_t i = 0; i < n; ++i) m[i] = char(int((8 * i) / n) % 2 != f);
      folds.push_back(std::move(m));
    }
    if (scheme)
      *scheme =
          "segments left out: the one test cut into 8 time blocks, even and odd blocks held out in turn";
  }
  return folds;
}

Fitted fit_structure(const Prepared& p, const Structure& s, std::vector<fit::Parameter> params,
                     const Options& o, int starts) {
  Fitted f;
  f.structure = s;
  f.parameters = params;
  const fit::Problem pr = problem(p, s, params, {});
  f.fit = fit_logged(pr, fit_options(o, starts), o);
  f.x = values_of(f.fit);
  f.prediction = DiscoverModel(p, s).predict_series(f.x);
  f.study = study_residual(views(p, f.prediction), p.sign, p.strain_scale, o.thresholds);
  f.max_abs = f.study.max_abs;
  return f;
}

double held_out_rms(const Prepared& p, const Fitted& f, const Options& o, std::vector<double>* by_test) {
  double sse = 0.0;
  std::size_t n = 0;
  std::vector<double> test_sse(p.series.size(), 0.0);
  std::vector<std::size_t> test_n(p.series.size(), 0);
  for (const auto& mask : held_out_folds(p)) {
    std::vector<fit::Parameter> params = f.parameters;
    for (std::size_t i = 0; i < params.size(); ++i) params[i].value = f.x[i];
    for (auto& q : params) {
      q.start_low = std::min(q.start_low, q.value);
      q.start_high = std::max(q.start_high, q.value);
    }
    const fit::Problem pr = problem(p, f.structure, params, mask);
    std::vector<double> x = f.x;
    try {
      x = values_of(fit_logged(pr, fit_options(o, 1), o));
    } catch (const Interrupted&) {
      throw;  // a stop request is not a failed fold
    } catch (const Error&) {
      // The fold cannot be fitted from here: predict with the full-data optimum (conservative).
    }
    const auto pred = DiscoverModel(p, f.structure).predict_series(x);
    std::size_t idx = 0;
    for (std::size_t k = 0; k < p.series.size(); ++k)
      for (std::size_t i = 0; i < p.series[k].f.size(); ++i, ++idx)
        if (!mask[idx]) {
          const double e2 = std::pow(pred[k][i] - p.series[k].f[i], 2);
          sse += e2;
          ++n;
          test_sse[k] += e2;
          ++test_n[k];
        }
  }
  if (by_test) {
    by_test->assign(p.series.size(), kNaN);
    for (std::size_t k = 0; k < p.series.size(); ++k)
      if (test_n[k]) (*by_test)[k] = std::sqrt(test_sse[k] / double(test_n[k]));
  }
  return n ? std::sqrt(sse / double(n)) : kNaN;
}

TestScaleControl test_scale_control(const Prepared& p, const Fitted& cur) {
  TestScaleControl c;
  c.applicable = p.series.size() >= 2 && cur.prediction.size() == p.series.size();
  if (!c.applicable) return c;
  // Each test's least-squares factor s_k = <f, F> / <F, F> of the forces f on the prediction F.
  double sse = 0.0;
  std::size_t n = 0;
  for (std::size_t k = 0; k < p.series.size(); ++k) {
    const auto& f = p.series[k].f;
    const auto& F = cur.prediction[k];
    double fF = 0.0, FF = 0.0;
    for (std::size_t i = 0; i < f.size(); ++i) {
      fF += f[i] * F[i];
      FF += F[i] * F[i];
    }
    const double sk = FF > 0.0 ? fF / FF : 1.0;
    c.scale.push_back(sk);
    for (std::size_t i = 0; i < f.size(); ++i) sse += std::pow(sk * F[i] - f[i], 2);
    n += f.size();
  }
  c.rms = std::sqrt(sse / double(n));
  c.free_parameters = cur.fit.k + p.series.size();
  c.bic = double(n) * std::log(std::max(sse, 1e-300) / double(n)) +
          double(c.free_parameters) * std::log(double(n));
  const double rms2 = cur.fit.rms * cur.fit.rms, excess = rms2 - std::pow(cur.study.noise_sigma, 2);
  if (excess > 0.0) c.explained_share = (rms2 - c.rms * c.rms) / excess;
  return c;
}

namespace {
std::string control_text(const TestScaleControl& c) {
  return "the test-consistency control (the current model with one force factor per test, " +
         list_text(c.scale) + ": RMS " + significant(c.rms, 4) + " N, BIC " + significant(c.bic, 7) + ")";
}
}  // namespace

std::vector<std::string> protocol_notes(const Prepared& p) {
  std::vector<std::string> notes;
  std::size_t hold = 0, unload = 0, n = 0;
  double rmin = 1e300, rmax = 0.0;
  for (const auto& s : p.series) {
    const PhaseLabels pl = classify_phases(s.t, s.d, p.sign);
    double sum = 0.0;
    int cnt = 0;
    for (std::size_t i = 0; i < s.t.size(); ++i) {
      hold += pl.phase[i] == Phase::hold ? 1 : 0;
      unload += pl.phase[i] == Phase::unload ? 1 : 0;
      if (pl.phase[i] == Phase::ramp) {
        sum += pl.rate[i];
        ++cnt;
      }
    }
    n += s.t.size();
    if (cnt) {
      rmin = std::min(rmin, sum / cnt);
      rmax = std::max(rmax, sum / cnt);
    }
  }
  if (unload == 0 && double(hold) < 0.05 * double(n) && rmax <= 1.1 * rmin)
    notes.push_back(
        "every test is a monotonic ramp at one rate (no hold, no unloading): relaxation effects (Prony "
        "terms, "
        "strain-dependent relaxation) are confounded with the shape of the elastic law, so an accepted "
        "relaxation effect here means a better curve shape, not evidence of viscoelasticity; tests at other "
        "rates or with holds would separate them");
  if (p.series.size() == 1)
    notes.push_back(
        "one test: the held-out check leaves out time blocks of it (interpolation), a weaker check than "
        "leaving out whole tests");
  return notes;
}

std::string stride_text(std::size_t stride) {
  if (stride <= 1) return "all samples kept";
  const std::size_t tens = stride % 100, last = stride % 10;
  const char* suffix = (tens >= 11 && tens <= 13) ? "th"
                       : last == 1                ? "st"
                       : last == 2                ? "nd"
                       : last == 3                ? "rd"
                                                  : "th";
  return "every " + std::to_string(stride) + suffix + " sample kept";
}

namespace {
/// Structure `s` fitted from the optimum `start` (the parameters they share start there).
Fitted fit_from(const Prepared& p, const Structure& s, const Fitted& start, const Options& o) {
  return fit_structure(p, s, structure_parameters(s, p, o.poisson, o.fix_poisson, &start.structure, &start.x),
                       o, o.starts);
}
}  // namespace

Fitted refit_from(const Prepared& p, const Fitted& cur, const Fitted& c, const Options& o) {
  return fit_from(p, cur.structure, c, o);
}

Structure without_effect(const Structure& s, const std::string& effect, const Structure& baseline) {
  Structure out = s;
  if (effect_law(effect) && s.law != baseline.law && effect_law(effect) == s.law) {
    out.law = baseline.law;
  } else if (effect == "extra_prony_term" && s.prony_terms > baseline.prony_terms) {
    out.prony_terms -= 1;
  } else {
    const auto it = std::find(out.effects.begin(), out.effects.end(), effect);
    if (it == out.effects.end() || baseline.has(effect))
      throw Error("discover: " + s.label() + " has no '" + effect + "' beyond " + baseline.label() +
                  " to remove");
    out.effects.erase(it);
  }
  return out;
}

std::vector<std::string> backward_step(const Prepared& p, const Structure& baseline, Fitted& cur,
                                       const std::string& just_added, int round, const Options& o,
                                       std::vector<Step>& steps) {
  std::vector<std::string> removed;
  bool again = true;
  while (again) {  // after a removal the others are tried again against the smaller model
    again = false;
    std::vector<std::string> present = effects_in(cur.structure, baseline);
    present.erase(std::unique(present.begin(), present.end()), present.end());  // extra terms: once
    for (const auto& e : present) {
      if (e == just_added) continue;
      Step st;
      st.round = round;
      st.removal = true;
      st.effect = e;
      const Structure s2 = without_effect(cur.structure, e, baseline);
      st.model = s2.label();
      try {
        Fitted red = fit_from(p, s2, cur, o);
        st.free_parameters = red.fit.k;
        st.rms = red.fit.rms;
        st.bic = red.fit.bic;
        st.delta_bic = red.fit.bic - cur.fit.bic;  // > 0: the effect still pays for itself
        if (!std::isfinite(cur.held_out_rms))
          cur.held_out_rms = held_out_rms(p, cur, o, &cur.held_out_by_test);
        red.held_out_rms = held_out_rms(p, red, o, &red.held_out_by_test);
        st.held_out_rms = red.held_out_rms;
        st.current_held_out_rms = cur.held_out_rms;
        st.held_out_by_test = red.held_out_by_test;
        st.current_held_out_by_test = cur.held_out_by_test;
        const bool bic_earned = -st.delta_bic < -o.bic_threshold;
        const bool held_out_earned = cur.held_out_rms < o.held_out_ratio * red.held_out_rms;
        if (bic_earned && held_out_earned) {
          st.reason = "kept: without it BIC rises by " + significant(st.delta_bic, 4) +
                      " and the held-out RMS from " + significant(cur.held_out_rms, 4) + " to " +
                      significant(red.held_out_rms, 4) + " N";
        } else {
          st.accepted = true;
          st.reason =
              "removed: it would not be accepted now (" +
              std::string(bic_earned ? "" : "BIC without it rises by only " + significant(st.delta_bic, 3)) +
              std::string(!bic_earned && !held_out_earned ? "; " : "") +
              std::string(held_out_earned ? ""
                                          : "held-out RMS with it " + significant(cur.held_out_rms, 4) +
                                                " N not below " + significant(o.held_out_ratio, 3) + " x " +
                                                significant(red.held_out_rms, 4) + " N without") +
              ")";
          cur = std::move(red);
          removed.push_back(e);
          again = true;
        }
        say(o, "round " + std::to_string(round) + " backward: " + e + " " + st.reason);
      } catch (const Interrupted&) {
        throw;
      } catch (const std::exception& ex) {
        st.reason = std::string("kept: the model without it cannot be fitted: ") + ex.what();
        say(o, "round " + std::to_string(round) + " backward: " + e + " " + st.reason);
      }
      steps.push_back(st);
      if (again) break;
    }
  }
  return removed;
}

namespace {

/// The candidates of one round, each fitted from the current optimum (a Step each, in library order).
std::vector<Fitted> fit_candidates(const Prepared& p, const Fitted& cur, int round, const Options& o,
                                   Report& r, std::vector<std::size_t>& step_of) {
  std::vector<Fitted> cand;
  for (const auto& e : effect_library()) {
    if (!o.effects.empty() && std::find(o.effects.begin(), o.effects.end(), e.name) == o.effects.end())
      continue;
    const std::string why = not_applicable(e.name, cur.structure, p);
    if (!why.empty()) {
      if (round == 1 && std::none_of(r.not_applicable.begin(), r.not_applicable.end(),
                                     [&](const auto& n) { return n.first == e.name; }))
        r.not_applicable.emplace_back(e.name, why);  // once (a round may run twice)
      continue;
    }
    const Structure s2 = with_effect(cur.structure, e.name);
    Step st;
    st.round = round;
    st.effect = e.name;
    st.model = s2.label();
    try {
      Fitted f = fit_from(p, s2, cur, o);
      st.free_parameters = f.fit.k;
      st.rms = f.fit.rms;
      st.bic = f.fit.bic;
      st.delta_bic = f.fit.bic - cur.fit.bic;
      say(o, "  round " + std::to_string(round) + " " + e.name + ": RMS " + significant(st.rms, 4) +
                 " N, dBIC " + significant(st.delta_bic, 4));
      cand.push_back(std::move(f));
      step_of.push_back(r.steps.size());
    } catch (const Interrupted&) {
      throw;  // a stop request is not a failed candidate
    } catch (const std::exception& ex) {
      st.reason = std::string("fit failed: ") + ex.what();
      say(o, "  round " + std::to_string(round) + " " + e.name + ": " + st.reason);
    }
    r.steps.push_back(st);
  }
  return cand;
}

/// Round `round`'s decision over its candidates (best BIC first): the accepted one becomes `cur`.
/// Returns the accepted effect ("" when none); `refitted` is set when the current model re-fitted
/// from a candidate's optimum (refit_from) beat the current optimum, and `cur` is then that refit
/// (until a candidate is accepted).
std::string decide(const Prepared& p, Fitted& cur, std::vector<Fitted>& cand,
                   const std::vector<std::size_t>& step_of, int round, const Options& o, Report& r,
                   std::optional<Fitted>& refitted) {
  r.control = test_scale_control(p, cur);
  r.control.round = round;
  std::vector<std::size_t> order(cand.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return cand[a].fit.bic < cand[b].fit.bic; });
  int tried = 0;
  std::string accepted;
  for (const std::size_t i : order) {
    Step& st = r.steps[step_of[i]];
    if (!accepted.empty()) {
      st.reason = "a better candidate was accepted";
      continue;
    }
    st.delta_bic = cand[i].fit.bic - cur.fit.bic;  // against the current model as it now stands
    if (!(st.delta_bic < -o.bic_threshold)) {
      st.reason = "BIC falls by " + significant(-st.delta_bic, 3) + " <= " + significant(o.bic_threshold, 3);
      continue;
    }
    // The FE rig's own discretisation error bounds what the data can be said to show (issue 28).
    st.improvement_rms = rms_improvement(cur.fit.rms, cand[i].fit.rms);
    if (stands_in_for_discretisation(r.discretisation, cur.fit.rms, cand[i].fit.rms)) {
      st.reason = discretisation_reason(r.discretisation, cur.fit.rms, cand[i].fit.rms);
      say(o, "round " + std::to_string(round) + " " + st.effect + ": " + st.reason);
      continue;
    }
    if (tried >= 3) {
      st.reason = "not held-out tested (three better-BIC candidates failed it)";
      continue;
    }
    ++tried;
    // The gain must be the effect's: the current structure re-fitted from the candidate's optimum.
    Fitted again = refit_from(p, cur, cand[i], o);
    st.current_refit_rms = again.fit.rms;
    if (again.fit.sse < cur.fit.sse) {
      say(o, "round " + std::to_string(round) + ": " + cur.structure.label() + " re-fitted from the " +
                 st.effect + " optimum reaches RMS " + significant(again.fit.rms, 4) + " N (was " +
                 significant(cur.fit.rms, 4) + " N): the current model from now on");
      cur = std::move(again);
      refitted = cur;
      st.delta_bic = cand[i].fit.bic - cur.fit.bic;
      if (!(st.delta_bic < -o.bic_threshold)) {
        st.reason = "the current model re-fitted from this candidate's optimum reaches RMS " +
                    significant(cur.fit.rms, 4) + " N; against it BIC falls by only " +
                    significant(-st.delta_bic, 3) + " (the gain was the optimizer's, not the effect's)";
        continue;
      }
      r.control = test_scale_control(p, cur);  // of the current model as it now stands
      r.control.round = round;
      st.improvement_rms = rms_improvement(cur.fit.rms, cand[i].fit.rms);
      if (stands_in_for_discretisation(r.discretisation, cur.fit.rms, cand[i].fit.rms)) {
        st.reason = discretisation_reason(r.discretisation, cur.fit.rms, cand[i].fit.rms);
        say(o, "round " + std::to_string(round) + " " + st.effect + ": " + st.reason);
        continue;
      }
    }
    // A shared effect must explain more than a factor per test (TestScaleControl).
    if (o.test_control && r.control.applicable && r.control.bic < cand[i].fit.bic - o.bic_threshold) {
      r.control.decided = true;
      st.reason = "BIC falls by " + significant(-st.delta_bic, 4) + ", but " + control_text(r.control) +
                  " is lower by " + significant(cand[i].fit.bic - r.control.bic, 4) +
                  ": the structure is a difference between the tests that this shared effect does not "
                  "explain";
      say(o, "round " + std::to_string(round) + " " + st.effect + ": " + st.reason);
      continue;
    }
    if (!std::isfinite(cur.held_out_rms)) cur.held_out_rms = held_out_rms(p, cur, o, &cur.held_out_by_test);
    cand[i].held_out_rms = held_out_rms(p, cand[i], o, &cand[i].held_out_by_test);
    st.held_out_rms = cand[i].held_out_rms;
    st.current_held_out_rms = cur.held_out_rms;
    st.held_out_by_test = cand[i].held_out_by_test;
    st.current_held_out_by_test = cur.held_out_by_test;
    say(o, "round " + std::to_string(round) + " " + st.effect + ": held-out RMS by test " +
               list_text(st.held_out_by_test) + " N (current " + list_text(st.current_held_out_by_test) +
               ")");
    if (cand[i].held_out_rms < o.held_out_ratio * cur.held_out_rms) {
      st.accepted = true;
      st.reason = "BIC falls by " + significant(-st.delta_bic, 4) + " and the held-out RMS from " +
                  significant(cur.held_out_rms, 4) + " to " + significant(cand[i].held_out_rms, 4) + " N";
      accepted = st.effect;
      say(o, "round " + std::to_string(round) + ": accepted " + st.effect + " (" + st.reason + ")");
      cur = cand[i];
    } else {
      st.reason = "held-out RMS " + significant(cand[i].held_out_rms, 4) + " N not below " +
                  significant(o.held_out_ratio, 3) + " x " + significant(cur.held_out_rms, 4) + " N";
    }
  }
  return accepted;
}

/// Why nothing is selected when the data's noise level is round-off (below th.noise_floor of the peak
/// force) or `cur`'s residual lies below th.below_noise x that level (noise-free data: a BIC with the
/// residual as its own noise scale makes any candidate that bends the curve toward a smooth residual
/// look very strong evidence); "" otherwise.
std::string below_noise(const Fitted& cur, const Thresholds& th) {
  const double sigma = cur.study.noise_sigma;
  const double peak = cur.fit.rms_percent_peak > 0.0 ? 100.0 * cur.fit.rms / cur.fit.rms_percent_peak : 0.0;
  if (peak > 0.0 && !(sigma >= th.noise_floor * peak))
    return "the data's noise level (" + significant(sigma, 4) +
           " N, from second differences of the force) is " + "below " + significant(th.noise_floor, 2) +
           " of the peak force (" + significant(peak, 4) +
           " N): the data carry no measurable noise (exact or synthetic data) to weigh a candidate "
           "against, " +
           "so no effect is selected; the residual (RMS " + significant(cur.fit.rms, 4) +
           " N) and its structure are reported";
  if (!(sigma > 0.0) || !(cur.fit.rms < th.below_noise * sigma)) return "";
  return "the residual (RMS " + significant(cur.fit.rms, 4) + " N) is below " +
         significant(th.below_noise, 2) + " x the data's noise level (" + significant(sigma, 4) +
         " N, from second differences of the force): a fit to noisy data cannot get there, so the data "
         "carry no noise to weigh a candidate against (noise-free or smoothed data) and no effect is "
         "selected; the structure left is smaller than the data's own high-frequency content";
}

}  // namespace

double rms_improvement(double rms_current, double rms_candidate) {
  return std::sqrt(std::max(0.0, rms_current * rms_current - rms_candidate * rms_candidate));
}

bool stands_in_for_discretisation(const DiscretisationGate& g, double rms_current, double rms_candidate) {
  return g.applied && !(rms_improvement(rms_current, rms_candidate) > g.factor * g.change_rms);
}

std::string discretisation_reason(const DiscretisationGate& g, double rms_current, double rms_candidate) {
  return "stands in for discretisation error: its improvement of the RMS, sqrt(" +
         significant(rms_current, 4) + "^2 - " + significant(rms_candidate, 4) +
         "^2) = " + significant(rms_improvement(rms_current, rms_candidate), 3) + " N, is not more than " +
         significant(g.factor, 3) + " x the change of the baseline's FE-rig force from the rig " + g.rig +
         " to the rig refined " + significant(g.refine_ratio, 3) + "x in h (" + significant(g.change_rms, 3) +
         " N)";
}

Report run(const measured::DataSet& data, const Options& o) {
  const auto t0 = std::chrono::steady_clock::now();
  Report r;
  r.options = o;
  // A force against the sign convention would be "explained" as drift: refused first.
  measured::check_force_sign(data, "");
  r.data = prepare(data, o.max_samples);
  const Prepared& p = r.data;
  held_out_folds(p, &r.held_out_scheme);
  r.exactness = exactness(p);
  r.notes = protocol_notes(p);
  for (const auto& n : r.notes) say(o, "note: " + n);
  Structure base;
  base.law = o.baseline_law;
  base.prony_terms = o.baseline_prony;
  say(o, "discover " + p.name + ": " + std::to_string(p.size()) + " samples in " +
             std::to_string(p.series.size()) + " tests (" + stride_text(p.stride) + "), forward model " +
             to_string(p.rig));
  r.baseline =
      fit_structure(p, base, structure_parameters(base, p, o.poisson, o.fix_poisson), o, 3 * o.starts);
  r.forward_model = DiscoverModel(p, base).name();
  say(o, "baseline " + base.label() + ": RMS " + significant(r.baseline.fit.rms, 4) + " N (" +
             significant(r.baseline.fit.rms_percent_peak, 3) + " % of peak), BIC " +
             significant(r.baseline.fit.bic, 7) +
             (r.baseline.study.structured ? ", residual structured" : ", residual is noise"));
  if (o.discretisation) {
    r.discretisation = o.discretisation(p, r.baseline);
    const DiscretisationGate& g = r.discretisation;
    say(o, g.applied
               ? "discretisation gate: the baseline's FE-rig force changes by RMS " +
                     significant(g.change_rms, 4) + " N from the rig " + g.rig + " to the refined rig " +
                     g.refined_rig + "; an effect must improve the RMS by more than " +
                     significant(g.factor * g.change_rms, 4) + " N"
               : "discretisation gate not applied: " + g.note);
  }
  Fitted cur = r.baseline;
  r.stop_reason = "round limit (" + std::to_string(o.max_rounds) + ")";
  bool redone = false;
  for (int round = 1; round <= o.max_rounds; ++round) {
    if (!cur.study.structured) {
      r.stop_reason = "the residual is noise (every decisive diagnostic passes)";
      break;
    }
    if (const std::string why = below_noise(cur, o.thresholds); !why.empty()) {
      r.stop_reason = why;
      r.notes.push_back(why);
      say(o, "round " + std::to_string(round) + ": " + why);
      break;
    }
    std::vector<std::size_t> step_of;
    std::vector<Fitted> cand = fit_candidates(p, cur, round, o, r, step_of);
    std::optional<Fitted> refitted;
    const std::string accepted = decide(p, cur, cand, step_of, round, o, r, refitted);
    const bool improved = refitted.has_value();
    if (improved && r.selected.empty() && refitted->structure.label() == base.label()) {
      // The baseline re-fitted from a candidate's optimum: its better optimum is the error before.
      r.notes.push_back("the baseline's multi-start fit (RMS " + significant(r.baseline.fit.rms, 4) +
                        " N) was improved by the re-fit from a candidate's optimum to RMS " +
                        significant(refitted->fit.rms, 4) + " N: that is the error before");
      say(o, "note: " + r.notes.back());
      r.baseline = *refitted;
    }
    if (accepted.empty()) {
      if (improved && !redone && cur.study.structured) {
        // The candidates were fitted from the old optimum: once more from the better one.
        say(o, "round " + std::to_string(round) + ": nothing accepted; the round again from the re-fitted " +
                   cur.structure.label());
        redone = true;
        --round;
        continue;
      }
      r.stop_reason =
          !cur.study.structured ? "the residual is noise (every decisive diagnostic passes)"
          : cand.empty()        ? "no applicable candidate"
          : r.control.decided
              ? "the tests differ by more than any candidate explains: " + control_text(r.control) +
                    " explains more than every candidate that passed BIC"
              : "no candidate passes both BIC and held-out prediction";
      say(o, "round " + std::to_string(round) + ": " + r.stop_reason);
      break;
    }
    redone = false;
    r.selected.push_back(accepted);
    for (const auto& e : backward_step(p, base, cur, accepted, round, o, r.steps)) r.removed.push_back(e);
  }
  if (!cur.study.structured) r.stop_reason = "the residual is noise (every decisive diagnostic passes)";
  r.final = cur;
  r.final_effects = effects_in(cur.structure, base);
  r.unexplained = cur.study.structured;
  if (!r.control.decided) {  // the control of the final model (the loop may have stopped before a round)
    r.control = test_scale_control(p, cur);
    r.control.round = r.steps.empty() ? 0 : r.steps.back().round;
  }
  r.signature = describe_signature(cur.study, o.thresholds);
  if (r.unexplained && r.control.applicable && (r.control.decided || r.control.explained_share >= 0.5))
    r.signature = "tests inconsistent: one force factor per test (" + list_text(r.control.scale) + ") " +
                  (r.control.decided
                       ? "explains more than any shared effect"
                       : "would explain " + significant(100.0 * r.control.explained_share, 3) +
                             " % of the residual variance above the noise (RMS " +
                             significant(cur.fit.rms, 4) + " -> " + significant(r.control.rms, 4) + " N)") +
                  "; " + r.signature;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  say(o, "final " + cur.structure.label() + ": RMS " + significant(cur.fit.rms, 4) + " N (" +
             significant(cur.fit.rms_percent_peak, 3) + " % of peak)" +
             (r.unexplained ? "; unexplained structure: " + r.signature : "; residual is noise"));
  return r;
}

namespace {

nlohmann::json study_json(const ResidualStudy& s) {
  using nlohmann::json;
  json j;
  j["rms_N"] = s.rms;
  j["max_abs_N"] = s.max_abs;
  j["mean_N"] = s.mean;
  j["noise_level_N"] = s.noise_sigma;
  j["structured"] = s.structured;
  j["diagnostics"] = json::array();
  for (const auto& d : s.diagnostics)
    j["diagnostics"].push_back({{"name", d.name},
                                {"statistic", num(d.statistic)},
                                {"p_value", num(d.p_value)},
                                {"threshold", d.threshold},
                                {"passed", d.passed},
                                {"decisive", d.decisive},
                                {"note", d.note}});
  const auto groups = [](const std::vector<GroupStat>& g) {
    json a = json::array();
    for (const auto& x : g)
      a.push_back({{"group", x.group},
                   {"n", x.n},
                   {"rms_N", x.rms},
                   {"mean_N", x.mean},
                   {"max_abs_N", x.max_abs},
                   {"x", num(x.x)}});
    return a;
  };
  j["by_phase"] = groups(s.by_phase);
  j["by_cycle"] = groups(s.by_cycle);
  j["by_test"] = groups(s.by_test);
  j["by_strain"] = groups(s.by_strain);
  j["spectrum_peak"] = {{"frequency_Hz", s.period.frequency_hz},
                        {"cycles_per_test", s.period.cycles},
                        {"fisher_g", s.period.g},
                        {"p_value", s.period.p}};
  j["first_cycle_rms_ratio"] = num(s.first_cycle_ratio);
  j["worst_test_rms_ratio"] = num(s.worst_test_ratio);
  j["rate_rms_spearman"] = num(s.rate_correlation);
  j["where"] = s.where;
  return j;
}

nlohmann::json model_json(const Fitted& f, double peak) {
  using nlohmann::json;
  json j;
  j["model"] = f.structure.label();
  j["rms_N"] = f.fit.rms;
  j["rel_rms"] = f.fit.rms / peak;
  j["rms_percent_of_peak"] = 100.0 * f.fit.rms / peak;
  j["max_abs_N"] = f.max_abs;
  j["held_out_rms_N"] = num(f.held_out_rms);
  j["bic"] = f.fit.bic;
  j["aic"] = f.fit.aic;
  j["free_parameters"] = f.fit.k;
  j["parameters"] = json::array();
  for (const auto& q : f.fit.parameters)
    j["parameters"].push_back({{"name", q.name},
                               {"value", q.value},
                               {"unit", q.unit},
                               {"fixed", q.fixed},
                               {"standard_error", num(q.standard_error)},
                               {"interval95", {num(q.lower95), num(q.upper95)}},
                               {"identifiable", q.identifiable}});
  j["confounded"] = json::array();
  for (const auto& c : f.fit.confounded)
    j["confounded"].push_back({{"a", c.a}, {"b", c.b}, {"correlation", c.correlation}});
  j["residual"] = study_json(f.study);
  return j;
}

}  // namespace

nlohmann::json to_json(const Report& r) {
  using nlohmann::json;
  const Prepared& p = r.data;
  json j;
  j["dataset"] = p.name;
  j["rig"] = to_string(p.rig);
  j["forward_model"] = {{"name", r.forward_model},
                        {"description", DiscoverModel(p, r.final.structure).description()},
                        {"exact_where", r.exactness}};
  j["samples"] = p.size();
  j["tests"] = p.series.size();
  j["decimation_stride"] = p.stride;
  j["peak_force_N"] = p.peak_force;
  j["baseline"] = model_json(r.baseline, p.peak_force);
  j["final"] = model_json(r.final, p.peak_force);
  j["steps"] = json::array();
  for (const auto& s : r.steps)
    j["steps"].push_back({{"round", s.round},
                          {"action", s.removal ? "remove" : "add"},
                          {"effect", s.effect},
                          {"model", s.model},
                          {"free_parameters", s.free_parameters},
                          {"rms_N", num(s.rms)},
                          {"held_out_rms_N", num(s.held_out_rms)},
                          {"held_out_rms_by_test_N", nums(s.held_out_by_test)},
                          {"criterion",
                           {{"bic", num(s.bic)},
                            {"delta_bic", num(s.delta_bic)},
                            {"bic_threshold", -r.options.bic_threshold},
                            {"current_held_out_rms_N", num(s.current_held_out_rms)},
                            {"current_held_out_rms_by_test_N", nums(s.current_held_out_by_test)},
                            {"current_refit_from_candidate_rms_N", num(s.current_refit_rms)},
                            {"improvement_rms_N", num(s.improvement_rms)},
                            {"held_out_ratio_required", r.options.held_out_ratio}}},
                          {"accepted", s.accepted},
                          {"reason", s.reason}});
  j["selected_effects"] = r.selected;
  j["removed_effects"] = r.removed;
  j["final_effects"] = r.final_effects;
  j["unexplained_structure"] = r.unexplained;
  j["unexplained_signature"] = r.signature;
  j["stop_reason"] = r.stop_reason;
  j["test_consistency_control"] = {{"applicable", r.control.applicable},
                                   {"round", r.control.round},
                                   {"scale_per_test", nums(r.control.scale)},
                                   {"rms_N", num(r.control.rms)},
                                   {"bic", num(r.control.bic)},
                                   {"free_parameters", r.control.free_parameters},
                                   {"explained_share", num(r.control.explained_share)},
                                   {"decided", r.control.decided}};
  j["selection_rule"] =
      "accept the lowest-BIC candidate when BIC falls by more than " +
      significant(r.options.bic_threshold, 3) + " and the held-out RMS falls below " +
      significant(r.options.held_out_ratio, 3) +
      " x the current model's, both against the current model re-fitted from the candidate's "
      "optimum" +
      std::string(r.options.test_control
                      ? ", and its BIC is not above the test-consistency control's (one force factor per "
                        "test) by more than the threshold"
                      : " (the test-consistency control off)") +
      "; after each acceptance every earlier effect that would not be accepted now is removed";
  if (r.options.discretisation) {
    const DiscretisationGate& g = r.discretisation;
    j["discretisation_gate"] = {
        {"applied", g.applied},
        {"baseline_force_change_rms_N", num(g.change_rms)},
        {"factor", g.factor},
        {"refine_ratio", g.refine_ratio},
        {"rig", g.rig},
        {"refined_rig", g.refined_rig},
        {"samples", g.samples},
        {"note", g.note},
        {"rule",
         "a candidate is accepted only when its improvement sqrt(RMS_current^2 - RMS_candidate^2) exceeds "
         "factor x the RMS change of the baseline's FE-rig force between the rig and the refined rig at the "
         "baseline's optimum; otherwise it stands in for discretisation error"}};
    if (g.applied)
      j["selection_rule"] = j["selection_rule"].get<std::string>() + "; and its RMS improvement exceeds " +
                            significant(g.factor, 3) +
                            " x the FE rig's discretisation change of the baseline (" +
                            significant(g.change_rms, 3) + " N)";
  }
  j["held_out"] = r.held_out_scheme;
  j["notes"] = r.notes;
  j["not_applicable"] = json::array();
  for (const auto& [e, why] : r.not_applicable) j["not_applicable"].push_back({{"effect", e}, {"why", why}});
  j["library"] = json::array();
  for (const auto& e : effect_library())
    j["library"].push_back(
        {{"effect", e.name}, {"kind", to_string(e.kind)}, {"change", e.change}, {"signature", e.signature}});
  j["options"] = {
      {"poisson", r.options.poisson},
      {"fix_poisson", r.options.fix_poisson},
      {"baseline", to_string(r.options.baseline_law) + "+prony:" + std::to_string(r.options.baseline_prony)},
      {"max_rounds", r.options.max_rounds},
      {"starts", r.options.starts},
      {"seed", r.options.seed},
      {"max_samples", r.options.max_samples},
      {"alpha", r.options.thresholds.alpha},
      {"test_control", r.options.test_control}};
  j["wall_seconds"] = r.seconds;
  return j;
}

}  // namespace tmlab::discover
