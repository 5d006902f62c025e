// Section IV-A of Xu et al. 2011 redone with error bars (paper_fit.hpp explains the study).
#include "studies/paper/paper_fit.hpp"

#include "calibration/closed_forms/indentation.hpp"
#include "calibration/fit/fit_output.hpp"
#include "calibration/fit/fitter.hpp"
#include "calibration/fit/relaxation_bands.hpp"
#include "calibration/fit/rig_forward_model.hpp"
#include "calibration/fit/surrogates.hpp"
#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/base/interrupt.hpp"
#include "core/config/config_reader.hpp"
#include "core/io/atomic_file.hpp"
#include "core/io/hdf5_file.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "studies/common/study_plot.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <ostream>
#include <random>
#include <sstream>

namespace tmlab::tm {

namespace {

namespace fs = std::filesystem;
namespace ms = tmlab::measured;
using nlohmann::json;

json num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

std::string mm(double d) { return significant(d * 1e3, 4) + "mm"; }

bool elastic_target(const std::string& t) { return t == "fig2" || t == "table1"; }

}  // namespace

bool is_paper_fit_target(const std::string& t) {
  return t == "fig2" || t == "fig3" || t == "table1" || t == "table2";
}

std::vector<double> paper_reference_force(const PaperFitSettings& s, bool visco, const ms::Test& t) {
  if (!visco) {
    std::vector<double> f;
    for (const double d : t.displacement_m)
      f.push_back(closed_forms::hertz_force(s.young, s.poisson, s.indenter_radius, d));
    return f;
  }
  closed_forms::RelaxationModulus m;
  m.e_inf = s.young;
  m.moduli = s.prony_moduli;
  m.taus = s.prony_taus;
  return closed_forms::lee_radok_sphere(m, s.poisson, s.indenter_radius, {t.time_s, t.displacement_m});
}

ms::DataSet paper_reference_data(const PaperFitSettings& s, bool visco, std::size_t k) {
  if (visco && !s.viscoelastic()) throw Error("paper: the viscoelastic targets need reference.prony");
  const double depth = s.depths.at(k);
  ms::DataSet d;
  d.meta.name = std::string(visco ? "lee_radok" : "hertz") + "_" + mm(depth);
  d.meta.test = ms::TestType::indentation;
  d.meta.indenter = ms::Indenter{ms::IndenterShape::sphere, s.indenter_radius, std::nullopt};
  d.meta.sample.shape = ms::SampleShape::half_space;
  d.meta.source =
      std::string("synthetic: ") + (visco ? "Lee-Radok" : "Hertz") +
      " reference of tmlab paper (parameters of cases/paper/xu2011_indentation.json, not the paper's)";
  d.meta.license = "CC0-1.0";
  ms::Test t;
  t.id = mm(depth);
  // Ramp samples uniform in time; hold samples quadratically spaced (dense early, where the short
  // relaxation time acts). The elastic reference has the ramp only (time plays no part).
  for (int i = 0; i <= s.ramp_samples; ++i) {
    t.time_s.push_back(s.ramp * i / s.ramp_samples);
    t.displacement_m.push_back(depth * i / s.ramp_samples);
  }
  if (visco)
    for (int i = 1; i <= s.hold_samples; ++i) {
      const double q = double(i) / s.hold_samples;
      t.time_s.push_back(s.ramp + s.hold * q * q);
      t.displacement_m.push_back(depth);
    }
  t.force_N = paper_reference_force(s, visco, t);
  double peak = 0.0;
  for (const double f : t.force_N) peak = std::max(peak, std::abs(f));
  std::mt19937_64 rng(s.seed + 1000 * (visco ? 1 : 0) + k);
  std::normal_distribution<double> noise(0.0, s.noise_percent / 100.0 * peak);
  for (std::size_t i = 1; i < t.force_N.size(); ++i) t.force_N[i] += noise(rng);  // t = 0: at rest, exact
  d.tests.push_back(std::move(t));
  return d;
}

std::vector<double> patch_graded_coordinates(double lo, double hi, double focus, double w, int np, int no) {
  if (!(lo < hi) || focus < lo || focus > hi || !(w > 0.0) || np < 1 || no < 1)
    throw Error("patch_graded_coordinates: bad interval, patch or cell counts");
  const double h = w / np;
  // One side of the focus, length L: np cells of size h (fewer if L is short), then `no` cells
  // growing by a ratio q with h sum_{i=1..no} q^i = L - w (bisection on q).
  auto side = [&](double L) {
    std::vector<double> c;  // distances from the focus, increasing, ending at L
    if (L <= 0.0) return c;
    if (L <= w * (1.0 + 1e-9)) {
      const int n = std::max(1, int(std::ceil(L / h - 1e-9)));
      for (int i = 1; i <= n; ++i) c.push_back(L * i / n);
      return c;
    }
    for (int i = 1; i <= np; ++i) c.push_back(h * i);
    const double rest = L - w;
    auto total = [&](double q) {
      double s = 0.0, p = 1.0;
      for (int i = 1; i <= no; ++i) s += h * (p *= q);
      return s;
    };
    double qa = 1e-3, qb = 1.0;
    while (total(qb) < rest) qb *= 2.0;
    for (int it = 0; it < 200; ++it) {
      const double qm = 0.5 * (qa + qb);
      (total(qm) < rest ? qa : qb) = qm;
    }
    double x = w, p = 1.0;
    for (int i = 1; i < no; ++i) c.push_back(x += h * (p *= qb));
    c.push_back(L);
    return c;
  };
  std::vector<double> out;
  const auto left = side(focus - lo), right = side(hi - focus);
  for (auto it = left.rbegin(); it != left.rend(); ++it) out.push_back(focus - *it);
  out.push_back(focus);
  for (const double x : right) out.push_back(focus + x);
  out.front() = lo;
  out.back() = hi;
  return out;
}

Mesh paper_fit_mesh(const rigs::RigSpec& s, double patch_factor, int patch_cells, int outer_cells) {
  if (s.shape != rigs::SampleShape::Block || s.test != rigs::RigTest::Indentation)
    throw Error("paper_fit_mesh: an indentation block rig is needed");
  const double a = std::sqrt(s.indenter_radius * s.history.peak());
  const double w = patch_factor * a;
  BoxGrid grid;
  grid[0] = patch_graded_coordinates(-0.5 * s.size_x, 0.5 * s.size_x, s.cx, w, patch_cells, outer_cells);
  grid[1] = patch_graded_coordinates(-0.5 * s.size_y, 0.5 * s.size_y, s.cy, w, patch_cells, outer_cells);
  grid[2] = patch_graded_coordinates(0.0, s.height, s.height, w, patch_cells, outer_cells);
  Mesh mesh = make_box_mesh(grid);
  for (PhysicalGroup& g : mesh.groups) {  // the names rigs::rig_mesh (make_block_mesh) gives the faces
    if (g.dim == 2 && g.tag == kBoxZmin) g.name = "bottom";
    if (g.dim == 2 && g.tag == kBoxZmax) g.name = "top";
  }
  return mesh;
}

fit::RigForwardModelOptions paper_fe_rig_options(const PaperFitSettings& s) {
  fit::RigForwardModelOptions fe;
  fe.substeps = s.substeps;
  fe.contact_stiffness_factor = s.contact_stiffness_factor;
  fe.newton_max_iterations = s.newton_max_iterations;
  const double pf = s.patch_factor;
  const int np = s.patch_cells, no = s.outer_cells;
  fe.mesh_builder = [pf, np, no](const rigs::RigSpec& r) { return paper_fit_mesh(r, pf, np, no); };
  return fe;
}

std::string paper_fit_spec(const PaperFitSettings& s, const std::string& law, bool visco) {
  return law + (visco ? "+prony:" + std::to_string(s.prony_moduli.size()) : "") +
         ",poisson=" + significant(s.poisson, 6);
}

fit::Problem paper_fit_problem(const PaperFitSettings& s, const std::string& kind, const std::string& law,
                               bool visco, const ms::DataSet& data) {
  const fit::ModelSpec spec = fit::parse_model_spec(paper_fit_spec(s, law, visco));
  fit::RigForwardModelOptions fe = paper_fe_rig_options(s);
  if (visco) fe.jacobian_step = s.relaxation.jacobian_step;
  fit::Problem pr = kind == "closed_form" ? fit::make_surrogate_problem(data, spec)
                                          : fit::make_rig_forward_problem(data, spec, {}, {}, fe);
  if (visco && s.relaxation.time_floor > 0.0)
    fit::band_relaxation_times(
        pr.parameters, spec, fit::relaxation_range(data, s.relaxation.time_floor, s.relaxation.time_ceiling));
  return pr;
}

double paper_truth(const PaperFitSettings& s, const std::string& name) {
  if (name == "young") return s.young;
  if (name == "poisson") return s.poisson;
  for (std::size_t j = 0; j < s.prony_moduli.size(); ++j) {
    if (name == "e" + std::to_string(j + 1)) return s.prony_moduli[j];
    if (name == "tau" + std::to_string(j + 1)) return s.prony_taus[j];
  }
  return std::nan("");
}

namespace {

/// One identification: a kind ("closed_form" or "tensor_mass"), a law, a depth.
struct FitJob {
  std::string kind, law;
  std::size_t depth_index = 0;
  std::string id() const { return kind + "_" + law; }
};

json run_fit(const FitJob& job, const PaperFitSettings& s, bool visco, std::ostream* log) {
  const ms::DataSet data = paper_reference_data(s, visco, job.depth_index);
  const std::string spec_text = paper_fit_spec(s, job.law, visco);
  fit::Problem pr = paper_fit_problem(s, job.kind, job.law, visco, data);
  fit::FitOptions fo;
  fo.threads = s.threads;
  fo.profile = false;  // each profile point is a full re-fit: too dear for FE indentation
  fo.max_iterations = s.max_iterations;
  if (visco) {
    if (s.relaxation.max_iterations > 0) fo.max_iterations = s.relaxation.max_iterations;
    fo.xtol = s.relaxation.xtol;
  }
  fo.seed = s.seed;
  if (job.kind == "closed_form") {
    fo.starts = std::max(12, s.starts);
    fo.local_runs = 3;
  } else {
    fo.starts = s.starts;
    fo.local_runs = s.local_runs;
  }
  json j = {{"kind", job.kind},
            {"law", job.law},
            {"depth_m", s.depths[job.depth_index]},
            {"spec", spec_text},
            {"forward_model", pr.model->name()},
            {"description", pr.model->description()}};
  const ms::Test& t = data.tests.front();
  j["time_s"] = t.time_s;
  j["displacement_m"] = t.displacement_m;
  j["force_N"] = t.force_N;
  j["reference_force_N"] = paper_reference_force(s, visco, t);
  const auto t0 = std::chrono::steady_clock::now();
  const std::clock_t c0 =
      std::clock();  // process CPU time: every thread of this fit (fits run one at a time)
  try {
    const fit::FitResult r = fit::fit(pr, fo);
    j["status"] = "ok";
    j["parameters"] = json::array();
    for (std::size_t i = 0; i < r.parameters.size(); ++i) {
      const fit::ParameterResult& p = r.parameters[i];
      const double truth = paper_truth(s, p.name);
      json q = fit::parameter_json(p, &pr.parameters.at(i));  // as in fit.json
      q["truth"] = num(truth);
      q["truth_inside_interval"] =
          !p.fixed && std::isfinite(truth) && truth >= p.lower95 && truth <= p.upper95;
      j["parameters"].push_back(q);
    }
    j["model_force_N"] = r.prediction;
    j["residual_rms_N"] = r.rms;
    j["residual_rms_percent_of_peak"] = r.rms_percent_peak;
    j["forward_solves"] = r.forward_solves;
    j["forward_effort"] = r.model_effort;
    j["surrogate_solves"] = r.global_solves;
    j["local_iterations"] = r.iterations;
    j["stop_reason"] = r.stop_reason;
    json conf = json::array();
    for (const auto& c : r.confounded)
      conf.push_back({{"a", c.a}, {"b", c.b}, {"correlation", c.correlation}});
    j["confounded"] = conf;
    j["notes"] = r.notes;
  } catch (const Interrupted&) {
    throw;
  } catch (const Error& e) {
    // A model that cannot follow the curve (no converged solve at any start) is a finding, not a
    // crash of the study: it is reported as such.
    j["status"] = "failed";
    j["reason"] = e.what();
  }
  j["wall_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  j["cpu_seconds"] = double(std::clock() - c0) / CLOCKS_PER_SEC;
  if (log)
    *log << "tmlab paper: " << job.id() << " at " << mm(s.depths[job.depth_index]) << ": "
         << j["status"].get<std::string>() << " (" << significant(j["wall_seconds"].get<double>(), 3) << " s"
         << (j.value("forward_effort", std::string()).empty() ? ""
                                                              : "; " + j["forward_effort"].get<std::string>())
         << ")\n";
  return j;
}

const json* param(const json& fitj, const std::string& name) {
  if (!fitj.contains("parameters")) return nullptr;
  for (const auto& p : fitj["parameters"])
    if (p["name"] == name) return &p;
  return nullptr;
}

double value_of(const json& fitj, const std::string& name) {
  const json* p = param(fitj, name);
  return p ? (*p)["value"].get<double>() : std::nan("");
}

std::string value_se(const json& fitj, const std::string& name, double scale) {
  const json* p = param(fitj, name);
  if (!p) return "-";
  std::string v = significant((*p)["value"].get<double>() * scale, 4);
  if ((*p)["fixed"].get<bool>()) return v + " (fixed)";
  const json& se = (*p)["standard_error"];
  const std::string edge = p->value("at_bound", std::string());
  return v + " ± " + (se.is_null() ? std::string("inf") : significant(se.get<double>() * scale, 2)) +
         (edge.empty() ? "" : " (at " + edge + " bound)");
}

/// The CPU seconds of a fit ("-" for a fit file written before they were recorded).
std::string cpu_of(const json& f) {
  return f.contains("cpu_seconds") ? significant(f["cpu_seconds"].get<double>(), 3) : std::string("-");
}

}  // namespace

json usable_depth(const PaperFitSettings& s, const std::vector<json>& fits) {
  auto find = [&](const std::string& law, std::size_t k) -> const json* {
    for (const auto& f : fits)
      if (f["kind"] == "tensor_mass" && f["law"] == law && f["depth_m"].get<double>() == s.depths[k])
        return &f;
    return nullptr;
  };
  json rows = json::array();
  double e0 = std::nan("");
  std::string first_bad;
  double last_good = 0.0;
  for (std::size_t k = 0; k < s.depths.size(); ++k) {
    const json* st = find("stvk", k);
    if (!st) continue;
    json row = {{"depth_m", s.depths[k]}};
    std::vector<std::string> why;
    if ((*st)["status"] != "ok") {
      why.push_back("no converged fit: " + (*st)["reason"].get<std::string>());
    } else {
      const std::string stop = st->value("stop_reason", std::string());
      row["converged"] = fit::converged_stop(stop);
      if (!fit::converged_stop(stop)) why.push_back("the fit did not converge (stop: " + stop + ")");
      const double e = value_of(*st, "young"), rms = (*st)["residual_rms_percent_of_peak"].get<double>();
      if (std::isnan(e0)) e0 = e;
      const double drift = 100.0 * (e / e0 - 1.0);
      row["young_Pa"] = e;
      row["rms_percent"] = rms;
      row["drift_percent"] = drift;
      if (rms > s.max_rms_percent)
        why.push_back("residual RMS " + significant(rms, 3) + " % of peak > " +
                      significant(s.max_rms_percent, 3));
      if (std::abs(drift) > s.max_drift_percent)
        why.push_back("E drifts " + significant(drift, 3) + " % from the shallowest depth's");
      if (const json* nh = find("neo_hookean", k); nh && (*nh)["status"] == "ok") {
        const double diff = 100.0 * (e / value_of(*nh, "young") - 1.0);
        row["difference_to_neo_hookean_percent"] = diff;
        if (std::abs(diff) > s.max_law_difference_percent)
          why.push_back("E differs " + significant(diff, 3) + " % from the neo-Hookean E on the same rig");
      }
    }
    row["usable"] = why.empty();
    row["reasons"] = why;
    if (why.empty() && first_bad.empty()) last_good = s.depths[k];
    if (!why.empty() && first_bad.empty()) first_bad = mm(s.depths[k]);
    rows.push_back(row);
  }
  std::string statement;
  if (rows.empty())
    statement = "St VK was not fitted (identification.laws)";
  else if (first_bad.empty())
    statement = "St VK is usable at every depth studied (up to " + mm(s.depths.back()) + ")";
  else
    statement =
        "St VK stops being usable at " + first_bad +
        (last_good > 0.0 ? " (usable up to " + mm(last_good) + ")" : " (not usable at any depth studied)");
  return {{"statement", statement},
          {"criteria",
           {{"max_rms_percent", s.max_rms_percent},
            {"max_drift_percent", s.max_drift_percent},
            {"max_law_difference_percent", s.max_law_difference_percent}}},
          {"depths", rows}};
}

namespace {

std::string table_markdown(const std::string& table, const PaperFitSettings& s, bool visco,
                           const std::vector<json>& fits, const json& usable) {
  std::ostringstream md;
  md << "# " << (table == "table1" ? "Table I" : "Table II") << " (Xu et al. 2011, Section IV-A) reproduced: "
     << (visco ? "relaxation (Lee-Radok reference)" : "elastic (Hertz reference)") << "\n\n"
     << "Reference curves: "
     << (visco ? "Lee-Radok, ramp " + significant(s.ramp, 3) + " s and hold " + significant(s.hold, 3) + " s"
               : "Hertz")
     << ", sphere R = " << significant(s.indenter_radius * 1e3, 4)
     << " mm on a half-space, E_inf = " << significant(s.young, 5)
     << " Pa, nu = " << significant(s.poisson, 3);
  for (std::size_t j = 0; j < s.prony_moduli.size() && visco; ++j)
    md << ", e" << j + 1 << " = " << significant(s.prony_moduli[j], 5) << " Pa, tau" << j + 1 << " = "
       << significant(s.prony_taus[j], 4) << " s";
  md << ", noise " << significant(s.noise_percent, 3)
     << " % of peak: OUR liver-range parameter set (cases/paper/xu2011_indentation.json), not Samur's or "
        "Nava's, "
        "which are not available. nu is fixed at the reference value in every fit (force data see only "
        "E/(1-nu^2)). "
        "Values are value ± standard error (SE from the Jacobian at the optimum, residual-variance "
        "scaled).\n\n";
  std::vector<std::string> names = {"young"};
  if (visco)
    for (std::size_t j = 0; j < s.prony_moduli.size(); ++j) {
      names.push_back("e" + std::to_string(j + 1));
      names.push_back("tau" + std::to_string(j + 1));
    }
  md << "| depth | identified by | law |";
  for (const auto& n : names) md << " " << n << (n.rfind("tau", 0) == 0 ? " [s]" : " [Pa]") << " |";
  md << " RMS % peak | truth in 95 % | forward solves | wall s | CPU s |\n|---|---|---|";
  for (std::size_t i = 0; i < names.size(); ++i) md << "---|";
  md << "---|---|---|---|---|\n";
  md << "| (truth) | generating values | |";
  for (const auto& n : names) md << " " << significant(paper_truth(s, n), 5) << " |";
  md << " | | | | |\n";
  for (const auto& f : fits) {
    md << "| " << significant(f["depth_m"].get<double>() * 1e3, 3) << " mm | "
       << (f["kind"] == "closed_form" ? std::string(visco ? "Lee-Radok (check)" : "Hertz (check)")
                                      : std::string("tensor-mass FE rig"))
       << " | " << f["law"].get<std::string>() << " |";
    if (f["status"] != "ok") {
      for (std::size_t i = 0; i < names.size(); ++i) md << " failed |";
      md << " - | - | - | " << significant(f["wall_seconds"].get<double>(), 3) << " | " << cpu_of(f)
         << " |\n";
      continue;
    }
    int inside = 0, total = 0;
    for (const auto& p : f["parameters"])
      if (!p["fixed"].get<bool>()) {
        ++total;
        inside += p["truth_inside_interval"].get<bool>() ? 1 : 0;
      }
    for (const auto& n : names) md << " " << value_se(f, n, 1.0) << " |";
    md << " " << significant(f["residual_rms_percent_of_peak"].get<double>(), 3) << " | " << inside << "/"
       << total << " | " << f["forward_solves"].get<long>() << " (+" << f["surrogate_solves"].get<long>()
       << " closed form) | " << significant(f["wall_seconds"].get<double>(), 3) << " | " << cpu_of(f)
       << " |\n";
  }
  md << "\n**St VK usable depth.** " << usable["statement"].get<std::string>()
     << ". Criteria: residual RMS <= " << significant(s.max_rms_percent, 3)
     << " % of peak, |E(d)/E(shallowest) - 1| <= " << significant(s.max_drift_percent, 3)
     << " %, |E_stvk/E_neo_hookean - 1| <= " << significant(s.max_law_difference_percent, 3)
     << " % on the same rig.\n\n";
  md << "| depth | E stvk [Pa] | RMS % | drift % | stvk vs neo-Hookean % | usable | why not "
        "|\n|---|---|---|---|---|---|---|\n";
  for (const auto& r : usable["depths"]) {
    auto opt = [&](const char* k) {
      return r.contains(k) ? significant(r[k].get<double>(), 4) : std::string("-");
    };
    std::string why;
    for (const auto& w : r["reasons"]) why += (why.empty() ? "" : "; ") + w.get<std::string>();
    md << "| " << significant(r["depth_m"].get<double>() * 1e3, 3) << " mm | " << opt("young_Pa") << " | "
       << opt("rms_percent") << " | " << opt("drift_percent") << " | "
       << opt("difference_to_neo_hookean_percent") << " | " << (r["usable"].get<bool>() ? "yes" : "no")
       << " | " << why << " |\n";
  }
  md << "\nThe tensor-mass rows are biased by the FE rig's discretisation (a finite block for the "
        "half-space, "
        "a coarse contact patch): compare laws on the same rig, and see docs/paper-experiments.md for the "
        "mesh's own error against Hertz.\n";
  return md.str();
}

}  // namespace

json run_paper_fit(const std::string& target, const PaperFitSettings& s, const PaperFitOptions& o,
                   const fs::path& dir) {
  if (!is_paper_fit_target(target))
    throw Error("unknown paper target '" + target + "' (expected fig2, fig3, table1 or table2)");
  const bool visco = !elastic_target(target);
  if (visco && !s.viscoelastic()) throw Error(o.params_file + ": " + target + " needs reference.prony");
  const std::string table = visco ? "table2" : "table1", figure = visco ? "fig3" : "fig2";
  std::vector<FitJob> jobs;
  for (std::size_t k = 0; k < s.depths.size(); ++k)
    for (const char* kind : {"closed_form", "tensor_mass"})
      for (const auto& law : s.laws) {
        if (std::string(kind) == "closed_form" && law != s.laws.front()) continue;  // one check per depth
        jobs.push_back({kind, law, k});
      }
  fs::create_directories(dir / "fits");
  std::vector<json> fits;
  std::size_t n = 0;
  for (const auto& job : jobs) {
    ++n;
    const fs::path file = dir / "fits" / (job.id() + "_" + mm(s.depths[job.depth_index]) + ".json");
    if (o.resume && fs::exists(file)) {
      std::ifstream in(file);
      fits.push_back(json::parse(in));
      if (o.log)
        *o.log << "tmlab paper " << target << ": " << file.filename().string()
               << " finished before: reused\n";
      continue;
    }
    try {
      check_interrupt("tmlab paper " + target);
    } catch (const Interrupted& e) {
      throw Interrupted(e.signal(), std::string(e.what()) + " (" + std::to_string(n - 1) + " of " +
                                        std::to_string(jobs.size()) +
                                        " fits finished): continue with the same command and --resume");
    }
    if (o.log) *o.log << "tmlab paper " << target << ": fit " << n << "/" << jobs.size() << "\n";
    json f = run_fit(job, s, visco, o.log);
    write_file_atomically(file, f.dump(1) + "\n");
    fits.push_back(std::move(f));
  }
  const json usable = usable_depth(s, fits);
  // Solve counts: FE solves of the tensor-mass fits; closed-form solves of the checks and of the
  // FE fits' global stage.
  long solves = 0, surrogate = 0;
  double wall = 0.0, cpu = 0.0;
  for (const auto& f : fits) {
    const long fs_ = f.value("forward_solves", 0L), ss = f.value("surrogate_solves", 0L);
    if (f["kind"] == "tensor_mass") {
      solves += fs_;
      surrogate += ss;
    } else {
      surrogate += fs_;
    }
    wall += f["wall_seconds"].get<double>();
    cpu += f.value("cpu_seconds", 0.0);
  }
  json all = {{"target", target},      {"table", table}, {"figure", figure},      {"params", o.params_file},
              {"viscoelastic", visco}, {"fits", fits},   {"usable_depth", usable}};
  write_file_atomically(dir / "paper_fit.json", all.dump(1) + "\n");
  // The table: markdown for reading, JSON for machines (value, SE, interval, truth per parameter).
  json tj = {{"table", table}, {"rows", json::array()}, {"usable_depth", usable}};
  for (const auto& f : fits) {
    json row = {{"depth_m", f["depth_m"]},
                {"kind", f["kind"]},
                {"law", f["law"]},
                {"status", f["status"]},
                {"wall_seconds", f["wall_seconds"]}};
    for (const char* k : {"parameters", "residual_rms_percent_of_peak", "forward_solves", "surrogate_solves",
                          "forward_effort", "cpu_seconds", "reason"})
      if (f.contains(k)) row[k] = f[k];
    tj["rows"].push_back(row);
  }
  write_file_atomically(dir / (table + ".json"), tj.dump(1) + "\n");
  write_file_atomically(dir / (table + ".md"), table_markdown(table, s, visco, fits, usable));
  json summary = {{"target", target},
                  {"fits", fits.size()},
                  {"fe_forward_solves", solves},
                  {"closed_form_solves", surrogate},
                  {"fit_wall_seconds", wall},
                  {"fit_cpu_seconds", cpu},
                  {"usable_depth", usable["statement"]},
                  {"plots", "skipped (--no-plots)"}};
  if (o.plots) {
    const ProcessStatus ps = draw_study_plot(o.tmlab_root, "paper", "tmlab_paper_fit_figure.py", dir);
    if (!ps.ok()) throw Error("drawing " + figure + " failed (" + ps.describe() + ")");
    summary["plots"] = "ok";
  }
  return summary;
}

}  // namespace tmlab::tm
