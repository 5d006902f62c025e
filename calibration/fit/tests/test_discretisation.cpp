// Tests of the discretisation shift (issue 28) against closed forms: a linear forward model
// F = A theta fitted by the engine, a "refined" model F + delta whose least-squares shift is known
// exactly, (1) delta = A v + r (r orthogonal to the columns of A): the shift is -v and the engine
// re-fitted on F + delta lands at theta* - v; (2) per-test weights: the shift is the weighted
// least-squares solution of W A dtheta = -W delta (an independent QR solve); (3) a log-transformed
// parameter of a model linear in x: the physical shift (dx/dt dt) is the physical least-squares
// shift; and the refined rig's rule and its refusals.
#include "calibration/fit/discretisation.hpp"

#include "calibration/fit/fitter.hpp"
#include "core/base/error.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

namespace tmlab::fit {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// F_i = sum_j A_ij x_j + offset_i (the offset: the "refined" model's perturbation).
class LinearModel final : public ForwardModel {
 public:
  LinearModel(Eigen::MatrixXd a, std::vector<double> offset) : a_(std::move(a)), offset_(std::move(offset)) {}
  std::string name() const override { return "linear"; }
  std::string description() const override { return "a linear test model"; }
  std::vector<double> predict(const std::vector<double>& x) const override {
    std::vector<double> f(std::size_t(a_.rows()), 0.0);
    for (Eigen::Index i = 0; i < a_.rows(); ++i) {
      f[std::size_t(i)] = offset_.empty() ? 0.0 : offset_[std::size_t(i)];
      for (Eigen::Index j = 0; j < a_.cols(); ++j) f[std::size_t(i)] += a_(i, j) * x[std::size_t(j)];
    }
    return f;
  }

 private:
  Eigen::MatrixXd a_;
  std::vector<double> offset_;
};

/// n samples t_i in [0, 1], split into two tests (the second half test 1); columns 1, t, t^2 up to p.
Eigen::MatrixXd design(int n, int p) {
  Eigen::MatrixXd a(n, p);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < p; ++j) a(i, j) = std::pow(double(i) / double(n - 1), j);
  return a;
}

Observations observations(const Eigen::VectorXd& force, std::vector<double> weights) {
  Observations d;
  const std::size_t n = std::size_t(force.size());
  for (std::size_t i = 0; i < n; ++i) {
    d.force.push_back(force(Eigen::Index(i)));
    d.test.push_back(i < n / 2 ? 0 : 1);
    d.peak_force = std::max(d.peak_force, std::abs(force(Eigen::Index(i))));
  }
  d.test_ids = {"a", "b"};
  d.weights = std::move(weights);
  return d;
}

Parameter free_parameter(const std::string& name, double value, double lower = -kInf, double upper = kInf) {
  Parameter q;
  q.name = name;
  q.unit = "N";
  q.value = value;
  q.lower = lower;
  q.upper = upper;
  q.start_low = q.start_high = value;
  return q;
}

/// A deterministic, irregular "noise" (the fit needs a residual for its covariance).
Eigen::VectorXd wiggle(int n, double amplitude) {
  Eigen::VectorXd e(n);
  for (int i = 0; i < n; ++i) e(i) = amplitude * std::sin(7.3 * i + 0.4 * i * i);
  return e;
}

FitOptions quiet_options() {
  FitOptions o;
  o.starts = 1;
  o.local_runs = 1;
  o.profile = false;
  o.threads = 1;
  return o;
}

Problem linear_problem(const Eigen::MatrixXd& a, const Eigen::VectorXd& data, std::vector<double> offset,
                       std::vector<double> weights, std::vector<Parameter> params) {
  Problem pr;
  pr.parameters = std::move(params);
  pr.model = std::make_unique<LinearModel>(a, std::move(offset));
  pr.data = observations(data, std::move(weights));
  return pr;
}

TEST(DiscretisationShift, IsMinusTheComponentOfThePerturbationInTheRangeOfJ) {
  const int n = 40, p = 3;
  const Eigen::MatrixXd a = design(n, p);
  const Eigen::Vector3d truth(2.0, -1.0, 0.5);
  const Eigen::VectorXd data = a * truth + wiggle(n, 0.01);
  const Problem pr =
      linear_problem(a, data, {}, {1.0, 1.0},
                     {free_parameter("c0", 1.0), free_parameter("c1", 0.0), free_parameter("c2", 0.0)});
  const FitResult r = fit(pr, quiet_options());
  ASSERT_EQ(r.linearisation.free.size(), 3u);
  // delta = A v + r_perp, r_perp orthogonal to A's columns: least squares sees A v only.
  const Eigen::Vector3d v(0.3, 0.2, -0.1);
  const Eigen::VectorXd raw = wiggle(n, 1.0).array().cos();
  const Eigen::VectorXd perp = raw - a * (a.transpose() * a).ldlt().solve(a.transpose() * raw);
  ASSERT_LT((a.transpose() * perp).norm(), 1e-10);
  const Eigen::VectorXd delta = a * v + perp;
  std::vector<double> fine = r.prediction;
  for (int i = 0; i < n; ++i) fine[std::size_t(i)] += delta(i);
  const std::vector<double> dt = linearised_shift(r.linearisation, pr.data, r.prediction, fine);
  ASSERT_EQ(dt.size(), 3u);
  for (int j = 0; j < p; ++j) EXPECT_NEAR(dt[std::size_t(j)], -v(j), 1e-7) << j;
  // The meaning: the engine re-fitted on the perturbed model lands at theta* + shift.
  std::vector<double> offset(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) offset[std::size_t(i)] = delta(i);
  const Problem fine_pr =
      linear_problem(a, data, offset, {1.0, 1.0},
                     {free_parameter("c0", 1.0), free_parameter("c1", 0.0), free_parameter("c2", 0.0)});
  const FitResult rf = fit(fine_pr, quiet_options());
  for (int j = 0; j < p; ++j)
    EXPECT_NEAR(rf.parameters[std::size_t(j)].value, r.parameters[std::size_t(j)].value + dt[std::size_t(j)],
                1e-7)
        << j;
}

TEST(DiscretisationShift, CarriesTheFitsPerTestWeights) {
  const int n = 30, p = 2;
  const Eigen::MatrixXd a = design(n, p);
  const Eigen::VectorXd data = a * Eigen::Vector2d(1.0, 3.0) + wiggle(n, 0.02);
  const std::vector<double> w = {1.0, 3.0};
  const Problem pr = linear_problem(a, data, {}, w, {free_parameter("c0", 0.5), free_parameter("c1", 1.0)});
  const FitResult r = fit(pr, quiet_options());
  Eigen::VectorXd delta(n);
  for (int i = 0; i < n; ++i) delta(i) = 0.1 * std::exp(-3.0 * double(i) / n) + 0.05 * std::cos(double(i));
  std::vector<double> fine = r.prediction;
  for (int i = 0; i < n; ++i) fine[std::size_t(i)] += delta(i);
  const std::vector<double> dt = linearised_shift(r.linearisation, pr.data, r.prediction, fine);
  // Independent: min || W (A dtheta + delta) || by Householder QR.
  Eigen::VectorXd wd(n);
  for (int i = 0; i < n; ++i) wd(i) = w[std::size_t(pr.data.test[std::size_t(i)])];
  const Eigen::VectorXd expect =
      (wd.asDiagonal() * a).colPivHouseholderQr().solve(-(wd.asDiagonal() * delta));
  for (int j = 0; j < p; ++j)
    EXPECT_NEAR(dt[std::size_t(j)], expect(j), 1e-7 * (1.0 + std::abs(expect(j)))) << j;
  // The unweighted solution differs (the test would pass with the weights ignored otherwise).
  const Eigen::VectorXd plain = a.colPivHouseholderQr().solve(-delta);
  EXPECT_GT((plain - expect).norm(), 1e-3);
}

TEST(DiscretisationShift, LogTransformedParameterGivesThePhysicalLeastSquaresShift) {
  // F = x g (one parameter x > 0, internal t = ln x): the physical least-squares shift of delta is
  // -(g^T g)^{-1} g^T delta, which dx/dt dt must reproduce exactly (F is linear in x).
  const int n = 25;
  const Eigen::MatrixXd g = design(n, 2).col(1) + 0.5 * design(n, 3).col(2);
  const Eigen::VectorXd data = 4000.0 * g + wiggle(n, 5.0);
  const Problem pr = linear_problem(g, data, {}, {1.0, 1.0}, {free_parameter("young", 3000.0, 0.0, kInf)});
  ASSERT_EQ(pr.parameters[0].transform(), Transform::Log);
  const FitResult r = fit(pr, quiet_options());
  const Eigen::VectorXd delta = -0.05 * r.parameters[0].value * g.col(0) + wiggle(n, 2.0);
  std::vector<double> fine = r.prediction;
  for (int i = 0; i < n; ++i) fine[std::size_t(i)] += delta(i);
  const std::vector<double> dt = linearised_shift(r.linearisation, pr.data, r.prediction, fine);
  const double dx = r.linearisation.dxdt[0] * dt[0];
  const double expect = -(g.col(0).dot(delta)) / g.col(0).squaredNorm();
  EXPECT_NEAR(dx, expect, 1e-6 * std::abs(expect));
  EXPECT_GT(expect, 0.0);  // a softer "refined" model: the estimate moves up
}

TEST(DiscretisationShift, RefusesForcesOfTheWrongSizeAndAnEmptyLinearisation) {
  const Eigen::MatrixXd a = design(10, 2);
  const Problem pr = linear_problem(a, a * Eigen::Vector2d(1.0, 1.0) + wiggle(10, 0.01), {}, {1.0, 1.0},
                                    {free_parameter("c0", 0.0), free_parameter("c1", 0.0)});
  const FitResult r = fit(pr, quiet_options());
  std::vector<double> shorter(r.prediction.begin(), r.prediction.end() - 1);
  EXPECT_THROW(linearised_shift(r.linearisation, pr.data, r.prediction, shorter), Error);
  EXPECT_THROW(linearised_shift(Linearisation{}, pr.data, r.prediction, r.prediction), Error);
  // A closed-form model is no FE rig: the report refuses it by name.
  try {
    discretisation_report(r, pr, *pr.model, 2.0);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not an FE-rig model"), std::string::npos) << e.what();
  }
}

TEST(RefinedRig, MultipliesCellsAndLayersByTheRatioAndRefusesNoRefinement) {
  RigForwardModelOptions o;
  o.mesh.cells = 12;
  o.mesh.layers = 6;
  o.mesh.grading = 3.0;
  o.substeps = 2;
  const RigForwardModelOptions f = refined_rig(o, 2.0);
  EXPECT_EQ(f.mesh.cells, 24);
  EXPECT_EQ(f.mesh.layers, 12);
  EXPECT_EQ(f.mesh.grading, 3.0);
  EXPECT_EQ(f.substeps, 2);
  const RigForwardModelOptions g = refined_rig(o, 1.5);
  EXPECT_EQ(g.mesh.cells, 18);
  EXPECT_EQ(g.mesh.layers, 9);
  EXPECT_THROW(refined_rig(o, 1.0), Error);
  EXPECT_THROW(refined_rig(o, 0.5), Error);
  o.mesh.cells = 4;
  o.mesh.layers = 2;
  EXPECT_THROW(refined_rig(o, 1.1), Error);  // 4.4 -> 4, 2.2 -> 2: nothing refined
}

}  // namespace
}  // namespace tmlab::fit
