// `tmlab paper fig2|fig3|table1|table2` (Section IV-A): the study's mesh, reference curves and
// settings, and the identification in quick mode (the committed parameter file's "quick" block, cut
// further here to one depth and a few iterations to stay a unit test): the tables' structure, resume,
// and the closed-form checks recover the generating parameters within their reported 95 % intervals
// (the tensor-mass rows cannot: the FE rig's mesh error is a bias, reported, not tested away).
#include "calibration/closed_forms/indentation.hpp"
#include "calibration/fit/fitter.hpp"
#include "calibration/fit/model_spec.hpp"
#include "calibration/fit/relaxation_bands.hpp"
#include "core/base/error.hpp"
#include "core/config/config_reader.hpp"
#include "core/testing/temp_dir.hpp"
#include "studies/paper/paper_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>

namespace tmlab::tm {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kRoot = TMLAB_SOURCE_DIR;
const std::string kParams = kRoot + "/cases/paper/xu2011_indentation.json";

PaperFitSettings quick_settings() {
  return paper_fit_settings(ConfigReader::parse_file(kParams), kParams, true);
}

/// The quick settings cut to a unit test: one depth, the smallest rig (one patch cell and one
/// outer cell per side: 192 tets) and few iterations. The FE rows then test the study's plumbing
/// (values, errors, solves, resume), not the rig's accuracy.
PaperFitSettings unit_settings(int max_iterations) {
  PaperFitSettings s = quick_settings();
  s.depths = {s.depths.front()};
  s.patch_cells = 1;
  s.outer_cells = 1;
  s.max_iterations = max_iterations;
  return s;
}

json read_json(const fs::path& p) {
  std::ifstream in(p);
  EXPECT_TRUE(in.good()) << p;
  return json::parse(in);
}

TEST(PaperFit, PatchGradedCoordinatesAreUniformInThePatchAndGrowBeyond) {
  const auto c = patch_graded_coordinates(-10.0, 10.0, 0.0, 1.5, 3, 4);
  ASSERT_EQ(c.size(), 2u * (3 + 4) + 1);
  EXPECT_DOUBLE_EQ(c.front(), -10.0);
  EXPECT_DOUBLE_EQ(c.back(), 10.0);
  for (std::size_t i = 1; i < c.size(); ++i) EXPECT_GT(c[i], c[i - 1]);
  // Right side: 3 cells of 0.5, then growing cells.
  EXPECT_NEAR(c[7 + 1] - c[7], 0.5, 1e-12);
  EXPECT_NEAR(c[7 + 3] - c[7 + 2], 0.5, 1e-12);
  for (std::size_t i = 7 + 4; i + 1 < c.size(); ++i) EXPECT_GT(c[i + 1] - c[i], c[i] - c[i - 1]);
  // One-sided (the top face is the focus): a patch below it only.
  const auto z = patch_graded_coordinates(0.0, 20.0, 20.0, 3.0, 2, 3);
  ASSERT_EQ(z.size(), 6u);
  EXPECT_NEAR(z[5] - z[4], 1.5, 1e-12);
  EXPECT_THROW(patch_graded_coordinates(0.0, 1.0, 2.0, 0.1, 2, 2), Error);
}

TEST(PaperFit, ReferenceCurvesAreHertzAndLeeRadokWithTheStatedNoise) {
  PaperFitSettings s = quick_settings();
  s.noise_percent = 0.0;
  const measured::DataSet e = paper_reference_data(s, false, 1);
  ASSERT_EQ(e.tests.size(), 1u);
  const measured::Test& t = e.tests[0];
  EXPECT_EQ(t.size(), std::size_t(s.ramp_samples + 1));
  EXPECT_DOUBLE_EQ(t.displacement_m.back(), s.depths[1]);
  EXPECT_NEAR(t.force_N.back(), closed_forms::hertz_force(s.young, s.poisson, s.indenter_radius, s.depths[1]),
              1e-15);
  const measured::DataSet v = paper_reference_data(s, true, 0);
  const measured::Test& tv = v.tests[0];
  EXPECT_EQ(tv.size(), std::size_t(s.ramp_samples + s.hold_samples + 1));
  EXPECT_GT(tv.force_N[std::size_t(s.ramp_samples)], tv.force_N.back());  // it relaxes in the hold
  EXPECT_EQ(paper_reference_force(s, true, tv), tv.force_N);
  // With noise: the same curve plus deviations of about the stated size.
  s.noise_percent = 1.0;
  const measured::DataSet noisy = paper_reference_data(s, true, 0);
  const measured::Test& tn = noisy.tests[0];
  double peak = 0.0, dev = 0.0;
  for (std::size_t i = 0; i < tv.size(); ++i) {
    peak = std::max(peak, tv.force_N[i]);
    dev = std::max(dev, std::abs(tn.force_N[i] - tv.force_N[i]));
  }
  EXPECT_GT(dev, 0.001 * peak);
  EXPECT_LT(dev, 0.05 * peak);
  // The instantaneous Prony weights of the file became long-term moduli: E_j = g_j / (1 - sum g) E_inf.
  ASSERT_EQ(s.prony_moduli.size(), 2u);
  EXPECT_NEAR(s.prony_moduli[0], 4000.0 * 0.35 / 0.45, 1e-9);
}

TEST(PaperFit, BadSettingsNameTheKey) {
  json p = ConfigReader::parse_file(kParams);
  json q = p;
  // The settings `q` are refused with an error that names `key`.
  const auto refused_naming = [&q](const std::string& key, const std::string& what) {
    try {
      paper_fit_settings(q, "f.json", false);
      ADD_FAILURE() << what << " accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  q["reference"]["depths"] = {0.002, 0.02};
  EXPECT_THROW(paper_fit_settings(q, "f.json", false), Error);
  q = p;
  q["identification"]["laws"] = {"ogden"};
  refused_naming("laws", "ogden");
  q = p;
  q["rig"]["cellz"] = 3;
  EXPECT_THROW(paper_fit_settings(q, "f.json", false), Error);
  for (const char* key : {"contact_stiffness_factor", "newton_max_iterations"}) {
    q = p;
    q["rig"][key] = -1;
    refused_naming(key, std::string(key) + " = -1");
  }
  // The relaxation fits' settings: each bad value is refused naming its key; the bands' two ends
  // are set together.
  const std::vector<std::pair<const char*, double>> bad = {{"time_floor", -0.5},   {"time_ceiling", -1.0},
                                                           {"jacobian_step", 0.0}, {"jacobian_step", 0.5},
                                                           {"xtol", 0.0},          {"max_iterations", -1}};
  for (const auto& [key, v] : bad) {
    q = p;
    q["identification"]["relaxation"][key] = v;
    refused_naming(key, std::string(key) + " = " + std::to_string(v));
  }
  q = p;
  q["identification"]["relaxation"]["time_ceiling"] = 0.0;
  refused_naming("time_ceiling", "a floor without a ceiling");
  q = p;
  q["identification"]["relaxation"]["tau3"] = 1.0;
  EXPECT_THROW(paper_fit_settings(q, "f.json", false), Error);
  q = p;
  q.erase("quick");
  EXPECT_THROW(paper_fit_settings(q, "f.json", true), Error);
  EXPECT_THROW(run_paper_fit("fig9", quick_settings(), {}, fs::temp_directory_path()), Error);
}

TEST(PaperFit, UsableDepthNeedsAConvergedFit) {
  // St VK at 2 mm converged and agreeing with neo-Hookean; at 4 mm within every numeric criterion
  // but stopped at the iteration limit: 4 mm is where it stops being usable, for that reason.
  PaperFitSettings s;
  s.depths = {0.002, 0.004};
  const auto fit = [](const std::string& law, double depth, double young, const std::string& stop) {
    return json{{"kind", "tensor_mass"},
                {"law", law},
                {"depth_m", depth},
                {"status", "ok"},
                {"stop_reason", stop},
                {"residual_rms_percent_of_peak", 1.0},
                {"parameters", json::array({{{"name", "young"}, {"value", young}}})}};
  };
  std::vector<json> fits = {fit("stvk", 0.002, 4000, "small step (xtol)"),
                            fit("neo_hookean", 0.002, 3900, "small step (xtol)"),
                            fit("stvk", 0.004, 4050, "exceeded max number of iterations"),
                            fit("neo_hookean", 0.004, 3950, "small gradient (gtol)")};
  const json u = usable_depth(s, fits);
  ASSERT_EQ(u["depths"].size(), 2u);
  EXPECT_TRUE(u["depths"][0]["usable"].get<bool>());
  EXPECT_FALSE(u["depths"][1]["usable"].get<bool>());
  EXPECT_FALSE(u["depths"][1]["converged"].get<bool>());
  ASSERT_EQ(u["depths"][1]["reasons"].size(), 1u);
  EXPECT_NE(u["depths"][1]["reasons"][0].get<std::string>().find("did not converge"), std::string::npos);
  EXPECT_NE(u["statement"].get<std::string>().find("stops being usable at 4mm"), std::string::npos)
      << u["statement"];
  // Converged at both depths: usable at both.
  fits[2]["stop_reason"] = "small step (xtol)";
  EXPECT_NE(usable_depth(s, fits)["statement"].get<std::string>().find("usable at every depth"),
            std::string::npos);
  EXPECT_TRUE(fit::converged_stop("small gradient (gtol)"));
  EXPECT_FALSE(fit::converged_stop("exceeded max number of iterations"));
}

/// The forces of the study's viscoelastic St VK rig (quick mesh, 2 mm: the default eps's solve
/// costs 20 s of CPU there and more at 8 mm; the truth parameters): the contact stiffness from the patch (the
/// parameter file's setting) against the solver's default, and a warm start (from the solve at parameters
/// the relaxation fits' Jacobian step away, as their Jacobian columns do) against a cold solve. Neither may
/// move the forces beyond the solvers' tolerance; both must cut the Newton iterations.
TEST(PaperFit, PatchContactStiffnessAndWarmStartsKeepTheRigForces) {
  const PaperFitSettings s = quick_settings();
  ASSERT_GT(s.contact_stiffness_factor, 0.0) << "the parameter file sets rig.contact_stiffness_factor";
  const fit::ModelSpec spec = fit::parse_model_spec("stvk+prony:2,poisson=0.45");
  // young, poisson, e1, e2, tau1, tau2 (law_parameters order)
  const std::vector<double> x = {s.young,           s.poisson,       s.prony_moduli[0],
                                 s.prony_moduli[1], s.prony_taus[0], s.prony_taus[1]};
  std::vector<double> xp = x;
  const double h = s.relaxation.jacobian_step;
  for (std::size_t i : {0u, 2u, 4u}) xp[i] *= 1.0 + h;
  for (const std::size_t k : {std::size_t(0)}) {
    const measured::DataSet d = paper_reference_data(s, true, k);
    fit::RigForwardModelOptions with_default = paper_fe_rig_options(s);
    with_default.contact_stiffness_factor = 0.0;
    const auto ref = fit::make_rig_forward_model(d, spec, with_default);
    const auto patch = fit::make_rig_forward_model(d, spec, paper_fe_rig_options(s));
    const auto warm = fit::make_rig_forward_model(d, spec, paper_fe_rig_options(s));
    const std::vector<double> f0 = ref->predict(x);
    std::shared_ptr<const fit::WarmStart> state;
    const std::vector<double> f1 = patch->predict_warm(x, nullptr, &state);
    ASSERT_TRUE(state);
    const std::vector<double> fp_cold = patch->predict(xp);
    const std::vector<double> fp_warm = warm->predict_warm(xp, state.get(), nullptr);
    ASSERT_EQ(f0.size(), f1.size());
    double peak = 0.0, d_eps = 0.0, d_warm = 0.0, d_h = 0.0;
    for (std::size_t i = 0; i < f0.size(); ++i) {
      peak = std::max(peak, std::abs(f0[i]));
      d_eps = std::max(d_eps, std::abs(f1[i] - f0[i]));
      d_warm = std::max(d_warm, std::abs(fp_warm[i] - fp_cold[i]));
      d_h = std::max(d_h, std::abs(fp_cold[i] - f1[i]));
    }
    const fit::RigForwardModelEffort e0 = fit::rig_forward_model_effort(*ref),
                                     e1 = fit::rig_forward_model_effort(*patch),
                                     ew = fit::rig_forward_model_effort(*warm);
    std::cout << "depth " << s.depths[k] << " m: peak " << peak << " N; |patch eps - default eps| "
              << d_eps / peak << " of peak, |warm - cold| " << d_warm / peak << " (the step " << h
              << " moves the force by " << d_h / peak << "); Newton iterations per solve: default eps "
              << e0.newton << ", patch eps " << e1.newton / 2.0 << ", warm " << ew.newton << "; outer "
              << e0.outer << " / " << e1.outer / 2.0 << " / " << ew.outer << "; cut-backs " << e0.cutbacks
              << " / " << e1.cutbacks << " / " << ew.cutbacks << "\n";
    EXPECT_LT(d_eps, 1e-6 * peak) << "depth " << k;
    // Warm and cold solves stop at different points within the contact tolerance (gap_tol), as the
    // two eps do: measured 9e-8 of the peak for both on the 11 samples (10 % of what a step of
    // 1e-6 changes, which is why the relaxation fits' Jacobian step is larger).
    EXPECT_LT(d_warm, 1e-7 * peak) << "depth " << k << ": warm and cold agree to the contact tolerance";
    EXPECT_LT(d_warm, 0.01 * d_h) << "depth " << k << ": a warm start must not blur a Jacobian difference";
    EXPECT_LT(e1.newton, 2 * e0.newton) << "patch eps: fewer Newton iterations (two solves counted)";
    EXPECT_LT(2 * ew.newton, e1.newton) << "warm start: fewer Newton iterations than a cold solve";
    EXPECT_EQ(ew.warm, 1);
  }
}

/// The relaxation fits' Prony times (both parameter sets, every depth, both kinds of fit): tau1 at
/// least half the shortest sampling interval, tau2 at most the test's duration, in ordered disjoint
/// bands that hold the generating values. Without the bands tau1 was bounded by 0 only, and the
/// FE fits drove it to 1e-3 s (docs/paper-experiments.md).
TEST(PaperFit, RelaxationFitsBoundAndOrderTheRelaxationTimes) {
  const json params = ConfigReader::parse_file(kParams);
  for (const bool quick : {true, false}) {
    const PaperFitSettings s = paper_fit_settings(params, kParams, quick);
    ASSERT_GT(s.relaxation.time_floor, 0.0) << "the parameter file sets identification.relaxation.time_floor";
    for (std::size_t k = 0; k < s.depths.size(); ++k) {
      const measured::DataSet d = paper_reference_data(s, true, k);
      const measured::Test& t = d.tests.front();
      double dt_min = 1e300;
      for (std::size_t i = 1; i < t.size(); ++i) dt_min = std::min(dt_min, t.time_s[i] - t.time_s[i - 1]);
      for (const char* kind : {"closed_form", "tensor_mass"}) {
        const fit::Problem pr = paper_fit_problem(s, kind, "stvk", true, d);
        const fit::Parameter& t1 = pr.parameters[fit::index_of(pr.parameters, "tau1")];
        const fit::Parameter& t2 = pr.parameters[fit::index_of(pr.parameters, "tau2")];
        EXPECT_NEAR(t1.lower, s.relaxation.time_floor * dt_min, 1e-12) << kind;
        EXPECT_DOUBLE_EQ(t1.upper, t2.lower) << kind;
        EXPECT_NEAR(t2.upper, s.relaxation.time_ceiling * (s.ramp + s.hold), 1e-12) << kind;
        EXPECT_GT(s.prony_taus[0], t1.lower);
        EXPECT_LT(s.prony_taus[0], t1.upper) << "quick " << quick << ": the generating tau1 lies in its band";
        EXPECT_GT(s.prony_taus[1], t2.lower);
        EXPECT_LT(s.prony_taus[1], t2.upper) << "quick " << quick << ": the generating tau2 lies in its band";
      }
    }
  }
}

/// The Jacobian column of tau1 (the worst-determined direction) on the quick viscoelastic St VK rig
/// at 2 mm, by the fitter's forward difference (the model's jacobian_step, started warm from the
/// base point as the fitter does) against a central difference with a 30 x larger step (its
/// truncation error ~1e-5, its contact noise ~5e-4). With the engine's step of 1e-6 the column is
/// noise (measured 143 % off: the contact tolerance, ~5e-8 of the peak, against a force change of
/// ~1e-7 in this weak direction); the file's step must bring that under 1 % (measured 0.16 %).
TEST(PaperFit, JacobianStepStandsAboveTheContactTolerance) {
  const PaperFitSettings s = quick_settings();
  const measured::DataSet d = paper_reference_data(s, true, 0);
  const fit::Problem pr = paper_fit_problem(s, "tensor_mass", "stvk", true, d);
  std::vector<double> x;
  for (const auto& p : pr.parameters) x.push_back(paper_truth(s, p.name));
  const std::size_t j = fit::index_of(pr.parameters, "tau1");
  const fit::Parameter& q = pr.parameters[j];
  const double t = q.to_internal(x[j]);
  auto at = [&](double tj) {
    std::vector<double> y = x;
    y[j] = q.to_physical(tj);
    return y;
  };
  std::shared_ptr<const fit::WarmStart> base;
  const std::vector<double> f0 = pr.model->predict_warm(x, nullptr, &base);
  const double big = 3e-3 * std::max(1.0, std::abs(t));
  const std::vector<double> fp = pr.model->predict_warm(at(t + big), base.get(), nullptr);
  const std::vector<double> fm = pr.model->predict_warm(at(t - big), base.get(), nullptr);
  auto column_error = [&](double rel) {
    const double h = rel * std::max(1.0, std::abs(t));
    const std::vector<double> fh = pr.model->predict_warm(at(t + h), base.get(), nullptr);
    double num = 0.0, den = 0.0;
    for (std::size_t i = 0; i < f0.size(); ++i) {
      const double ref = (fp[i] - fm[i]) / (2 * big), fd = (fh[i] - f0[i]) / h;
      num += (fd - ref) * (fd - ref);
      den += ref * ref;
    }
    return std::sqrt(num / den);
  };
  const double err_file = column_error(pr.model->jacobian_step()), err_old = column_error(1e-6);
  std::cout << "tau1 column: relative error " << err_file << " with the step " << pr.model->jacobian_step()
            << ", " << err_old << " with 1e-6\n";
  EXPECT_LT(err_file, 1e-2);
  EXPECT_LT(err_file, err_old);
}

class PaperFitRun : public tmlab::testing::TempDirTest {};

/// A quick relaxation fit on the FE rig (St VK, 2 mm, the quick rig and iteration limit of the
/// parameter file) converges: Levenberg-Marquardt stops on its own test, not at the iteration
/// limit, no relaxation time ends on a bound, and every standard error is finite. Before the bands,
/// the Jacobian step and the iteration limit of 20 it stopped at the limit of 6 with tau1 = 0.038 s
/// (docs/paper-experiments.md, "before").

TEST_F(PaperFitRun, QuickRelaxationFeFitConvergesWithoutACollapsedTerm) {
  PaperFitSettings s = quick_settings();
  s.depths = {s.depths.front()};
  s.laws = {"stvk"};
  PaperFitOptions o;
  o.params_file = kParams;
  o.tmlab_root = kRoot;
  o.plots = false;
  run_paper_fit("table2", s, o, dir_);
  const json t = read_json(dir_ / "table2.json");
  bool seen = false;
  for (const auto& row : t["rows"]) {
    if (row["kind"] != "tensor_mass") continue;
    seen = true;
    ASSERT_EQ(row["status"], "ok") << row.dump();
    const json f = read_json(dir_ / "fits" / "tensor_mass_stvk_2mm.json");
    EXPECT_EQ(f["stop_reason"].get<std::string>().find("exceeded"), std::string::npos) << f["stop_reason"];
    for (const auto& p : row["parameters"]) {
      if (p["fixed"].get<bool>()) continue;
      EXPECT_EQ(p["at_bound"], "") << p.dump();
      EXPECT_TRUE(p["standard_error"].is_number()) << p.dump();
    }
  }
  EXPECT_TRUE(seen);
}

/// Every closed-form check row recovers every free, identifiable parameter within its interval;
/// every row has the table's structure.
void check_table(const json& t, std::size_t depths, std::size_t laws, std::size_t free_params) {
  ASSERT_EQ(t["rows"].size(), depths * (1 + laws));
  for (const auto& row : t["rows"]) {
    ASSERT_TRUE(row.contains("status")) << row.dump();
    if (row["status"] != "ok") {
      EXPECT_EQ(row["kind"], "tensor_mass") << "a closed-form check failed: " << row.dump();
      EXPECT_TRUE(row.contains("reason"));
      continue;
    }
    std::size_t n_free = 0;
    for (const auto& p : row["parameters"]) {
      ASSERT_TRUE(p.contains("value") && p.contains("standard_error") && p.contains("interval95"));
      if (p["fixed"].get<bool>()) {
        EXPECT_EQ(p["name"], "poisson");
        continue;
      }
      ++n_free;
      if (row["kind"] == "closed_form" && p["identifiable"].get<bool>()) {
        EXPECT_TRUE(p["truth_inside_interval"].get<bool>())
            << "depth " << row["depth_m"] << " " << p["name"] << " = " << p["value"] << " +- "
            << p["standard_error"] << ", truth " << p["truth"];
      }
      if (row["kind"] == "tensor_mass" && p["identifiable"].get<bool>()) {
        EXPECT_TRUE(p["standard_error"].is_number()) << p.dump();
      }
    }
    EXPECT_EQ(n_free, free_params);
    EXPECT_GT(row["forward_solves"].get<long>(), 0);
  }
  EXPECT_FALSE(t["usable_depth"]["statement"].get<std::string>().empty());
}

TEST_F(PaperFitRun, QuickElasticTableHasValuesWithErrorsAndResumeReusesTheFits) {
  // The shallowest depth only: an FE sphere indentation at 8 mm takes minutes even on the quick rig.
  const PaperFitSettings s = unit_settings(3);
  PaperFitOptions o;
  o.params_file = kParams;
  o.tmlab_root = kRoot;
  o.plots = false;
  const json summary = run_paper_fit("table1", s, o, dir_);
  const json t = read_json(dir_ / "table1.json");
  check_table(t, s.depths.size(), s.laws.size(), 1);
  EXPECT_GT(summary["fe_forward_solves"].get<long>(), 0);
  std::ifstream md(dir_ / "table1.md");
  const std::string text((std::istreambuf_iterator<char>(md)), {});
  EXPECT_NE(text.find("St VK usable depth"), std::string::npos);
  EXPECT_NE(text.find(" ± "), std::string::npos);
  // Every usable-depth row of St VK names its depth; the shallowest has zero drift by definition.
  const json& rows = t["usable_depth"]["depths"];
  ASSERT_EQ(rows.size(), s.depths.size());
  if (rows[0].contains("drift_percent")) {
    EXPECT_DOUBLE_EQ(rows[0]["drift_percent"].get<double>(), 0.0);
  }
  // --resume: every fit is reused, so nothing is solved and the table is the same.
  o.resume = true;
  const json again = run_paper_fit("fig2", s, o, dir_);
  EXPECT_EQ(read_json(dir_ / "table1.json"), t);
  EXPECT_EQ(again["fe_forward_solves"], summary["fe_forward_solves"]);
}

TEST_F(PaperFitRun, QuickRelaxationChecksRecoverTheFiveParameters) {
  PaperFitSettings s = unit_settings(2);
  s.laws = {"stvk"};  // St VK only: the FE Prony fit is the dear part
  PaperFitOptions o;
  o.params_file = kParams;
  o.tmlab_root = kRoot;
  o.plots = false;
  run_paper_fit("table2", s, o, dir_);
  check_table(read_json(dir_ / "table2.json"), 1, 1, 5);
}

}  // namespace
}  // namespace tmlab::tm
