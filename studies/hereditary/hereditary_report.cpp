// Tested end to end, not by a unit test of its own: write_hereditary_study is the whole study (every
// sweep and the liver runs) and its result is files. ctest test_cli_hereditary
// (apps/tmlab/tests/test_cli_hereditary.cpp) runs `tmlab hereditary --quick` and checks every file
// this writes (hereditary.h5 datasets, hereditary.md, the PNGs), the summary's orders, amplification
// and liver blocks, and bad parameters; test_cli_resume (CliStudyResume.InterruptedStudiesResume)
// interrupts it at its checkpoints and resumes it to the uninterrupted result. The numerics it calls
// are unit-tested in tests/test_hereditary_study.cpp.
#include "studies/hereditary/hereditary_report.hpp"

#include "core/base/interrupt.hpp"

#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/config/config_reader.hpp"
#include "core/io/hdf5_file.hpp"
#include "core/results/json_number.hpp"
#include "studies/common/study_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

namespace tmlab::tm {

namespace {

using Integ = ViscoelasticOptions::Integration;
constexpr Integ kSchemes[] = {Integ::Midpoint, Integ::ExactLinear, Integ::BackwardEuler};
using Log = std::function<void(const std::string&)>;

std::string sci(double v, int digits = 2) {
  if (std::isnan(v)) return "-";
  if (std::isinf(v)) return v > 0 ? "never" : "-inf";
  return scientific(v, digits);
}

std::string fixed(double v, int digits = 2) { return std::isnan(v) ? "-" : fixed_point(v, digits); }

std::string str(Integ s) { return ViscoelasticOptions::to_string(s); }

/// The study's checkpoint: the finished sweeps and liver studies by key, written after each one;
/// on --resume those of the interrupted study are taken from here. (The other steps are cheap and
/// run again.)
class StudyCheckpoint {
 public:
  explicit StudyCheckpoint(const HereditaryRunOptions& o) : o_(o) {
    if (o.resume) d_ = *o.resume;
  }

  SweepResult sweep(const std::string& key, const std::function<SweepResult()>& run) {
    if (d_.has(key + ".head")) {
      if (o_.log) o_.log(key + ": from the checkpoint of the interrupted study");
      const nlohmann::json names = nlohmann::json::parse(d_.text(key + ".names"));
      SweepResult r;
      r.history = names.at(0), r.scheme = names.at(1);
      const auto& h = d_.doubles(key + ".head");
      r.order = h.at(0), r.fit_max_dt_over_tau = h.at(1), r.breakdown_1pct = h.at(2),
      r.breakdown_10pct = h.at(3);
      const auto& dt = d_.doubles(key + ".dt");
      const auto& q = d_.doubles(key + ".dt_over_tau");
      const auto& e = d_.doubles(key + ".error");
      const auto& qc = d_.doubles(key + ".quadrature");
      const auto& n = d_.ints(key + ".steps");
      if (q.size() != dt.size() || e.size() != dt.size() || qc.size() != dt.size() || n.size() != dt.size())
        throw Error(d_.source() + ": inconsistent entry " + key + "; run without --resume");
      for (std::size_t i = 0; i < dt.size(); ++i)
        r.runs.push_back({dt[i], q[i], e[i], qc[i], static_cast<int>(n[i])});
      return r;
    }
    SweepResult r = run();
    std::vector<double> dt, q, e, qc;
    std::vector<std::int64_t> n;
    for (const auto& x : r.runs) {
      dt.push_back(x.dt), q.push_back(x.dt_over_tau), e.push_back(x.error), qc.push_back(x.quadrature);
      n.push_back(x.steps);
    }
    d_.put_text(key + ".names", nlohmann::json::array({r.history, r.scheme}).dump());
    d_.put(key + ".head",
           std::vector<double>{r.order, r.fit_max_dt_over_tau, r.breakdown_1pct, r.breakdown_10pct});
    d_.put(key + ".dt", dt);
    d_.put(key + ".dt_over_tau", q);
    d_.put(key + ".error", e);
    d_.put(key + ".quadrature", qc);
    d_.put(key + ".steps", n);
    commit("the sweep of " + r.history + " " + r.scheme);
    return r;
  }

  LiverStudy liver(const std::string& key, const std::function<LiverStudy()>& run) {
    if (d_.has(key + ".head")) {
      if (o_.log) o_.log(key + ": from the checkpoint of the interrupted study");
      LiverStudy ls;
      const auto& h = d_.doubles(key + ".head");
      ls.reference_check = h.at(0), ls.richardson_correction = h.at(1), ls.path_check = h.at(2);
      ls.path_quadrature = h.at(3), ls.peak_force = h.at(4), ls.seconds = h.at(5);
      const auto& c = d_.ints(key + ".counts");
      ls.num_tets = static_cast<int>(c.at(0)), ls.num_nodes = static_cast<int>(c.at(1));
      ls.node_tets = static_cast<int>(c.at(2));
      const std::size_t runs = static_cast<std::size_t>(c.at(3));
      ls.t_ref = d_.doubles(key + ".t_ref");
      ls.force_ref = d_.doubles(key + ".force_ref");
      ls.describe = nlohmann::json::parse(d_.text(key + ".describe"));
      for (std::size_t i = 0; i < runs; ++i) {
        const std::string k = key + ".run" + std::to_string(i);
        LiverRun r;
        r.scheme = d_.text(k + ".scheme");
        const auto& v = d_.doubles(k + ".num");
        r.dt = v.at(0), r.error = v.at(1), r.isolated_error = v.at(2), r.path_deviation = v.at(3);
        r.seconds = v.at(4);
        r.t = d_.doubles(k + ".t");
        r.force = d_.doubles(k + ".force");
        ls.runs.push_back(std::move(r));
      }
      return ls;
    }
    LiverStudy ls = run();
    d_.put(key + ".head", std::vector<double>{ls.reference_check, ls.richardson_correction, ls.path_check,
                                              ls.path_quadrature, ls.peak_force, ls.seconds});
    d_.put(key + ".counts", std::vector<std::int64_t>{ls.num_tets, ls.num_nodes, ls.node_tets,
                                                      static_cast<std::int64_t>(ls.runs.size())});
    d_.put(key + ".t_ref", ls.t_ref);
    d_.put(key + ".force_ref", ls.force_ref);
    d_.put_text(key + ".describe", ls.describe.dump());
    for (std::size_t i = 0; i < ls.runs.size(); ++i) {
      const std::string k = key + ".run" + std::to_string(i);
      const LiverRun& r = ls.runs[i];
      d_.put_text(k + ".scheme", r.scheme);
      d_.put(k + ".num", std::vector<double>{r.dt, r.error, r.isolated_error, r.path_deviation, r.seconds});
      d_.put(k + ".t", r.t);
      d_.put(k + ".force", r.force);
    }
    commit("the liver study (" + key + ")");
    return ls;
  }

 private:
  /// Writes the checkpoint (when the study has one), then stops here if a signal is pending.
  void commit(const std::string& after) {
    if (o_.checkpoint.empty()) return;
    write_checkpoint(o_.checkpoint, "hereditary", o_.fingerprint, d_);
    check_interrupt("after " + after + "; the finished parts are in the checkpoint " +
                    o_.checkpoint.string() + ": continue with the same command and --resume");
  }
  const HereditaryRunOptions& o_;
  CheckpointData d_;
};

/// Where each step writes: its datasets, its markdown section and its summary entry.
struct Sink {
  H5File& h5;
  std::ostringstream& md;
  nlohmann::json& summary;
  StudyCheckpoint& ck;
};

void write_header(Sink& out, const HereditaryRunOptions& o) {
  const StudyOptions& so = o.study;
  out.h5.set_attribute("/", "alpha", so.alpha);
  out.h5.set_attribute("/", "tau", so.tau);
  out.h5.set_attribute("/", "error_definition",
                       "max_n |X_rec(t_n) - X(t_n)| / max_n |X(t_n)|, X = X_e + alpha h");
  out.md << "# tmlab hereditary: recursion errors against the exact hereditary integral\n\n"
         << "Command: `" << o.command_line << "`\n\n"
         << "One Prony term, alpha = " << so.alpha << ", tau = " << so.tau
         << " (times in units of tau). Error = max over the step times of |X_rec - X| / max |X|.\n\n";
}

/// One history and scheme of the sweep: datasets, table row and summary entry. Returns the largest
/// reference quadrature check of its runs.
double write_sweep(Sink& out, const DriverHistory& x, const SweepResult& r, nlohmann::json& hs) {
  const std::string g = "/sweep/" + x.name() + "/" + r.scheme;
  std::vector<double> dt, q, e, qc;
  double e01 = std::numeric_limits<double>::quiet_NaN(), e1 = e01, quad_max = 0.0;
  for (const auto& run : r.runs) {
    dt.push_back(run.dt), q.push_back(run.dt_over_tau), e.push_back(run.error), qc.push_back(run.quadrature);
    quad_max = std::max(quad_max, run.quadrature);
    if (std::abs(std::log10(run.dt_over_tau) + 1.0) < 1e-9) e01 = run.error;
    if (std::abs(std::log10(run.dt_over_tau)) < 1e-9) e1 = run.error;
  }
  out.h5.write(g + "/dt", dt, {dt.size()});
  out.h5.write(g + "/dt_over_tau", q, {q.size()});
  out.h5.write(g + "/error", e, {e.size()});
  out.h5.write(g + "/reference_quadrature_check", qc, {qc.size()});
  out.h5.set_attribute(g, "order", r.order);
  out.h5.set_attribute(g, "fit_max_dt_over_tau", r.fit_max_dt_over_tau);
  out.h5.set_attribute(g, "breakdown_1pct", r.breakdown_1pct);
  out.h5.set_attribute(g, "breakdown_10pct", r.breakdown_10pct);
  hs["schemes"][r.scheme] = {{"order", finite_or_null(r.order)},
                             {"fit_max_dt_over_tau", r.fit_max_dt_over_tau},
                             {"breakdown_dt_over_tau_1pct", finite_or_null(r.breakdown_1pct)},
                             {"breakdown_dt_over_tau_10pct", finite_or_null(r.breakdown_10pct)},
                             {"error_at_dt_over_tau_0.1", finite_or_null(e01)},
                             {"error_at_dt_over_tau_1", finite_or_null(e1)}};
  out.md << "| " << x.name() << " | " << r.scheme << " | " << fixed(r.order) << " | "
         << sci(r.fit_max_dt_over_tau, 1) << " | " << sci(e01) << " | " << sci(e1) << " | "
         << sci(r.breakdown_1pct) << " | " << sci(r.breakdown_10pct) << " |\n";
  return quad_max;
}

/// The recursion error of every scheme against dt/tau per history: orders and breakdown thresholds.
void write_sweeps(Sink& out, const HereditaryRunOptions& o) {
  const bool quick = o.study.quick;
  out.md << "## Observed orders and breakdown thresholds\n\n"
         << "| history | scheme | order (fit dt/tau <= window) | window | error at dt/tau = 0.1 | at 1 | "
            "dt/tau at 1 % | at 10 % |\n"
         << "|---|---|---|---|---|---|---|---|\n";
  double quad_max = 0.0;
  out.summary["histories"] = nlohmann::json::object();
  for (std::size_t xi = 0; xi < o.histories.size(); ++xi) {
    const DriverHistory& x = o.histories[xi];
    nlohmann::json hs = {{"description", x.describe()}, {"schemes", nlohmann::json::object()}};
    out.h5.create_group("/sweep/" + x.name());
    out.h5.set_attribute("/sweep/" + x.name(), "description", x.describe().dump());
    for (Integ s : kSchemes) {
      const SweepResult r = out.ck.sweep("sweep" + std::to_string(xi) + "." + str(s),
                                         [&] { return sweep(x, s, o.study, quick ? Log() : o.log); });
      quad_max = std::max(quad_max, write_sweep(out, x, r, hs));
      if (!quick && o.log)
        o.log(x.name() + " " + r.scheme + ": order " + fixed(r.order) + ", 1 % at dt/tau " +
              sci(r.breakdown_1pct));
    }
    out.summary["histories"][x.name()] = hs;
  }
  out.summary["reference_quadrature_check_max"] = quad_max;
  out.md << "\nReference check: the exact integral with twice the quadrature panels differs by at most "
         << sci(quad_max) << " (relative), far below every error in the table.\n";
}

/// The recursion's decay a and increment weight c against dt/tau.
void write_amplification(Sink& out) {
  std::vector<double> xs;
  for (int k = -12; k <= 8; ++k) xs.push_back(std::pow(10.0, k / 4.0));
  out.h5.write("/amplification/dt_over_tau", xs, {xs.size()});
  nlohmann::json amp;
  out.md << "\n## Amplification factor a and increment weight c of h^{n+1} = a h^n + c (X_e^{n+1} - "
            "X_e^n)\n\n"
         << "| dt/tau | midpoint a | midpoint c | exact_linear a | exact_linear c | backward_euler a = c "
            "|\n|---|---|---|---|---|---|\n";
  for (Integ s : kSchemes) {
    std::vector<double> a, c;
    double amin = 1.0, amax = 0.0;
    for (double x : xs) {
      const RecursionFactors f = recursion_factors(s, x, 1.0);
      a.push_back(f.a), c.push_back(f.c);
      amin = std::min(amin, f.a), amax = std::max(amax, f.a);
    }
    out.h5.write("/amplification/" + str(s) + "_a", a, {a.size()});
    out.h5.write("/amplification/" + str(s) + "_c", c, {c.size()});
    amp[str(s)] = {{"min_a", amin}, {"max_a", amax}, {"range_dt_over_tau", {xs.front(), xs.back()}}};
  }
  for (double x : {0.1, 1.0, 2.0, 5.0, 10.0, 100.0}) {
    const auto m = recursion_factors(Integ::Midpoint, x, 1.0),
               e = recursion_factors(Integ::ExactLinear, x, 1.0),
               b = recursion_factors(Integ::BackwardEuler, x, 1.0);
    out.md << "| " << x << " | " << sci(m.a) << " | " << sci(m.c) << " | " << sci(e.a) << " | " << sci(e.c)
           << " | " << sci(b.a) << " |\n";
  }
  out.summary["amplification"] = amp;
}

/// Time histories of the ramp-hold at large steps (oscillation?), and sign changes in the hold.
void write_time_histories(Sink& out, const StudyOptions& so) {
  const DriverHistory rh = DriverHistory::ramp_hold("ramp_hold", 0.1, so.tau, 12.0 * so.tau);
  const TimeHistory fine = time_history(rh, Integ::ExactLinear, so.alpha, so.tau, 0.01 * so.tau);
  out.h5.write("/time_history/exact_fine/t", fine.t, {fine.t.size()});
  out.h5.write("/time_history/exact_fine/x", fine.x_exact, {fine.x_exact.size()});
  nlohmann::json osc;
  out.md << "\n## Ramp-hold (ramp over tau, hold to 12 tau) at large steps: sign changes of h^{n+1} - h^n "
            "after the ramp\n\n"
         << "| dt/tau | midpoint | exact_linear | backward_euler |\n|---|---|---|---|\n";
  for (double q : {0.5, 2.5, 5.0}) {
    out.md << "| " << q;
    for (Integ s : kSchemes) {
      const TimeHistory th = time_history(rh, s, so.alpha, so.tau, q * so.tau);
      char g[96];
      std::snprintf(g, sizeof g, "/time_history/%s/dt_over_tau_%g", str(s).c_str(), q);
      out.h5.write(std::string(g) + "/t", th.t, {th.t.size()});
      out.h5.write(std::string(g) + "/x_rec", th.x_rec, {th.x_rec.size()});
      out.h5.write(std::string(g) + "/x_exact", th.x_exact, {th.x_exact.size()});
      const int sc = sign_changes(th, so.tau);
      osc[str(s)][fixed(q, 1)] = sc;
      out.md << " | " << sc;
    }
    out.md << " |\n";
  }
  out.summary["ramp_hold_sign_changes_after_ramp"] = osc;
}

/// The ramp-hold kink on and off the step grid: dt = tau 2^-m, T_r = tau (on) or 4/3 tau (off).
void write_kink(Sink& out, const StudyOptions& so) {
  nlohmann::json kink;
  out.md << "\n## Ramp-hold kink on / off the step grid (dt = tau 2^-m, m = 3..9; order from a fit over all "
            "m)\n\n"
         << "| scheme | kink on grid (T_r = tau) | kink inside a step (T_r = 4/3 tau) |\n|---|---|---|\n";
  const DriverHistory on = DriverHistory::ramp_hold("kink_on_grid", 0.1, so.tau, 6.0 * so.tau);
  const DriverHistory off = DriverHistory::ramp_hold("kink_off_grid", 0.1, 4.0 / 3.0 * so.tau, 6.0 * so.tau);
  for (Integ s : kSchemes) {
    out.md << "| " << str(s);
    for (const auto* x : {&on, &off}) {
      std::vector<RecursionError> runs;
      for (int m = 3; m <= (so.quick ? 6 : 9); ++m)
        runs.push_back(recursion_error(*x, s, so.alpha, so.tau, so.tau * std::ldexp(1.0, -m)));
      const double order = fitted_order(runs, 1.0);
      std::vector<double> dt, e;
      for (const auto& r : runs) dt.push_back(r.dt), e.push_back(r.error);
      const std::string g = "/kink/" + x->name() + "/" + str(s);
      out.h5.write(g + "/dt", dt, {dt.size()});
      out.h5.write(g + "/error", e, {e.size()});
      out.h5.set_attribute(g, "order", order);
      kink[x->name()][str(s)] = {{"order", finite_or_null(order)}, {"finest_error", runs.back().error}};
      out.md << " | " << fixed(order) << " (finest " << sci(runs.back().error) << ")";
    }
    out.md << " |\n";
  }
  out.summary["kink"] = kink;
}

/// Haptic steps: dt = 1 ms, tau from 0.5 ms to 1 s, histories in seconds.
void write_haptic(Sink& out, const StudyOptions& so) {
  constexpr double kTwoPi = 2.0 * 3.14159265358979323846;
  const double dt = 1e-3;
  const std::vector<double> taus = {5e-4, 1e-3, 2e-3, 5e-3, 1e-2, 0.1, 1.0};
  const std::vector<DriverHistory> hap = {
      DriverHistory::ramp_hold("haptic_ramp_100ms", 0.1, 0.1, 1.0),
      DriverHistory::ramp_hold("haptic_ramp_5ms", 0.1, 0.005, 1.0),
      DriverHistory::sine("haptic_sine_2Hz", 0.1, kTwoPi * 2.0, 1.0),
      DriverHistory::random("haptic_random_0.5-20Hz", 0.1, so.seed, 8, kTwoPi * 0.5, kTwoPi * 20.0, 1.0)};
  out.h5.write("/haptic/tau", taus, {taus.size()});
  out.h5.set_attribute("/haptic", "dt", dt);
  nlohmann::json hj;
  out.md << "\n## Haptic step dt = 1 ms: error against tau\n\n| history | scheme |";
  for (double t : taus) out.md << " tau = " << t * 1e3 << " ms |";
  out.md << "\n|---|---|";
  for (std::size_t i = 0; i < taus.size(); ++i) out.md << "---|";
  out.md << "\n";
  for (const auto& x : hap) {
    out.h5.create_group("/haptic/" + x.name());
    out.h5.set_attribute("/haptic/" + x.name(), "description", x.describe().dump());
    for (Integ s : kSchemes) {
      std::vector<double> e;
      out.md << "| " << x.name() << " | " << str(s) << " |";
      for (double tau : taus) {
        e.push_back(recursion_error(x, s, so.alpha, tau, dt).error);
        out.md << " " << sci(e.back()) << " |";
      }
      out.md << "\n";
      out.h5.write("/haptic/" + x.name() + "/" + str(s) + "_error", e, {e.size()});
      hj[x.name()][str(s)] = e;
    }
  }
  out.summary["haptic"] = {{"dt", dt}, {"tau", taus}, {"error", hj}};
}

/// The liver study's options for one history form: the short set of steps for quick runs and for pk2
/// (a pk2 step costs ~7x a nodal_force one; the short set keeps the study to about two minutes).
LiverStudyOptions liver_options(const std::string& history, bool quick) {
  LiverStudyOptions lo;
  lo.history = history;
  if (quick || history == "pk2") {
    lo.dts = {0.2, 0.1};
    lo.reference_dts = {0.05, 0.025};
  }
  return lo;
}

/// The liver study's runs of one scheme: force histories, errors, their table rows and summary entries.
void write_liver_scheme(Sink& out, const std::string& root, const LiverStudy& ls, Integ s,
                        nlohmann::json& lj) {
  std::vector<double> dt, e, iso;
  for (const auto& r : ls.runs) {
    if (r.scheme != str(s)) continue;
    dt.push_back(r.dt), e.push_back(r.error), iso.push_back(r.isolated_error);
    char g[128];
    std::snprintf(g, sizeof g, "%s/%s/dt_%g", root.c_str(), r.scheme.c_str(), r.dt);
    out.h5.write(std::string(g) + "/t", r.t, {r.t.size()});
    out.h5.write(std::string(g) + "/force", r.force, {r.force.size()});
    lj["runs"].push_back({{"scheme", r.scheme},
                          {"dt", r.dt},
                          {"error", r.error},
                          {"isolated_error", finite_or_null(r.isolated_error)},
                          {"path_deviation", finite_or_null(r.path_deviation)},
                          {"seconds", r.seconds}});
    out.md << "| " << r.scheme << " | " << r.dt << " | " << sci(r.error) << " | " << sci(r.isolated_error)
           << " | " << sci(r.path_deviation) << " | " << fixed(r.seconds, 1) << " |\n";
  }
  out.h5.write(root + "/" + str(s) + "/dt", dt, {dt.size()});
  out.h5.write(root + "/" + str(s) + "/error", e, {e.size()});
  out.h5.write(root + "/" + str(s) + "/isolated_error", iso, {iso.size()});
  if (dt.size() >= 2)
    lj["order_" + str(s)] =
        finite_or_null(std::log(e[e.size() - 2] / e.back()) / std::log(dt[dt.size() - 2] / dt.back()));
}

/// The liver relaxation in one history form (nodal_force: the seed's; pk2: objective).
void write_liver(Sink& out, const HereditaryRunOptions& o, const nlohmann::json& params,
                 const std::string& hist) {
  const LiverStudyOptions lo = liver_options(hist, o.study.quick);
  const LiverStudy ls = out.ck.liver(
      "liver." + hist, [&] { return liver_study(params, o.params_file, o.tmlab_root, lo, o.log); });
  const std::string root = "/liver/" + hist;
  out.h5.write(root + "/t_ref", ls.t_ref, {ls.t_ref.size()});
  out.h5.write(root + "/force_ref", ls.force_ref, {ls.force_ref.size()});
  out.h5.set_attribute(root, "description", ls.describe.dump());
  nlohmann::json lj = {{"description", ls.describe},
                       {"peak_force_N", ls.peak_force},
                       {"reference_check_midpoint_vs_exact_linear", ls.reference_check},
                       {"richardson_correction", ls.richardson_correction},
                       {"path_check", finite_or_null(ls.path_check)},
                       {"path_quadrature", finite_or_null(ls.path_quadrature)},
                       {"num_tets", ls.num_tets},
                       {"node_tets", ls.node_tets},
                       {"seconds", ls.seconds},
                       {"runs", nlohmann::json::array()}};
  out.md << "\n## Liver relaxation (fig6, node " << lo.node << ", " << hist << " history)\n\n"
         << "Reaction force of the pushed node; reference: Richardson extrapolation of exact_linear at dt "
            "= "
         << lo.reference_dts[0] << ", " << lo.reference_dts[1] << " s (peak " << fixed(ls.peak_force, 4)
         << " N). Checks: the midpoint Richardson reference differs by " << sci(ls.reference_check)
         << "; Richardson correction " << sci(ls.richardson_correction)
         << "; reaction from the exact hereditary integral along the finest path vs reference "
         << sci(ls.path_check) << " (its sampling check " << sci(ls.path_quadrature)
         << "). Errors relative to the peak, max over t = k "
         << *std::max_element(lo.dts.begin(), lo.dts.end())
         << " s. Path deviation: max |y_run - y_ref| / peak, y the elastic part of the reaction.\n\n"
         << "| scheme | dt [s] | coupled error | isolated recursion error | path deviation | wall [s] |\n"
         << "|---|---|---|---|---|---|\n";
  for (Integ s : kSchemes) write_liver_scheme(out, root, ls, s, lj);
  out.summary["liver"][hist] = lj;
}

}  // namespace

nlohmann::json write_hereditary_study(const HereditaryRunOptions& o, const std::filesystem::path& dir) {
  nlohmann::json summary = {{"alpha", o.study.alpha}, {"tau", o.study.tau}};
  std::ostringstream md;
  H5File h5 = H5File::create((dir / "hereditary.h5").string());
  StudyCheckpoint ck(o);
  Sink out{h5, md, summary, ck};
  write_header(out, o);
  write_sweeps(out, o);
  write_amplification(out);
  write_time_histories(out, o.study);
  write_kink(out, o.study);
  write_haptic(out, o.study);
  if (o.liver) {
    const nlohmann::json params = ConfigReader::parse_file(o.params_file);
    for (const std::string& hist : o.liver_histories) write_liver(out, o, params, hist);
  }
  h5.close();
  std::ofstream(dir / "hereditary.md") << md.str();
  if (o.plots) {
    const ProcessStatus ps = draw_study_plot(o.tmlab_root, "hereditary", "tmlab_hereditary_plot.py", dir);
    if (!ps.ok()) throw Error("drawing the hereditary plots failed (" + ps.describe() + ")");
  }
  return summary;
}

}  // namespace tmlab::tm
