// The ElasticModel contract, checked through the interface for every elastic implementation in
// tensormass/kernels: sizes, outputs overwritten (not accumulated), f = dW/du and K v = df/du v by
// central differences, the assembled K equal to the matrix-free action and symmetric, and the
// history hooks of an elastic model being no-ops.
#include "tensormass/kernels/elastic_model.hpp"
#include "tensormass/kernels/tensor_mass.hpp"
#include "tensormass/kernels/tl_oracle.hpp"
#include "tensormass/testing/test_meshes.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <random>
#include <string>

namespace tmlab::tm {
namespace {

struct ModelCase {
  std::string name;
  std::function<std::unique_ptr<ElasticModel>(const Mesh&, const StVenantKirchhoff&)> make;
};

class ElasticModelContract : public ::testing::TestWithParam<ModelCase> {
 protected:
  void SetUp() override {
    std::mt19937 rng(31);
    mesh_ = testing::jittered_box(3, h_, 0.2, rng);
    model_ = GetParam().make(mesh_, StVenantKirchhoff::from_young_poisson(3000.0, 0.45));
    u_ = testing::random_displacement(mesh_.num_points(), 0.1 * h_, rng);
    v_ = testing::random_displacement(mesh_.num_points(), 1.0, rng);
  }
  const double h_ = 0.01;
  Mesh mesh_;
  std::unique_ptr<ElasticModel> model_;
  VecX u_, v_;
};

TEST_P(ElasticModelContract, SizesAndOverwrittenOutputs) {
  const ElasticModel& m = *model_;
  EXPECT_EQ(m.num_nodes(), mesh_.num_points());
  EXPECT_EQ(m.num_dofs(), 3 * mesh_.num_points());
  VecX f_fresh, f_reused = VecX::Constant(7, 1e9);  // wrong size and garbage: must be replaced
  m.internal_force(u_, f_fresh);
  m.internal_force(u_, f_reused);
  ASSERT_EQ(f_fresh.size(), m.num_dofs());
  EXPECT_EQ(f_reused, f_fresh);
  VecX kv_fresh, kv_reused = VecX::Constant(m.num_dofs(), -3.0);
  m.tangent_apply(u_, v_, kv_fresh);
  m.tangent_apply(u_, v_, kv_reused);
  ASSERT_EQ(kv_fresh.size(), m.num_dofs());
  EXPECT_EQ(kv_reused, kv_fresh);
}

TEST_P(ElasticModelContract, ForceIsTheEnergyGradientAndTangentTheForceDerivative) {
  const ElasticModel& m = *model_;
  const double eps = 1e-6;
  VecX f, kv, fp, fm;
  m.internal_force(u_, f);
  m.tangent_apply(u_, v_, kv);
  const double dw = (m.energy(u_ + eps * v_) - m.energy(u_ - eps * v_)) / (2.0 * eps);
  EXPECT_NEAR(dw, f.dot(v_), 1e-6 * std::abs(f.dot(v_)));
  m.internal_force(u_ + eps * v_, fp);
  m.internal_force(u_ - eps * v_, fm);
  const VecX df = (fp - fm) / (2.0 * eps);
  EXPECT_LT((df - kv).norm(), 1e-6 * kv.norm());
}

TEST_P(ElasticModelContract, AssembledTangentIsTheActionAndSymmetric) {
  const ElasticModel& m = *model_;
  SpMat K;
  m.tangent(u_, K);
  ASSERT_EQ(K.rows(), m.num_dofs());
  ASSERT_EQ(K.cols(), m.num_dofs());
  VecX kv;
  m.tangent_apply(u_, v_, kv);
  EXPECT_LT((K * v_ - kv).norm(), 1e-12 * kv.norm());
  const SpMat asym = SpMat(K.transpose()) - K;
  EXPECT_LT(asym.norm(), 1e-12 * K.norm());
  // A second call on the same matrix (the pattern is reused) gives the same values at another u.
  const VecX u2 = 0.5 * u_;
  m.tangent(u2, K);
  VecX kv2;
  m.tangent_apply(u2, v_, kv2);
  EXPECT_LT((K * v_ - kv2).norm(), 1e-12 * kv2.norm());
}

TEST_P(ElasticModelContract, ElasticModelsHaveNoHistory) {
  ElasticModel& m = *model_;
  EXPECT_FALSE(m.has_history());
  EXPECT_TRUE(m.energy_is_potential());
  const double w = m.energy(u_);
  VecX f0, f1;
  m.internal_force(u_, f0);
  m.begin_step(0.1);
  m.commit_step(u_);
  m.begin_step(0.0);
  EXPECT_EQ(m.energy(u_), w);
  m.internal_force(u_, f1);
  EXPECT_EQ(f1, f0);
}

INSTANTIATE_TEST_SUITE_P(
    Kernels, ElasticModelContract,
    ::testing::Values(
        ModelCase{"TensorMassStVK",
                  [](const Mesh& mesh, const StVenantKirchhoff& mat) -> std::unique_ptr<ElasticModel> {
                    return std::make_unique<TensorMassStVK>(mesh, mat);
                  }},
        ModelCase{"TotalLagrangianStVK",
                  [](const Mesh& mesh, const StVenantKirchhoff& mat) -> std::unique_ptr<ElasticModel> {
                    return std::make_unique<TotalLagrangianStVK>(mesh, mat);
                  }}),
    [](const ::testing::TestParamInfo<ModelCase>& p) { return p.param.name; });

}  // namespace
}  // namespace tmlab::tm
