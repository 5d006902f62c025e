// tmlab discover DATA.csv | --benchmark: model discovery from measured data (issue 15;
// docs/discover.md). Thin: tmlab::discover does the work; this file reads the options, writes
// report.json, discover.h5, the plots, index.html and the manifest through the result protocol
// (a failed run leaves FAILED), and prints progress on standard error.
#include "commands.hpp"

#include "cli_args.hpp"
#include "fit_checkpoint.hpp"

#include "calibration/data/measured_data.hpp"
#include "calibration/data/sign_convention.hpp"
#include "calibration/discover/benchmark.hpp"
#include "calibration/discover/discover.hpp"
#include "calibration/discover/fe_refit.hpp"
#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/base/interrupt.hpp"
#include "core/base/process.hpp"
#include "core/io/hdf5_file.hpp"
#include "core/results/run_output.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

namespace tmlab::cli {

namespace fs = std::filesystem;

namespace {

/// The checkpoint of a discover command whose units are a list of T (fits, benchmark sets): writes
/// the finished units through `put`, and with --resume reads them back through `get` before the
/// result directory is touched. Not copyable or movable (its writer refers to `done`).
template <class T>
class UnitList {
 public:
  using Put = void (*)(CheckpointData&, const std::vector<T>&);
  using Get = std::vector<T> (*)(const CheckpointData&);
  UnitList(const fs::path& dir, const std::string& kind, const nlohmann::json& fingerprint,
           const CheckpointSchedule& schedule, Put put, std::string noun)
      : noun_(std::move(noun)),
        ck(dir / RunOutput::kStaging / "checkpoint.h5", kind, fingerprint, schedule, [this, put] {
          CheckpointData d;
          put(d, done_);
          return d;
        }) {}
  UnitList(const UnitList&) = delete;
  UnitList& operator=(const UnitList&) = delete;

  /// The units of the interrupted run (--resume), said on standard error.
  std::vector<T> restore(Get get) {
    done_ = get(ck.read());
    ck.resumed_from(count());
    std::cerr << "tmlab discover: resuming from " << ck.path().string() << ": " << count()
              << " taken from it, the rest runs\n";
    return done_;
  }
  /// Records a finished unit (a checkpoint when one is due).
  void finished(const T& unit) {
    done_.push_back(unit);
    ck.unit_finished(count());
  }

 private:
  std::string count() const { return std::to_string(done_.size()) + " finished " + noun_; }
  std::vector<T> done_;
  std::string noun_;

 public:
  UnitCheckpoint ck;
};

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

/// The page a reader opens first: what was found, the error before and after, the figures, each
/// step with its evidence, the diagnostics, the parameters.
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
    << cell(j["tests"]) << " tests (" << discover::stride_text(j["decimation_stride"].get<std::size_t>())
    << ").</p>\n";
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

std::string benchmark_text(const discover::BenchmarkResult& b) {
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

/// Every option of the loop that changes its result: part of what --resume must match.
nlohmann::json options_fingerprint(const discover::Options& o) {
  return {{"poisson", o.poisson},
          {"fix_poisson", o.fix_poisson},
          {"max_samples", o.max_samples},
          {"baseline", o.baseline_law + "+prony:" + std::to_string(o.baseline_prony)},
          {"rounds", o.max_rounds},
          {"bic_threshold", o.bic_threshold},
          {"held_out_ratio", o.held_out_ratio},
          {"starts", o.starts},
          {"threads", o.threads},
          {"seed", o.seed},
          {"alpha", o.thresholds.alpha},
          {"effects", o.effects}};
}

/// --checkpoint-every (default: every 60 s of wall time, and always at a stop request).
CheckpointSchedule checkpoint_schedule(const Parsed& p) {
  try {
    return p.has("--checkpoint-every") ? CheckpointSchedule::parse(p.get("--checkpoint-every"))
                                       : CheckpointSchedule{};
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
}

int run_benchmark_command(const Parsed& p, const discover::Options& o, const std::string& command_line) {
  const bool quick = p.has("--quick");
  const fs::path dir = p.has("--out") ? fs::path(p.get("--out"))
                                      : fs::path(tmlab_root()) / "results" / "discover" /
                                            (quick ? "benchmark-quick" : "benchmark");
  // A checkpoint after every finished set (docs/robustness.md); --resume reads it before the result
  // directory is touched.
  nlohmann::json fingerprint = options_fingerprint(o);
  fingerprint["benchmark"] = {{"quick", quick},
                              {"rig", p.has("--rig") ? p.get("--rig") : "all"},
                              {"only", p.has("--only") ? p.get("--only") : "all"}};
  discover::BenchmarkLog log;
  UnitList<discover::BenchmarkEntry> units(dir, "discover-benchmark", fingerprint, checkpoint_schedule(p),
                                           put_benchmark_entries, "benchmark set(s)");
  UnitCheckpoint& ck = units.ck;
  if (p.has("--resume")) {
    refuse_resume_of_complete(dir, "benchmark");
    log.restored = units.restore(get_benchmark_entries);
  }
  log.finished = [&units](const discover::BenchmarkEntry& e) { units.finished(e); };
  RunOutput out(dir, &std::cerr,
                p.has("--resume") ? RunOutput::Previous::ResumeInterrupted : RunOutput::Previous::Discard);
  try {
    ManifestInput mi;
    mi.command_line = split_words(command_line);
    mi.config = {{"quick", quick},
                 {"rig", p.has("--rig") ? p.get("--rig") : "all"},
                 {"only", p.has("--only") ? p.get("--only") : "all"},
                 {"seed", o.seed},
                 {"starts", o.starts},
                 {"threads", o.threads}};
    out.write_json("manifest.json", make_manifest(mi));
    auto sets = discover::benchmark_sets(quick);
    if (p.has("--rig")) {
      // Only the sets of the rigs named (e.g. to rerun the indentation sets alone).
      const std::string rigs = "," + p.get("--rig") + ",";
      std::vector<discover::SyntheticSet> kept;
      for (auto& s : sets)
        if (rigs.find("," + discover::to_string(s.rig) + ",") != std::string::npos)
          kept.push_back(std::move(s));
      if (kept.empty())
        throw UsageError(
            "--rig: no benchmark set on '" + p.get("--rig") +
            "' (unconfined_compression, sphere_indentation, uniaxial_tension, confined_compression)");
      sets = std::move(kept);
    }
    if (p.has("--only")) {
      // Only the sets whose truth is named (e.g. to rerun one effect's sets).
      const std::string only = "," + p.get("--only") + ",";
      std::vector<discover::SyntheticSet> kept;
      for (auto& s : sets)
        if (only.find("," + s.truth + ",") != std::string::npos) kept.push_back(std::move(s));
      if (kept.empty()) throw UsageError("--only: no benchmark set has the truth '" + p.get("--only") + "'");
      sets = std::move(kept);
    }
    if (p.has("--write-sets"))
      // Each set in the interchange format, so that `tmlab discover sets/NAME.csv` reruns one alone.
      for (const auto& s : sets) measured::write_data_set(s.data, out.staging_dir() / "sets");
    const discover::BenchmarkResult b = discover::run_benchmark(sets, o, &log);
    const nlohmann::json j = discover::to_json(b);
    out.write_json("benchmark.json", j);
    const std::string text = benchmark_text(b);
    {
      std::ofstream f(out.file("confusion_matrix.csv"));
      f << text.substr(text.find('\n') + 1);
      if (!f) throw Error("discover: cannot write " + out.file("confusion_matrix.csv").string());
    }
    std::cout << text << "library sets: " << b.library_correct << " / " << b.library_sets
              << " right (diagonal fraction " << significant(b.diagonal_fraction, 3) << "; "
              << b.library_exact << " with the exact law, no family credit)\n"
              << "noise-only sets: " << b.noise_false_positives << " false positives of " << b.noise_sets
              << "\n"
              << "outside-library sets: " << b.outside_flagged << " of " << b.outside_sets
              << " flagged as unexplained structure, " << b.outside_forced << " with an effect added\n"
              << "median error reduction (library sets): " << significant(100.0 * b.median_error_reduction, 3)
              << " %\n";
    ck.remove();  // a complete result holds no checkpoint
    out.finalize({{"diagonal_fraction", b.diagonal_fraction},
                  {"noise_only_false_positives", b.noise_false_positives},
                  {"outside_library_flagged", b.outside_flagged},
                  {"median_error_reduction", b.median_error_reduction}});
    std::cout << "written: " << out.dir().string() << "/ (benchmark.json, confusion_matrix.csv)\n";
  } catch (const Interrupted& e) {
    const Interrupted stopped = ck.stopped(e);
    out.abandon(stopped);
    throw stopped;
  } catch (const std::exception& e) {
    out.abandon(e);
    throw;
  }
  return 0;
}

}  // namespace

namespace {

/// discover.h5: per test the data, the baseline's and the final model's forces (and the FE refits').
void write_discover_h5(const fs::path& path, const discover::Report& r,
                       const std::vector<discover::FeRefit>& fe_refits) {
  H5File h5 = H5File::create(path.string());
  for (std::size_t k = 0; k < r.data.series.size(); ++k) {
    const discover::Series& s = r.data.series[k];
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

/// The error before and after, each accepted effect and the FE refits, on stdout.
void print_discover_report(const discover::Report& r, const std::vector<discover::FeRefit>& fe_refits) {
  std::cout << "baseline " << r.baseline.structure.label() << ": RMS " << significant(r.baseline.fit.rms, 4)
            << " N (" << significant(r.baseline.fit.rms_percent_peak, 3) << " % of peak), max "
            << significant(r.baseline.max_abs, 4) << " N\n";
  for (const auto& s : r.steps)
    if (s.accepted)
      std::cout << "round " << s.round << (s.removal ? ": removed " : ": added ") << s.effect << " ("
                << s.reason << ")\n";
  std::cout << "final " << r.final.structure.label() << ": RMS " << significant(r.final.fit.rms, 4) << " N ("
            << significant(r.final.fit.rms_percent_peak, 3) << " % of peak), max "
            << significant(r.final.max_abs, 4) << " N\n"
            << "unexplained structure: " << (r.unexplained ? "yes: " + r.signature : std::string("no"))
            << "\n";
  for (const auto& fr : fe_refits)
    std::cout << "FE rig " << fr.which << " " << fr.model << ": "
              << (fr.done ? "RMS " + significant(fr.fit.rms, 4) + " N refitted (" +
                                significant(fr.fe_rms_at_closed_form, 4) + " N at the closed-form optimum)"
                          : "not refitted: " + fr.why_not)
              << "\n";
}

/// tmlab discover DATA.csv: the loop, its FE refits (--forward fe_rig), report.json, discover.h5,
/// the plots and index.html.
int run_discover_command(const Parsed& p, discover::Options o, const std::string& forward,
                         const discover::FeRefitOptions& fe, const std::string& command_line) {
  const fs::path csv = p.positional[0];
  const measured::DataSet data = measured::read_data_set(csv);
  measured::check_force_sign(data, csv.string());  // the check tmlab fit makes (one rule)
  const fs::path dir = p.has("--out") ? fs::path(p.get("--out"))
                                      : fs::path(tmlab_root()) / "results" / "discover" / data.meta.name;
  if (!p.has("--out")) {
    const std::string why = result_name_problem(data.meta.name);
    if (!why.empty()) throw Error("discover: result name: " + why);
  }
  // A checkpoint after every fit of the loop (and of the FE refits) (docs/robustness.md); --resume
  // reads it before the result directory is touched.
  nlohmann::json fingerprint = options_fingerprint(o);
  fingerprint["forward"] = forward;
  if (forward == "fe_rig")
    fingerprint["fe_rig"] = {{"mesh", {fe.mesh.cells, fe.mesh.layers}},
                             {"substeps", fe.substeps},
                             {"iterations", fe.max_iterations},
                             {"max_samples", fe.max_samples}};
  fingerprint["data"] = {{"csv", file_hash(csv)}, {"metadata", file_hash(measured::metadata_path(csv))}};
  discover::FitLog log;
  UnitList<discover::FitOutcome> units(dir, "discover", fingerprint, checkpoint_schedule(p), put_fit_outcomes,
                                       "fit(s)");
  UnitCheckpoint& ck = units.ck;
  if (p.has("--resume")) {
    refuse_resume_of_complete(dir, "discovery");
    log.restored = units.restore(get_fit_outcomes);
  }
  log.finished = [&units](const discover::FitOutcome& f) { units.finished(f); };
  o.fit_log = &log;
  RunOutput out(dir, &std::cerr,
                p.has("--resume") ? RunOutput::Previous::ResumeInterrupted : RunOutput::Previous::Discard);
  try {
    ManifestInput mi;
    mi.command_line = split_words(command_line);
    mi.config = {{"poisson", o.poisson},
                 {"fix_poisson", o.fix_poisson},
                 {"max_samples", o.max_samples},
                 {"rounds", o.max_rounds},
                 {"starts", o.starts},
                 {"threads", o.threads},
                 {"seed", o.seed},
                 {"effects", o.effects},
                 {"bic_threshold", o.bic_threshold},
                 {"held_out_ratio", o.held_out_ratio},
                 {"alpha", o.thresholds.alpha},
                 {"forward", forward}};
    mi.input_files = {csv, measured::metadata_path(csv)};
    out.write_json("manifest.json", make_manifest(mi));
    const discover::Report r = discover::run(data, o);
    nlohmann::json j = discover::to_json(r);
    std::vector<discover::FeRefit> fe_refits;
    if (forward == "fe_rig") {
      fe_refits = discover::fe_rig_refit(data, r, o, fe);
      j["fe_rig"] = discover::to_json(fe_refits, r.data.peak_force, fe);
    }
    out.write_json("report.json", j);
    write_discover_h5(out.file("discover.h5"), r, fe_refits);
    bool plots_ok = false;
    std::string plots = "skipped (--no-plots)";
    if (!p.has("--no-plots")) {
      const ProcessStatus ps = run_python(
          fs::path(tmlab_root()) / "calibration" / "discover" / "python" / "tmlab_discover_plot.py",
          {out.staging_dir().string()}, ProcessOutput::discard());
      plots_ok = ps.ok();
      plots = ps.ok() ? "ok" : "failed (" + ps.describe() + ")";
      if (!ps.ok()) std::cerr << "tmlab discover: plots " << plots << "\n";
    }
    {
      std::ofstream f(out.file("index.html"));
      f << report_html(j, plots_ok);
      if (!f) throw Error("discover: cannot write " + out.file("index.html").string());
    }
    print_discover_report(r, fe_refits);
    ck.remove();  // a complete result holds no checkpoint
    out.finalize({{"selected_effects", r.selected},
                  {"unexplained_structure", r.unexplained},
                  {"baseline_rms_N", r.baseline.fit.rms},
                  {"final_rms_N", r.final.fit.rms},
                  {"plots", plots}});
    std::cout << "written: " << out.dir().string()
              << "/ (index.html, report.json, discover.h5, manifest.json, summary.json"
              << (plots_ok ? ", discover_*.png" : "") << ")\n";
  } catch (const Interrupted& e) {
    const Interrupted stopped = ck.stopped(e);
    out.abandon(stopped);
    throw stopped;
  } catch (const std::exception& e) {
    out.abandon(e);
    throw;
  }
  return 0;
}

}  // namespace

int cmd_discover(const std::vector<std::string>& args, const std::string& command_line) {
  const Parsed p = parse(args,
                         {"--out", "--poisson", "--max-samples", "--rounds", "--starts", "--threads",
                          "--seed", "--effects", "--baseline-prony", "--rig", "--only", "--forward", "--mesh",
                          "--substeps", "--fe-iterations", "--fe-max-samples", "--checkpoint-every"},
                         {"--benchmark", "--quick", "--write-sets", "--free-poisson", "--no-plots", "--quiet",
                          "--resume", "--no-test-control"});
  discover::Options o;
  auto whole = [&](const std::string& key, int fallback, int lo, int hi) {
    return p.has(key) ? int(parse_whole(key, p.get(key), lo, hi)) : fallback;
  };
  o.max_samples = std::size_t(whole("--max-samples", int(o.max_samples), 50, 1000000));
  o.max_rounds = whole("--rounds", o.max_rounds, 1, 20);
  o.starts = whole("--starts", o.starts, 1, 1000);
  o.threads = whole("--threads", 2, 1, 64);
  o.seed = (unsigned long)whole("--seed", 1, 1, 1000000);
  o.baseline_prony = whole("--baseline-prony", o.baseline_prony, 0, 4);
  if (p.has("--poisson")) {
    o.poisson = parse_double("--poisson", p.get("--poisson"));
    if (!(o.poisson > 0.0 && o.poisson < 0.4999)) throw UsageError("--poisson must lie in (0, 0.4999)");
  }
  o.fix_poisson = !p.has("--free-poisson");
  o.test_control = !p.has("--no-test-control");
  if (p.has("--effects")) {
    std::string s = p.get("--effects");
    std::size_t a = 0;
    for (;;) {
      const std::size_t b = s.find(',', a);
      const std::string e = s.substr(a, b == std::string::npos ? std::string::npos : b - a);
      discover::effect_info(e);  // tmlab::Error naming the known effects
      o.effects.push_back(e);
      if (b == std::string::npos) break;
      a = b + 1;
    }
  }
  const std::string forward = p.get("--forward", "closed_form");
  if (forward != "closed_form" && forward != "fe_rig")
    throw UsageError("--forward must be closed_form or fe_rig (got '" + forward + "')");
  discover::FeRefitOptions fe;
  if (p.has("--mesh")) {
    const std::string m = p.get("--mesh");
    const std::size_t comma = m.find(',');
    if (comma == std::string::npos) throw UsageError("--mesh needs CELLS,LAYERS, got '" + m + "'");
    fe.mesh.cells = int(parse_whole("--mesh CELLS", m.substr(0, comma), 2, 400));
    fe.mesh.layers = int(parse_whole("--mesh LAYERS", m.substr(comma + 1), 1, 400));
  }
  fe.substeps = whole("--substeps", fe.substeps, 1, 100);
  fe.max_iterations = whole("--fe-iterations", fe.max_iterations, 1, 200);
  fe.max_samples = std::size_t(whole("--fe-max-samples", int(fe.max_samples), 20, 1000000));
  if (forward != "fe_rig" &&
      (p.has("--mesh") || p.has("--substeps") || p.has("--fe-iterations") || p.has("--fe-max-samples")))
    throw UsageError("--mesh, --substeps, --fe-iterations and --fe-max-samples are for --forward fe_rig");
  if (!p.has("--quiet"))
    o.progress = [](const std::string& line) { std::cerr << line << "\n" << std::flush; };
  if (p.has("--benchmark")) {
    if (!p.positional.empty()) throw UsageError("discover --benchmark takes no DATA.csv");
    if (forward != "closed_form") throw UsageError("--forward fe_rig is for one DATA.csv, not --benchmark");
    return run_benchmark_command(p, o, command_line);
  }
  if (p.has("--quick") || p.has("--rig") || p.has("--only") || p.has("--write-sets"))
    throw UsageError("--quick, --rig, --only and --write-sets are for --benchmark");
  if (p.positional.size() != 1) throw UsageError("discover needs exactly one DATA.csv (or --benchmark)");
  return run_discover_command(p, o, forward, fe, command_line);
}

}  // namespace tmlab::cli
