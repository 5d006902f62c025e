// What a discovery and its benchmark write and say: see discover_output.hpp.
#include "calibration/discover/discover_output.hpp"

#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/base/process.hpp"
#include "core/io/hdf5_file.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>

namespace tmlab::discover {

namespace fs = std::filesystem;

namespace {

std::string html_escape(const std::string& s) {
  std::string o;
  for (const char c : s) {
    if (c == '<')
      o += "&lt;";
    else if (c == '>')
      o += "&gt;";
    else if (c == '&')
      o += "&amp;";
    else if (c == '"')
      o += "&quot;";
    else
      o += c;
  }
  return o;
}

std::string cell(const nlohmann::json& v, int digits = 4) {
  if (v.is_null()) return "-";
  if (v.is_number()) return significant(v.get<double>(), digits);
  if (v.is_boolean()) return v.get<bool>() ? "yes" : "no";
  if (v.is_string()) return html_escape(v.get<std::string>());
  return html_escape(v.dump());
}

}  // namespace

std::string report_html(const nlohmann::json& j, bool plots) {
  std::ostringstream h;
  const auto& b = j["baseline"];
  const auto& f = j["final"];
  h << "<!doctype html><html><head><meta charset=\"utf-8\"><title>tmlab discover: " << cell(j["dataset"])
    << "</title><style>body{font-family:sans-serif;max-width:1100px;margin:auto;padding:1em}"
       "table{border-collapse:collapse;margin:0.5em 0}td,th{border:1px solid #bbb;padding:2px "
       "6px;font-size:90%}"
       "th{background:#eee}.yes{background:#dfd}.no{background:#fdd}img{max-width:100%}</style></"
       "head><body>\n";
  h << "<h1>tmlab discover: " << cell(j["dataset"]) << "</h1>\n";
  h << "<p><b>Selected effects:</b> ";
  if (j["selected_effects"].empty()) h << "none";
  for (std::size_t i = 0; i < j["selected_effects"].size(); ++i)
    h << (i ? ", " : "") << "<code>" << cell(j["selected_effects"][i]) << "</code>";
  for (std::size_t i = 0; i < j["removed_effects"].size(); ++i)
    h << (i ? ", " : "; removed again: ") << "<code>" << cell(j["removed_effects"][i]) << "</code>";
  h << ". <b>Unexplained structure:</b> " << (j["unexplained_structure"].get<bool>() ? "yes: " : "no")
    << cell(j["unexplained_signature"]) << "</p>\n";
  h << "<p>Stopped: " << cell(j["stop_reason"]) << ". Selection rule: " << cell(j["selection_rule"])
    << "; held-out: " << cell(j["held_out"]) << ".</p>\n";
  if (const auto& c = j["test_consistency_control"]; c["applicable"].get<bool>()) {
    h << "<p><b>Test-consistency control</b> (the current model with one force factor per test, round "
      << c["round"].get<int>() << "): factors";
    for (const auto& x : c["scale_per_test"])
      h << " " << (x.is_null() ? "-" : significant(x.get<double>(), 4));
    h << ", RMS " << (c["rms_N"].is_null() ? "-" : significant(c["rms_N"].get<double>(), 4)) << " N, BIC "
      << (c["bic"].is_null() ? "-" : significant(c["bic"].get<double>(), 7))
      << (c["decided"].get<bool>() ? "; it explained more than every candidate that passed BIC"
                                   : "; no candidate was refused by it")
      << ".</p>\n";
  }
  if (j.contains("discretisation_gate")) {
    const auto& g = j["discretisation_gate"];
    h << "<p><b>Discretisation gate</b> (--forward fe_rig): ";
    if (g["applied"].get<bool>())
      h << "the baseline's FE-rig force changes by RMS " << cell(g["baseline_force_change_rms_N"])
        << " N from the rig " << cell(g["rig"]) << " to the refined rig " << cell(g["refined_rig"])
        << "; a candidate whose RMS improvement is not more than " << cell(g["factor"])
        << " x that stands in for discretisation error and is not accepted.</p>\n";
    else
      h << "not applied: " << cell(g["note"]) << ".</p>\n";
  }
  for (const auto& n : j["notes"]) h << "<p><b>Note:</b> " << cell(n) << "</p>\n";
  h << "<p>Forward model <code>" << cell(j["forward_model"]["name"])
    << "</code>: " << cell(j["forward_model"]["exact_where"]) << ".</p>\n";
  h << "<h2>Error before and after</h2><table><tr><th></th><th>model</th><th>RMS [N]</th><th>% of peak</th>"
       "<th>max |residual| [N]</th><th>BIC</th><th>free parameters</th><th>residual is noise</th></tr>\n";
  for (const auto& [name, m] : {std::pair<std::string, const nlohmann::json&>{"before", b}, {"after", f}})
    h << "<tr><td>" << name << "</td><td><code>" << cell(m["model"]) << "</code></td><td>" << cell(m["rms_N"])
      << "</td><td>" << cell(m["rms_percent_of_peak"], 3) << "</td><td>" << cell(m["max_abs_N"])
      << "</td><td>" << cell(m["bic"], 7) << "</td><td>" << cell(m["free_parameters"]) << "</td><td>"
      << (m["residual"]["structured"].get<bool>() ? "no" : "yes") << "</td></tr>\n";
  h << "</table><p>Peak force " << cell(j["peak_force_N"]) << " N; " << cell(j["samples"]) << " samples in "
    << cell(j["tests"]) << " tests (" << stride_text(j["decimation_stride"].get<std::size_t>()) << ").</p>\n";
  if (j.contains("fe_rig")) {
    // --forward fe_rig: the baseline and the final model refitted on the FE rig.
    h << "<h2>On the FE rig (--forward fe_rig)</h2><p>" << cell(j["fe_rig"]["description"])
      << ".</p><table><tr><th></th><th>model</th><th>closed form RMS [N]</th><th>FE rig at the closed-form "
         "optimum [N]</th><th>FE rig refitted [N]</th><th>% of peak</th><th>s</th></tr>\n";
    for (const auto& m : j["fe_rig"]["models"]) {
      h << "<tr><td>" << cell(m["which"]) << "</td><td><code>" << cell(m["model"]) << "</code></td>";
      if (m["refitted"].get<bool>())
        h << "<td>" << cell(m["closed_form_rms_N"]) << "</td><td>"
          << cell(m["fe_rms_at_closed_form_optimum_N"]) << "</td><td>" << cell(m["rms_N"]) << "</td><td>"
          << significant(100.0 * m["rel_rms"].get<double>(), 3) << "</td><td>" << cell(m["wall_seconds"], 3)
          << "</td></tr>\n";
      else
        h << "<td colspan=\"5\">not refitted: " << cell(m["why_not"]) << "</td></tr>\n";
    }
    h << "</table>\n";
  }
  if (plots)
    for (const char* p : {"discover_fits.png", "discover_residuals.png", "discover_residual_vs_strain.png"})
      h << "<p><img src=\"" << p << "\" alt=\"" << p << "\"></p>\n";
  h << "<h2>Steps</h2><table><tr><th>round</th><th>action</th><th>effect</th><th>model</th><th>RMS "
       "[N]</th><th>dBIC</th>"
       "<th>held-out RMS [N]</th><th>current held-out [N]</th><th>accepted</th><th>why</th></tr>\n";
  for (const auto& s : j["steps"])
    h << "<tr class=\"" << (s["accepted"].get<bool>() ? "yes" : "") << "\"><td>" << cell(s["round"])
      << "</td><td>" << cell(s["action"]) << "</td><td><code>" << cell(s["effect"]) << "</code></td><td>"
      << cell(s["model"]) << "</td><td>" << cell(s["rms_N"]) << "</td><td>"
      << cell(s["criterion"]["delta_bic"]) << "</td><td>" << cell(s["held_out_rms_N"]) << "</td><td>"
      << cell(s["criterion"]["current_held_out_rms_N"]) << "</td><td>" << cell(s["accepted"]) << "</td><td>"
      << cell(s["reason"]) << "</td></tr>\n";
  h << "</table>\n";
  for (const auto& [name, m] : {std::pair<std::string, const nlohmann::json&>{"baseline", b}, {"final", f}}) {
    h << "<h2>Residual diagnostics, " << name
      << "</h2><table><tr><th>diagnostic</th><th>statistic</th>"
         "<th>p</th><th>threshold</th><th>passed</th><th>decisive</th><th>note</th></tr>\n";
    for (const auto& d : m["residual"]["diagnostics"])
      h << "<tr class=\"" << (d["passed"].get<bool>() ? "yes" : "no") << "\"><td>" << cell(d["name"])
        << "</td><td>" << cell(d["statistic"]) << "</td><td>" << cell(d["p_value"], 2) << "</td><td>"
        << cell(d["threshold"]) << "</td><td>" << cell(d["passed"]) << "</td><td>" << cell(d["decisive"])
        << "</td><td>" << cell(d["note"]) << "</td></tr>\n";
    h << "</table><p>Where: " << cell(m["residual"]["where"])
      << "</p><table><tr><th>group</th><th>n</th>"
         "<th>RMS [N]</th><th>mean [N]</th></tr>\n";
    for (const char* g : {"by_phase", "by_cycle", "by_test", "by_strain"})
      for (const auto& x : m["residual"][g])
        h << "<tr><td>" << cell(x["group"]) << "</td><td>" << cell(x["n"]) << "</td><td>"
          << cell(x["rms_N"], 3) << "</td><td>" << cell(x["mean_N"], 3) << "</td></tr>\n";
    h << "</table>\n";
  }
  h << "<h2>Final parameters</h2><table><tr><th>name</th><th>value</th><th>unit</th><th>standard error</th>"
       "<th>95 % interval</th></tr>\n";
  for (const auto& q : f["parameters"])
    h << "<tr><td>" << cell(q["name"]) << "</td><td>" << cell(q["value"], 5) << "</td><td>" << cell(q["unit"])
      << "</td><td>" << (q["fixed"].get<bool>() ? "fixed" : cell(q["standard_error"], 3)) << "</td><td>"
      << (q["fixed"].get<bool>()
              ? ""
              : "[" + cell(q["interval95"][0], 4) + ", " + cell(q["interval95"][1], 4) + "]")
      << "</td></tr>\n";
  h << "</table>\n<h2>The library</h2><table><tr><th>effect</th><th>kind</th><th>change of the forward "
       "model</th>"
       "<th>residual signature it explains</th></tr>\n";
  for (const auto& e : j["library"])
    h << "<tr><td><code>" << cell(e["effect"]) << "</code></td><td>" << cell(e["kind"]) << "</td><td>"
      << cell(e["change"]) << "</td><td>" << cell(e["signature"]) << "</td></tr>\n";
  h << "</table>\n<p>Not applicable here:</p><ul>";
  for (const auto& e : j["not_applicable"])
    h << "<li><code>" << cell(e["effect"]) << "</code>: " << cell(e["why"]) << "</li>";
  h << "</ul><p>Method and thresholds: docs/discover.md. Full numbers: <a "
       "href=\"report.json\">report.json</a>.</p>"
       "</body></html>\n";
  return h.str();
}

void write_report_html(const fs::path& path, const nlohmann::json& report, bool plots) {
  std::ofstream f(path);
  f << report_html(report, plots);
  if (!f) throw Error("discover: cannot write " + path.string());
}

std::string benchmark_text(const BenchmarkResult& b) {
  std::ostringstream s;
  s << "confusion matrix (rows: truth; columns: effects found, only columns with a count)\n";
  std::vector<std::size_t> used;
  for (std::size_t c = 0; c < b.columns.size(); ++c) {
    bool any = false;
    for (const auto& r : b.confusion) any |= r[c] > 0;
    if (any) used.push_back(c);
  }
  s << "truth";
  for (const std::size_t c : used) s << "," << b.columns[c];
  s << "\n";
  for (std::size_t r = 0; r < b.rows.size(); ++r) {
    s << b.rows[r];
    for (const std::size_t c : used) s << "," << b.confusion[r][c];
    s << "\n";
  }
  return s.str();
}

void write_confusion_csv(const fs::path& path, const BenchmarkResult& b) {
  const std::string text = benchmark_text(b);
  std::ofstream f(path);
  f << text.substr(text.find('\n') + 1);
  if (!f) throw Error("discover: cannot write " + path.string());
}

void print_benchmark_report(std::ostream& os, const BenchmarkResult& b) {
  const std::string text = benchmark_text(b);
  os << text << "library sets: " << b.library_correct << " / " << b.library_sets
     << " right (diagonal fraction " << significant(b.diagonal_fraction, 3) << "; " << b.library_exact
     << " with the exact law, no family credit)\n"
     << "noise-only sets: " << b.noise_false_positives << " false positives of " << b.noise_sets << "\n"
     << "outside-library sets: " << b.outside_flagged << " of " << b.outside_sets
     << " flagged as unexplained structure, " << b.outside_forced << " with an effect added\n"
     << "median error reduction (library sets): " << significant(100.0 * b.median_error_reduction, 3)
     << " %\n";
}

nlohmann::json options_fingerprint(const Options& o) {
  return {{"poisson", o.poisson},
          {"fix_poisson", o.fix_poisson},
          {"max_samples", o.max_samples},
          {"baseline", to_string(o.baseline_law) + "+prony:" + std::to_string(o.baseline_prony)},
          {"rounds", o.max_rounds},
          {"bic_threshold", o.bic_threshold},
          {"held_out_ratio", o.held_out_ratio},
          {"starts", o.starts},
          {"threads", o.threads},
          {"seed", o.seed},
          {"alpha", o.thresholds.alpha},
          {"test_control", o.test_control},
          {"effects", o.effects}};
}

nlohmann::json summary_json(const Report& r, const std::string& plots) {
  return {{"selected_effects", r.selected},
          {"unexplained_structure", r.unexplained},
          {"baseline_rms_N", r.baseline.fit.rms},
          {"final_rms_N", r.final.fit.rms},
          {"plots", plots}};
}

nlohmann::json summary_json(const BenchmarkResult& b) {
  return {{"diagonal_fraction", b.diagonal_fraction},
          {"noise_only_false_positives", b.noise_false_positives},
          {"outside_library_flagged", b.outside_flagged},
          {"median_error_reduction", b.median_error_reduction}};
}

std::string write_discover_plots(const fs::path& dir, const fs::path& tmlab_root) {
  const ProcessStatus ps =
      run_python(tmlab_root / "calibration" / "discover" / "python" / "tmlab_discover_plot.py",
                 {dir.string()}, ProcessOutput::discard());
  return ps.ok() ? "ok" : "failed (" + ps.describe() + ")";
}

void write_discover_h5(const fs::path& path, const Report& r, const std::vector<FeRefit>& fe_refits) {
  H5File h5 = H5File::create(path.string());
  for (std::size_t k = 0; k < r.data.series.size(); ++k) {
    const Series& s = r.data.series[k];
    char g[32];
    std::snprintf(g, sizeof g, "/tests/%03zu", k);
    const std::string gs(g);
    h5.write(gs + "/time_s", s.t, {s.t.size()});
    h5.write(gs + "/displacement_m", s.d, {s.t.size()});
    h5.write(gs + "/force_N", s.f, {s.t.size()});
    h5.write(gs + "/baseline_N", r.baseline.prediction[k], {s.t.size()});
    h5.write(gs + "/final_N", r.final.prediction[k], {s.t.size()});
    for (const auto& fr : fe_refits)
      if (fr.done) h5.write(gs + "/fe_rig_" + fr.which + "_N", fr.prediction[k], {s.t.size()});
    h5.set_attribute(g, "id", s.id);
  }
  h5.close();
}

void print_discover_report(std::ostream& os, const Report& r, const std::vector<FeRefit>& fe_refits) {
  os << "baseline " << r.baseline.structure.label() << ": RMS " << significant(r.baseline.fit.rms, 4)
     << " N (" << significant(r.baseline.fit.rms_percent_peak, 3) << " % of peak), max "
     << significant(r.baseline.max_abs, 4) << " N\n";
  if (r.options.discretisation)
    os << "discretisation gate: "
       << (r.discretisation.applied
               ? "baseline FE-rig force change RMS " + significant(r.discretisation.change_rms, 4) +
                     " N (rig " + r.discretisation.rig + " -> " + r.discretisation.refined_rig +
                     "); an effect must improve the RMS by more than " +
                     significant(r.discretisation.factor, 3) + " x that"
               : "not applied: " + r.discretisation.note)
       << "\n";
  for (const auto& s : r.steps)
    if (s.accepted)
      os << "round " << s.round << (s.removal ? ": removed " : ": added ") << s.effect << " (" << s.reason
         << ")\n";
    else if (s.reason.rfind("stands in for discretisation error", 0) == 0)
      os << "round " << s.round << ": not added " << s.effect << " (" << s.reason << ")\n";
  os << "final " << r.final.structure.label() << ": RMS " << significant(r.final.fit.rms, 4) << " N ("
     << significant(r.final.fit.rms_percent_peak, 3) << " % of peak), max " << significant(r.final.max_abs, 4)
     << " N\n"
     << "unexplained structure: " << (r.unexplained ? "yes: " + r.signature : std::string("no")) << "\n";
  for (const auto& fr : fe_refits)
    os << "FE rig " << fr.which << " " << fr.model << ": "
       << (fr.done ? "RMS " + significant(fr.fit.rms, 4) + " N refitted (" +
                         significant(fr.fe_rms_at_closed_form, 4) + " N at the closed-form optimum)"
                   : "not refitted: " + fr.why_not)
       << "\n";
}

}  // namespace tmlab::discover
