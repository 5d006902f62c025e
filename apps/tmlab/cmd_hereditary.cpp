// tmlab hereditary: the Prony recursions (midpoint = the seed's eq. 20, exact_linear, backward_euler)
// against the exact hereditary integral, on prescribed strain histories and on the liver relaxation
// experiment (tensormass/include/tmlab/tensormass/hereditary_study.hpp; docs/hereditary.md).
// Writes <results>/hereditary/: hereditary.h5, hereditary.md (tables), PNG plots, manifest.json and
// summary.json last (RunOutput protocol).
#include "cli_args.hpp"

#include "commands.hpp"
#include "core/base/format.hpp"

#include "core/base/error.hpp"
#include "core/base/process.hpp"
#include "core/config/config_reader.hpp"
#include "core/io/hdf5_file.hpp"
#include "core/results/run_output.hpp"
#include "verification/studies/hereditary_study.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>

namespace tmlab::cli {

namespace {

namespace fs = std::filesystem;
using Integ = tm::ViscoelasticOptions::Integration;
constexpr Integ kSchemes[] = {Integ::Midpoint, Integ::ExactLinear, Integ::BackwardEuler};

std::string sci(double v, int digits = 2) {
  if (std::isnan(v)) return "-";
  if (std::isinf(v)) return v > 0 ? "never" : "-inf";
  return scientific(v, digits);
}

std::string fixed(double v, int digits = 2) { return std::isnan(v) ? "-" : fixed_point(v, digits); }

/// JSON cannot hold inf/NaN: null instead.
nlohmann::json num(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string w; std::getline(in, w, ',');)
    if (!w.empty()) out.push_back(w);
  return out;
}

std::string str(Integ s) { return tm::ViscoelasticOptions::to_string(s); }

}  // namespace

int cmd_hereditary(const std::vector<std::string>& args, const std::string& command_line) {
  const Parsed p = parse(args, {"--histories", "--results", "--params", "--seed", "--liver-history"},
                         {"--liver", "--no-liver", "--quick", "--no-plots"});
  if (!p.positional.empty()) throw UsageError("hereditary takes no positional arguments");
  if (p.has("--liver") && p.has("--no-liver")) throw UsageError("give --liver or --no-liver, not both");
  const bool quick = p.has("--quick");
  const bool liver = !p.has("--no-liver");
  const std::vector<std::string> groups = split_list(p.get("--histories", "ramp_hold,sine,random"));
  if (groups.empty()) throw UsageError("--histories needs a comma-separated list (ramp_hold, sine, random)");
  tm::StudyOptions so;
  so.quick = quick;
  if (p.has("--seed")) {
    const double s = parse_double("--seed", p.get("--seed"));
    if (!(s >= 0.0) || s != std::floor(s) || s > 9.0e15)
      throw UsageError("--seed needs a non-negative integer");
    so.seed = static_cast<std::uint64_t>(s);
  }
  const std::vector<tm::DriverHistory> histories = tm::study_histories(groups, so);
  // Quick runs only the seed's form (a pk2 liver step costs ~7x a nodal_force one).
  const std::string lh = p.get("--liver-history", quick ? "nodal_force" : "both");
  if (lh != "nodal_force" && lh != "pk2" && lh != "both")
    throw UsageError("--liver-history must be nodal_force, pk2 or both (got '" + lh + "')");
  const std::vector<std::string> liver_histories =
      lh == "both" ? std::vector<std::string>{"nodal_force", "pk2"} : std::vector<std::string>{lh};
  const std::string params_file =
      p.get("--params", (fs::path(tmlab_root()) / "cases" / "paper" / "xu2011_liver.json").string());
  const fs::path dir =
      fs::path(p.get("--results", (fs::path(tmlab_root()) / "results").string())) / "hereditary";
  auto log = [](const std::string& m) { std::cerr << "tmlab hereditary: " << m << "\n"; };

  RunOutput out(dir);
  try {
    nlohmann::json config = {
        {"histories", groups}, {"quick", quick}, {"liver", liver},  {"liver_history", liver_histories},
        {"alpha", so.alpha},   {"tau", so.tau},  {"seed", so.seed}, {"params", params_file}};
    std::vector<fs::path> inputs;
    if (liver) inputs.push_back(params_file);
    out.write_json("manifest.json", make_manifest({split_words(command_line), config, inputs}));
    H5File h5 = H5File::create(out.file("hereditary.h5").string());
    h5.set_attribute("/", "alpha", so.alpha);
    h5.set_attribute("/", "tau", so.tau);
    h5.set_attribute("/", "error_definition",
                     "max_n |X_rec(t_n) - X(t_n)| / max_n |X(t_n)|, X = X_e + alpha h");
    nlohmann::json summary = {{"alpha", so.alpha}, {"tau", so.tau}, {"histories", nlohmann::json::object()}};
    std::ostringstream md;
    md << "# tmlab hereditary: recursion errors against the exact hereditary integral\n\n"
       << "Command: `" << command_line << "`\n\n"
       << "One Prony term, alpha = " << so.alpha << ", tau = " << so.tau
       << " (times in units of tau). Error = max over the step times of |X_rec - X| / max |X|.\n\n"
       << "## Observed orders and breakdown thresholds\n\n"
       << "| history | scheme | order (fit dt/tau <= window) | window | error at dt/tau = 0.1 | at 1 | "
          "dt/tau at 1 % | at 10 % |\n"
       << "|---|---|---|---|---|---|---|---|\n";

    // ---- sweeps
    double quad_max = 0.0;
    std::vector<tm::SweepResult> sweeps;
    for (const auto& x : histories) {
      nlohmann::json hs = {{"description", x.describe()}, {"schemes", nlohmann::json::object()}};
      h5.create_group("/sweep/" + x.name());
      h5.set_attribute("/sweep/" + x.name(), "description", x.describe().dump());
      for (Integ s : kSchemes) {
        const tm::SweepResult r =
            tm::sweep(x, s, so, quick ? std::function<void(const std::string&)>() : log);
        sweeps.push_back(r);
        const std::string g = "/sweep/" + x.name() + "/" + r.scheme;
        std::vector<double> dt, q, e, qc;
        double e01 = std::numeric_limits<double>::quiet_NaN(), e1 = e01;
        for (const auto& run : r.runs) {
          dt.push_back(run.dt), q.push_back(run.dt_over_tau), e.push_back(run.error),
              qc.push_back(run.quadrature);
          quad_max = std::max(quad_max, run.quadrature);
          if (std::abs(std::log10(run.dt_over_tau) + 1.0) < 1e-9) e01 = run.error;
          if (std::abs(std::log10(run.dt_over_tau)) < 1e-9) e1 = run.error;
        }
        h5.write(g + "/dt", dt, {dt.size()});
        h5.write(g + "/dt_over_tau", q, {q.size()});
        h5.write(g + "/error", e, {e.size()});
        h5.write(g + "/reference_quadrature_check", qc, {qc.size()});
        h5.set_attribute(g, "order", r.order);
        h5.set_attribute(g, "fit_max_dt_over_tau", r.fit_max_dt_over_tau);
        h5.set_attribute(g, "breakdown_1pct", r.breakdown_1pct);
        h5.set_attribute(g, "breakdown_10pct", r.breakdown_10pct);
        hs["schemes"][r.scheme] = {{"order", num(r.order)},
                                   {"fit_max_dt_over_tau", r.fit_max_dt_over_tau},
                                   {"breakdown_dt_over_tau_1pct", num(r.breakdown_1pct)},
                                   {"breakdown_dt_over_tau_10pct", num(r.breakdown_10pct)},
                                   {"error_at_dt_over_tau_0.1", num(e01)},
                                   {"error_at_dt_over_tau_1", num(e1)}};
        md << "| " << x.name() << " | " << r.scheme << " | " << fixed(r.order) << " | "
           << sci(r.fit_max_dt_over_tau, 1) << " | " << sci(e01) << " | " << sci(e1) << " | "
           << sci(r.breakdown_1pct) << " | " << sci(r.breakdown_10pct) << " |\n";
        if (!quick)
          log(x.name() + " " + r.scheme + ": order " + fixed(r.order) + ", 1 % at dt/tau " +
              sci(r.breakdown_1pct));
      }
      summary["histories"][x.name()] = hs;
    }
    summary["reference_quadrature_check_max"] = quad_max;
    md << "\nReference check: the exact integral with twice the quadrature panels differs by at most "
       << sci(quad_max) << " (relative), far below every error in the table.\n";

    // ---- amplification factors (the recursion's decay a and increment weight c)
    {
      std::vector<double> xs;
      for (int k = -12; k <= 8; ++k) xs.push_back(std::pow(10.0, k / 4.0));
      h5.write("/amplification/dt_over_tau", xs, {xs.size()});
      nlohmann::json amp;
      md << "\n## Amplification factor a and increment weight c of h^{n+1} = a h^n + c (X_e^{n+1} - "
            "X_e^n)\n\n"
         << "| dt/tau | midpoint a | midpoint c | exact_linear a | exact_linear c | backward_euler a = c "
            "|\n|---|---|---|---|---|---|\n";
      for (Integ s : kSchemes) {
        std::vector<double> a, c;
        double amin = 1.0, amax = 0.0;
        for (double x : xs) {
          const tm::RecursionFactors f = tm::recursion_factors(s, x, 1.0);
          a.push_back(f.a), c.push_back(f.c);
          amin = std::min(amin, f.a), amax = std::max(amax, f.a);
        }
        h5.write("/amplification/" + str(s) + "_a", a, {a.size()});
        h5.write("/amplification/" + str(s) + "_c", c, {c.size()});
        amp[str(s)] = {{"min_a", amin}, {"max_a", amax}, {"range_dt_over_tau", {xs.front(), xs.back()}}};
      }
      for (double x : {0.1, 1.0, 2.0, 5.0, 10.0, 100.0}) {
        const auto m = tm::recursion_factors(Integ::Midpoint, x, 1.0),
                   e = tm::recursion_factors(Integ::ExactLinear, x, 1.0),
                   b = tm::recursion_factors(Integ::BackwardEuler, x, 1.0);
        md << "| " << x << " | " << sci(m.a) << " | " << sci(m.c) << " | " << sci(e.a) << " | " << sci(e.c)
           << " | " << sci(b.a) << " |\n";
      }
      summary["amplification"] = amp;
    }

    // ---- time histories of the ramp-hold at large steps (oscillation?), and sign changes in the hold
    {
      const tm::DriverHistory rh = tm::DriverHistory::ramp_hold("ramp_hold", 0.1, so.tau, 12.0 * so.tau);
      const tm::TimeHistory fine = tm::time_history(rh, Integ::ExactLinear, so.alpha, so.tau, 0.01 * so.tau);
      h5.write("/time_history/exact_fine/t", fine.t, {fine.t.size()});
      h5.write("/time_history/exact_fine/x", fine.x_exact, {fine.x_exact.size()});
      nlohmann::json osc;
      md << "\n## Ramp-hold (ramp over tau, hold to 12 tau) at large steps: sign changes of h^{n+1} - h^n "
            "after the ramp\n\n"
         << "| dt/tau | midpoint | exact_linear | backward_euler |\n|---|---|---|---|\n";
      for (double q : {0.5, 2.5, 5.0}) {
        md << "| " << q;
        for (Integ s : kSchemes) {
          const tm::TimeHistory th = tm::time_history(rh, s, so.alpha, so.tau, q * so.tau);
          char g[96];
          std::snprintf(g, sizeof g, "/time_history/%s/dt_over_tau_%g", str(s).c_str(), q);
          h5.write(std::string(g) + "/t", th.t, {th.t.size()});
          h5.write(std::string(g) + "/x_rec", th.x_rec, {th.x_rec.size()});
          h5.write(std::string(g) + "/x_exact", th.x_exact, {th.x_exact.size()});
          const int sc = tm::sign_changes(th, so.tau);
          osc[str(s)][fixed(q, 1)] = sc;
          md << " | " << sc;
        }
        md << " |\n";
      }
      summary["ramp_hold_sign_changes_after_ramp"] = osc;
    }

    // ---- ramp-hold kink on and off the step grid: dt = tau 2^-m, T_r = tau (on) or 4/3 tau (off)
    {
      nlohmann::json kink;
      md << "\n## Ramp-hold kink on / off the step grid (dt = tau 2^-m, m = 3..9; order from a fit over all "
            "m)\n\n"
         << "| scheme | kink on grid (T_r = tau) | kink inside a step (T_r = 4/3 tau) |\n|---|---|---|\n";
      const tm::DriverHistory on = tm::DriverHistory::ramp_hold("kink_on_grid", 0.1, so.tau, 6.0 * so.tau);
      const tm::DriverHistory off =
          tm::DriverHistory::ramp_hold("kink_off_grid", 0.1, 4.0 / 3.0 * so.tau, 6.0 * so.tau);
      for (Integ s : kSchemes) {
        md << "| " << str(s);
        for (const auto* x : {&on, &off}) {
          std::vector<tm::RecursionError> runs;
          for (int m = 3; m <= (quick ? 6 : 9); ++m)
            runs.push_back(tm::recursion_error(*x, s, so.alpha, so.tau, so.tau * std::ldexp(1.0, -m)));
          const double order = tm::fitted_order(runs, 1.0);
          std::vector<double> dt, e;
          for (const auto& r : runs) dt.push_back(r.dt), e.push_back(r.error);
          h5.write("/kink/" + x->name() + "/" + str(s) + "/dt", dt, {dt.size()});
          h5.write("/kink/" + x->name() + "/" + str(s) + "/error", e, {e.size()});
          h5.set_attribute("/kink/" + x->name() + "/" + str(s), "order", order);
          kink[x->name()][str(s)] = {{"order", num(order)}, {"finest_error", runs.back().error}};
          md << " | " << fixed(order) << " (finest " << sci(runs.back().error) << ")";
        }
        md << " |\n";
      }
      summary["kink"] = kink;
    }

    // ---- haptic: dt = 1 ms, tau from 0.5 ms to 1 s, histories in seconds
    {
      const double dt = 1e-3;
      const std::vector<double> taus = {5e-4, 1e-3, 2e-3, 5e-3, 1e-2, 0.1, 1.0};
      const std::vector<tm::DriverHistory> hap = {
          tm::DriverHistory::ramp_hold("haptic_ramp_100ms", 0.1, 0.1, 1.0),
          tm::DriverHistory::ramp_hold("haptic_ramp_5ms", 0.1, 0.005, 1.0),
          tm::DriverHistory::sine("haptic_sine_2Hz", 0.1, 2.0 * 3.14159265358979323846 * 2.0, 1.0),
          tm::DriverHistory::random("haptic_random_0.5-20Hz", 0.1, so.seed, 8,
                                    2.0 * 3.14159265358979323846 * 0.5, 2.0 * 3.14159265358979323846 * 20.0,
                                    1.0)};
      h5.write("/haptic/tau", taus, {taus.size()});
      h5.set_attribute("/haptic", "dt", dt);
      nlohmann::json hj;
      md << "\n## Haptic step dt = 1 ms: error against tau\n\n| history | scheme |";
      for (double t : taus) md << " tau = " << t * 1e3 << " ms |";
      md << "\n|---|---|";
      for (std::size_t i = 0; i < taus.size(); ++i) md << "---|";
      md << "\n";
      for (const auto& x : hap) {
        h5.create_group("/haptic/" + x.name());
        h5.set_attribute("/haptic/" + x.name(), "description", x.describe().dump());
        for (Integ s : kSchemes) {
          std::vector<double> e;
          md << "| " << x.name() << " | " << str(s) << " |";
          for (double tau : taus) {
            e.push_back(tm::recursion_error(x, s, so.alpha, tau, dt).error);
            md << " " << sci(e.back()) << " |";
          }
          md << "\n";
          h5.write("/haptic/" + x.name() + "/" + str(s) + "_error", e, {e.size()});
          hj[x.name()][str(s)] = e;
        }
      }
      summary["haptic"] = {{"dt", dt}, {"tau", taus}, {"error", hj}};
    }

    // ---- the liver relaxation, per history form (seed nodal_force, objective pk2)
    if (liver) {
      const nlohmann::json params = ConfigReader::parse_file(params_file);
      for (const std::string& hist : liver_histories) {
        tm::LiverStudyOptions lo;
        lo.history = hist;
        if (quick || hist == "pk2") {  // pk2: the short set keeps the study to about two minutes
          lo.dts = {0.2, 0.1};
          lo.reference_dts = {0.05, 0.025};
        }
        const tm::LiverStudy ls = tm::liver_study(params, params_file, tmlab_root(), lo, log);
        const std::string root = "/liver/" + hist;
        h5.write(root + "/t_ref", ls.t_ref, {ls.t_ref.size()});
        h5.write(root + "/force_ref", ls.force_ref, {ls.force_ref.size()});
        h5.set_attribute(root, "description", ls.describe.dump());
        nlohmann::json lj = {{"description", ls.describe},
                             {"peak_force_N", ls.peak_force},
                             {"reference_check_midpoint_vs_exact_linear", ls.reference_check},
                             {"richardson_correction", ls.richardson_correction},
                             {"path_check", num(ls.path_check)},
                             {"path_quadrature", num(ls.path_quadrature)},
                             {"num_tets", ls.num_tets},
                             {"node_tets", ls.node_tets},
                             {"seconds", ls.seconds},
                             {"runs", nlohmann::json::array()}};
        md << "\n## Liver relaxation (fig6, node " << lo.node << ", " << hist << " history)\n\n"
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
        for (Integ s : kSchemes) {
          std::vector<double> dt, e, iso;
          for (const auto& r : ls.runs) {
            if (r.scheme != str(s)) continue;
            dt.push_back(r.dt), e.push_back(r.error), iso.push_back(r.isolated_error);
            char g[128];
            std::snprintf(g, sizeof g, "%s/%s/dt_%g", root.c_str(), r.scheme.c_str(), r.dt);
            h5.write(std::string(g) + "/t", r.t, {r.t.size()});
            h5.write(std::string(g) + "/force", r.force, {r.force.size()});
            lj["runs"].push_back({{"scheme", r.scheme},
                                  {"dt", r.dt},
                                  {"error", r.error},
                                  {"isolated_error", num(r.isolated_error)},
                                  {"path_deviation", num(r.path_deviation)},
                                  {"seconds", r.seconds}});
            md << "| " << r.scheme << " | " << r.dt << " | " << sci(r.error) << " | " << sci(r.isolated_error)
               << " | " << sci(r.path_deviation) << " | " << fixed(r.seconds, 1) << " |\n";
          }
          h5.write(root + "/" + str(s) + "/dt", dt, {dt.size()});
          h5.write(root + "/" + str(s) + "/error", e, {e.size()});
          h5.write(root + "/" + str(s) + "/isolated_error", iso, {iso.size()});
          if (dt.size() >= 2)
            lj["order_" + str(s)] =
                num(std::log(e[e.size() - 2] / e.back()) / std::log(dt[dt.size() - 2] / dt.back()));
        }
        summary["liver"][hist] = lj;
      }
    }
    h5.close();
    std::ofstream(out.file("hereditary.md")) << md.str();

    if (!p.has("--no-plots")) {
      const fs::path script =
          fs::path(tmlab_root()) / "verification" / "studies" / "python" / "tmlab_hereditary_plot.py";
      const ProcessStatus ps = run_python(script, {out.staging_dir().string()});
      if (!ps.ok()) throw Error("drawing the hereditary plots failed (" + ps.describe() + ")");
    }
    out.finalize(summary);
  } catch (const std::exception& e) {
    out.abandon(e);
    throw;
  }
  std::cout << "results " << dir.string() << "/ (hereditary.h5, hereditary.md, summary.json, *.png)\n";
  return 0;
}

}  // namespace tmlab::cli
