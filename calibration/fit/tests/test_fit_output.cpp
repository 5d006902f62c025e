// What a fit writes (calibration/fit/fit_output.hpp): fit.json from a FitResult and its problem
// (each parameter with its bounds, nulls for non-finite numbers, the global stage with the
// simulated-annealing block only when it ran, the note when fewer local runs ran than asked, the
// tests with their weights), fit.h5 read back, and the forward-model rule of --forward.
#include "calibration/fit/fit_output.hpp"

#include "calibration/fit/synthetic_data.hpp"
#include "core/base/error.hpp"
#include "core/io/hdf5_file.hpp"
#include "core/testing/temp_dir.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <sstream>

namespace {

namespace fit = tmlab::fit;
using nlohmann::json;
constexpr double kInf = std::numeric_limits<double>::infinity();

fit::Problem sample_problem() {
  fit::Problem pr;
  fit::Parameter young;
  young.name = "young";
  young.unit = "Pa";
  young.lower = 100.0;
  young.upper = 1e6;
  fit::Parameter poisson;
  poisson.name = "poisson";
  poisson.unit = "1";
  poisson.fixed = true;
  pr.parameters = {young, poisson};  // poisson unbounded: null bounds
  pr.data.force = {1.0, 2.0, 3.0};
  pr.data.test = {0, 0, 1};
  pr.data.test_ids = {"a", "b"};
  pr.data.weights = {1.0, 0.5};
  pr.data.peak_force = 3.0;
  return pr;
}

fit::FitResult sample_result() {
  fit::FitResult r;
  r.model_name = "homogeneous_platen";
  r.model_description = "closed form";
  r.cost_name = "least_squares";
  r.parameters = {{"young", "Pa", 1e6, false, "logit", 10.0, 0.99e6, kInf, true},
                  {"poisson", "1", 0.49, true, "identity", kInf, 0.49, 0.49, false}};
  r.free_names = {"young"};
  r.correlation = {{1.0}};
  r.rms = 0.25;
  r.n = 3;
  r.k = 1;
  r.global_stage = "siman";
  r.global_model_name = "homogeneous_platen";
  r.local_runs = 2;
  r.start_costs = {0.5, kInf};
  r.prediction = {1.5, 2.5, 2.0};
  r.notes = {"poisson fixed"};
  return r;
}

TEST(FitOutput, ToJsonCarriesTheResultAndTheProblem) {
  const fit::FitResult r = sample_result();
  const fit::Problem pr = sample_problem();
  fit::FitOptions o;
  o.global = fit::GlobalStage::Siman;
  o.local_runs = 3;
  const json j = fit::to_json(r, pr, o, fit::parse_model_spec("neo_hookean,poisson=0.49"));
  EXPECT_EQ(j["model"]["law"], "neo_hookean");
  EXPECT_EQ(j["model"]["forward_model"], "homogeneous_platen");
  ASSERT_EQ(j["parameters"].size(), 2u);
  const json& y = j["parameters"][0];
  EXPECT_EQ(y["name"], "young");
  EXPECT_EQ(y["value"], 1e6);
  EXPECT_EQ(y["transform"], "logit");
  EXPECT_EQ(y["bounds"], json({100.0, 1e6}));
  EXPECT_EQ(y["at_bound"], "upper");
  EXPECT_EQ(y["interval95"], json({0.99e6, nullptr}));
  const json& p = j["parameters"][1];
  EXPECT_TRUE(p["standard_error"].is_null());
  EXPECT_EQ(p["bounds"], json({nullptr, nullptr}));
  EXPECT_EQ(p["at_bound"], "");
  EXPECT_EQ(j["peak_force_N"], 3.0);
  EXPECT_EQ(j["global_stage"]["starts"], 1);  // simulated annealing: one start
  EXPECT_TRUE(j["global_stage"].contains("siman"));
  EXPECT_EQ(j["global_stage"]["start_costs"], json({0.5, nullptr}));
  EXPECT_EQ(j["global_stage"]["local_runs_requested"], 3);
  ASSERT_EQ(j["notes"].size(), 2u);  // the result's note, then why 2 local runs of 3 ran
  EXPECT_NE(j["notes"][1].get<std::string>().find("--local-runs 3"), std::string::npos);
  EXPECT_EQ(j["tests"], json({{{"id", "a"}, {"weight", 1.0}}, {{"id", "b"}, {"weight", 0.5}}}));
  EXPECT_FALSE(j.contains("profile"));
  EXPECT_FALSE(j.contains("noise_sigma_N"));  // only with priors

  o.global = fit::GlobalStage::MultiStart;
  o.local_runs = 2;
  const json m = fit::to_json(r, pr, o, fit::parse_model_spec("neo_hookean"));
  EXPECT_FALSE(m["global_stage"].contains("siman"));
  EXPECT_EQ(m["global_stage"]["starts"], o.starts);
  EXPECT_EQ(m["notes"].size(), 1u);
  EXPECT_EQ(fit::local_runs_note(r, o), "");
}

TEST(FitOutput, ParameterJsonWithoutBounds) {
  const json j = fit::parameter_json({"tau1", "s", 2.0, false, "log", 0.1, 1.8, 2.2, true}, nullptr);
  EXPECT_EQ(j["bounds"], json({nullptr, nullptr}));
  EXPECT_EQ(j["at_bound"], "");
  EXPECT_EQ(j["interval95"], json({1.8, 2.2}));
}

class FitOutputFiles : public tmlab::testing::TempDirTest {};

TEST_F(FitOutputFiles, H5HoldsDataModelAndResidualPerTest) {
  tmlab::measured::DataSet data = fit::synthetic::compression_data(0.1, 3);
  data.tests[0].id = "t1";
  fit::synthetic::set_forces(data, {1.0, 2.0, 4.0});
  fit::FitResult r = sample_result();
  r.prediction = {1.5, 2.0, 3.0};
  r.profile.parameter = "young";
  r.profile.points = {{1.0, 9.0}, {2.0, 8.0}};
  fit::write_fit_h5(dir_ / "fit.h5", data, r);
  const tmlab::H5File h5 = tmlab::H5File::open_read((dir_ / "fit.h5").string());
  EXPECT_EQ(h5.read_double("/tests/000/force_N"), (std::vector<double>{1.0, 2.0, 4.0}));
  EXPECT_EQ(h5.read_double("/tests/000/model_force_N"), (std::vector<double>{1.5, 2.0, 3.0}));
  EXPECT_EQ(h5.read_double("/tests/000/residual_N"), (std::vector<double>{0.5, 0.0, -1.0}));
  EXPECT_EQ(h5.read_double("/profile/sse_N2"), (std::vector<double>{9.0, 8.0}));
  EXPECT_EQ(h5.read_double("/correlation"), (std::vector<double>{1.0}));
}

TEST(FitOutput, ForwardModelRule) {
  tmlab::measured::DataSet data = fit::synthetic::compression_data(0.1, 20);
  std::vector<double> force;
  for (const double d : data.tests[0].displacement_m) force.push_back(1e3 * d);  // positive in compression
  fit::synthetic::set_forces(data, force);
  const auto spec = fit::parse_model_spec("neo_hookean,poisson=0.49");
  std::string why;
  const fit::Problem closed = fit::make_problem(data, spec, {}, {}, "auto", {}, why);
  EXPECT_EQ(why, "");  // the closed form covers unconfined compression of a hyperelastic law
  EXPECT_EQ(closed.model->name(),
            fit::make_problem(data, spec, {}, {}, "closed_form", {}, why).model->name());
  EXPECT_THROW(fit::make_problem(data, spec, {}, {}, "fem", {}, why), tmlab::Error);
  // Prony terms on platen data: no closed form; auto falls back to the FE rig and says why.
  const auto visco = fit::parse_model_spec("neo_hookean+prony:1,poisson=0.49");
  EXPECT_THROW(fit::make_problem(data, visco, {}, {}, "closed_form", {}, why), tmlab::Error);
  why.clear();
  const fit::Problem fe = fit::make_problem(data, visco, {}, {}, "auto", {}, why);
  EXPECT_NE(why.find("FE rig"), std::string::npos) << why;
  EXPECT_NE(fe.model->name(), closed.model->name());
}

}  // namespace

namespace {

TEST(FitOutput, ResultNameSummaryAndPlan) {
  EXPECT_EQ(fit::result_name("EF10", fit::parse_model_spec("ogden:2+prony:1,poisson=0.49")),
            "EF10-ogden2-prony1");
  EXPECT_EQ(fit::result_name("EF10", fit::parse_model_spec("neo_hookean")), "EF10-neo_hookean");
  const fit::FitResult r = sample_result();
  const json s = fit::summary_json(r, fit::parse_model_spec("neo_hookean"), "ok");
  EXPECT_EQ(s["forward_model"], "homogeneous_platen");
  EXPECT_EQ(s["global_stage"], "siman");
  EXPECT_EQ(s["plots"], "ok");
  tmlab::measured::DataSet data = fit::synthetic::compression_data(0.1, 20);
  std::vector<double> force;
  for (const double d : data.tests[0].displacement_m) force.push_back(1e3 * d);
  fit::synthetic::set_forces(data, force);
  const auto spec = fit::parse_model_spec("neo_hookean,poisson=0.49");
  std::string why;
  const fit::Problem pr = fit::make_problem(data, spec, {}, {}, "closed_form", {}, why);
  std::ostringstream os;
  fit::print_fit_plan(os, "EF10", spec, "multistart", "closed_form", pr, why);
  EXPECT_EQ(os.str(), "fit EF10 with neo_hookean,poisson=0.49 (" + pr.model->description() + ")\n");
  std::ostringstream fe;
  fit::print_fit_plan(fe, "EF10", spec, "multistart", "fe_rig", pr, "no closed form here");
  EXPECT_NE(fe.str().find("global stage on the FE rig itself (no closed form: no closed form here)"),
            std::string::npos);
}

}  // namespace
