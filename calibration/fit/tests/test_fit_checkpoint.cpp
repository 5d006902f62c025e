// The checkpoint entries of a fit (calibration/fit/fit_checkpoint.hpp): FitUnits and a whole
// FitResult written to a checkpoint file and read back equal, every double bit for bit (NaN and
// infinities included); a checkpoint whose parts do not fit together refused.
#include "calibration/fit/fit_checkpoint.hpp"

#include "core/base/error.hpp"
#include "core/results/checkpoint.hpp"
#include "core/testing/temp_dir.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <sstream>

namespace {

using tmlab::CheckpointData;
namespace fit = tmlab::fit;

constexpr double kInf = std::numeric_limits<double>::infinity();
const double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Equal bit for bit (so NaN equals NaN of the same payload).
bool same(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!same(a[i], b[i])) return false;
  return true;
}

fit::FitResult sample_result() {
  fit::FitResult r;
  r.model_name = "homogeneous_platen";
  r.model_description = "unconfined compression, \"closed form\"";
  r.cost_name = "least_squares";
  r.parameters = {{"young", "Pa", 1234.5678901234, false, "log", 12.25, 1200.0, 1270.0, true},
                  {"poisson", "1", 0.49, true, "identity", 0.0, 0.49, 0.49, true},
                  {"c01", "Pa", -1e-300, false, "identity", kInf, -kInf, kInf, false}};
  r.free_names = {"young", "c01"};
  r.correlation = {{1.0, -0.95}, {-0.95, 1.0}};
  r.cost = 0.1 + 0.2;
  r.sse = 3.0e-7;
  r.rms = 1.0 / 3.0;
  r.rms_percent_peak = 2.5;
  r.n = 150;
  r.k = 2;
  r.aic = -1234.5;
  r.bic = -1230.25;
  r.forward_solves = 987;
  r.global_stage = "multistart";
  r.global_model_name = "homogeneous_platen";
  r.global_solves = 12;
  r.global_costs = {1.0, kNaN, 3.0};
  r.prior_cost = 0.125;
  r.noise_sigma = 0.01;
  r.wall_seconds = 1.5;
  r.threads = 2;
  r.iterations = 17;
  r.local_runs = 3;
  r.stop_reason = "small step";
  r.start_costs = {0.5, kInf};
  r.prediction = {0.0, -0.0, 1e-310, 2.0};
  r.profile.parameter = "young";
  r.profile.points = {{1100.0, 4.0}, {1234.5, 3.0}, {1300.0, kNaN}};
  r.profile.lower95 = 1150.0;
  r.profile.upper95 = kInf;
  r.profile.lower_found = true;
  r.profile.upper_found = false;
  r.confounded = {{"young", "c01", -0.95, "one of them fixed"}};
  r.notes = {"poisson fixed", "ünïcode note"};
  return r;
}

void expect_equal(const fit::FitResult& a, const fit::FitResult& b) {
  EXPECT_EQ(a.model_name, b.model_name);
  EXPECT_EQ(a.model_description, b.model_description);
  EXPECT_EQ(a.cost_name, b.cost_name);
  ASSERT_EQ(a.parameters.size(), b.parameters.size());
  for (std::size_t i = 0; i < a.parameters.size(); ++i) {
    const auto &p = a.parameters[i], &q = b.parameters[i];
    EXPECT_EQ(p.name, q.name);
    EXPECT_EQ(p.unit, q.unit);
    EXPECT_EQ(p.fixed, q.fixed);
    EXPECT_EQ(p.transform, q.transform);
    EXPECT_EQ(p.identifiable, q.identifiable);
    EXPECT_TRUE(same(p.value, q.value) && same(p.standard_error, q.standard_error) &&
                same(p.lower95, q.lower95) && same(p.upper95, q.upper95))
        << p.name;
  }
  EXPECT_EQ(a.free_names, b.free_names);
  EXPECT_EQ(a.correlation, b.correlation);
  for (const auto& [x, y] : {std::pair<double, double>{a.cost, b.cost},
                             {a.sse, b.sse},
                             {a.rms, b.rms},
                             {a.rms_percent_peak, b.rms_percent_peak},
                             {a.aic, b.aic},
                             {a.bic, b.bic},
                             {a.prior_cost, b.prior_cost},
                             {a.noise_sigma, b.noise_sigma},
                             {a.wall_seconds, b.wall_seconds},
                             {a.profile.lower95, b.profile.lower95},
                             {a.profile.upper95, b.profile.upper95}})
    EXPECT_TRUE(same(x, y)) << x << " " << y;
  EXPECT_EQ(a.n, b.n);
  EXPECT_EQ(a.k, b.k);
  EXPECT_EQ(a.forward_solves, b.forward_solves);
  EXPECT_EQ(a.global_stage, b.global_stage);
  EXPECT_EQ(a.global_model_name, b.global_model_name);
  EXPECT_EQ(a.global_solves, b.global_solves);
  EXPECT_TRUE(same(a.global_costs, b.global_costs));
  EXPECT_TRUE(same(a.start_costs, b.start_costs));
  EXPECT_TRUE(same(a.prediction, b.prediction));
  EXPECT_EQ(a.threads, b.threads);
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(a.local_runs, b.local_runs);
  EXPECT_EQ(a.stop_reason, b.stop_reason);
  EXPECT_EQ(a.profile.parameter, b.profile.parameter);
  EXPECT_EQ(a.profile.lower_found, b.profile.lower_found);
  EXPECT_EQ(a.profile.upper_found, b.profile.upper_found);
  ASSERT_EQ(a.profile.points.size(), b.profile.points.size());
  for (std::size_t i = 0; i < a.profile.points.size(); ++i)
    EXPECT_TRUE(same(a.profile.points[i].value, b.profile.points[i].value) &&
                same(a.profile.points[i].sse, b.profile.points[i].sse));
  ASSERT_EQ(a.confounded.size(), b.confounded.size());
  for (std::size_t i = 0; i < a.confounded.size(); ++i) {
    EXPECT_EQ(a.confounded[i].a, b.confounded[i].a);
    EXPECT_EQ(a.confounded[i].b, b.confounded[i].b);
    EXPECT_TRUE(same(a.confounded[i].correlation, b.confounded[i].correlation));
    EXPECT_EQ(a.confounded[i].note, b.confounded[i].note);
  }
  EXPECT_EQ(a.notes, b.notes);
}

class FitCheckpointTest : public tmlab::testing::TempDirTest {
 protected:
  /// `d` through a checkpoint file and back.
  CheckpointData through_file(const CheckpointData& d) const {
    const auto path = dir_ / "checkpoint.h5";
    tmlab::write_checkpoint(path, "fit", {{"k", 1}}, d);
    return tmlab::read_checkpoint(path, "fit", {{"k", 1}});
  }
};

TEST_F(FitCheckpointTest, FitResultRoundTripsExactly) {
  const fit::FitResult r = sample_result();
  CheckpointData d;
  fit::put_fit_result(d, "fit.0", r);
  expect_equal(r, fit::get_fit_result(through_file(d), "fit.0"));
}

TEST_F(FitCheckpointTest, FitUnitsRoundTripExactly) {
  fit::FitUnits u;
  u.global_done = true;
  u.candidates = {{0.1, 0.2, 0.3}, {kNaN, -1.0, 1e300}};
  u.order = {1, 0};
  u.start_costs = {2.0, kInf};
  u.global_costs = {1.0 / 7.0};
  u.solves = 40;
  u.global_solves = 12;
  u.local_runs = {{{0.11, 0.21, 0.31}, 0.5, 9, "small step", 55},
                  {{1.0, 2.0, 3.0}, kNaN, 0, "gsl error", 60}};
  u.profile = {{3.5, 70}, {kInf, 75}};
  CheckpointData d;
  fit::put_fit_units(d, u);
  const fit::FitUnits v = fit::get_fit_units(through_file(d));
  EXPECT_EQ(v.global_done, u.global_done);
  ASSERT_EQ(v.candidates.size(), u.candidates.size());
  for (std::size_t c = 0; c < u.candidates.size(); ++c) EXPECT_TRUE(same(v.candidates[c], u.candidates[c]));
  EXPECT_EQ(v.order, u.order);
  EXPECT_TRUE(same(v.start_costs, u.start_costs));
  EXPECT_TRUE(same(v.global_costs, u.global_costs));
  EXPECT_EQ(v.solves, u.solves);
  EXPECT_EQ(v.global_solves, u.global_solves);
  ASSERT_EQ(v.local_runs.size(), 2u);
  for (std::size_t r = 0; r < 2; ++r) {
    EXPECT_TRUE(same(v.local_runs[r].t, u.local_runs[r].t));
    EXPECT_TRUE(same(v.local_runs[r].cost, u.local_runs[r].cost));
    EXPECT_EQ(v.local_runs[r].iterations, u.local_runs[r].iterations);
    EXPECT_EQ(v.local_runs[r].reason, u.local_runs[r].reason);
    EXPECT_EQ(v.local_runs[r].solves, u.local_runs[r].solves);
  }
  ASSERT_EQ(v.profile.size(), 2u);
  EXPECT_TRUE(same(v.profile[1].sse, kInf));
  EXPECT_EQ(v.profile[1].solves, 75);
  EXPECT_EQ(fit::describe(v), "the global stage, 2 local run(s) and 2 profile-likelihood point(s)");
  EXPECT_EQ(fit::describe(fit::FitUnits{}), "nothing");
}

TEST_F(FitCheckpointTest, InconsistentEntriesAreRefused) {
  fit::FitUnits u;
  u.global_done = true;
  u.candidates = {{0.1, 0.2}};
  u.order = {0};
  CheckpointData d;
  fit::put_fit_units(d, u);
  d.put("global.order", std::vector<std::int64_t>{3});  // a candidate that does not exist
  EXPECT_THROW(fit::get_fit_units(d), tmlab::Error);
  CheckpointData e;
  fit::put_fit_result(e, "r", sample_result());
  e.put("r.scalars", std::vector<double>{1.0});
  EXPECT_THROW(fit::get_fit_result(e, "r"), tmlab::Error);
  e.put_text("r.meta", "{not json");
  EXPECT_THROW(fit::get_fit_result(e, "r"), tmlab::Error);
}

}  // namespace

namespace {

TEST_F(FitCheckpointTest, FitCheckpointRecordsAndRestoresUnits) {
  tmlab::CheckpointSchedule every;
  every.every_steps = 1;
  every.every_seconds = 0.0;
  const nlohmann::json fingerprint = {{"model", "neo_hookean"}};
  fit::FitOptions o;
  std::filesystem::create_directories(dir_ / ".incomplete");  // the staging area RunOutput makes
  {
    fit::FitCheckpoint ck(dir_, fingerprint, every);
    ck.record(o);
    ASSERT_TRUE(o.resume.unit_finished);
    fit::FitUnits u;
    u.global_done = true;
    u.candidates = {{0.5, 0.25}};
    u.order = {0};
    u.local_runs = {{{0.5, 0.125}, 1.0 / 3.0, 4, "small step", 9}};
    o.resume.unit_finished(u);  // written: every unit
    EXPECT_TRUE(std::filesystem::exists(ck.file().path()));
  }
  fit::FitOptions resumed;
  fit::FitCheckpoint again(dir_, fingerprint, every);
  std::ostringstream log;
  again.restore(resumed, log);
  ASSERT_NE(resumed.resume.restored, nullptr);
  ASSERT_EQ(resumed.resume.restored->local_runs.size(), 1u);
  EXPECT_EQ(resumed.resume.restored->local_runs[0].cost, 1.0 / 3.0);
  EXPECT_NE(log.str().find("the global stage and 1 local run(s) taken from it"), std::string::npos)
      << log.str();
  fit::FitOptions other;
  fit::FitCheckpoint changed(dir_, {{"model", "yeoh"}}, every);  // another configuration: refused
  EXPECT_THROW(changed.restore(other, log), tmlab::Error);
}

}  // namespace
