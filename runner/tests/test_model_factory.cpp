// make_model: the kernel each "model" builds, the viscoelastic forms (and `visco` set only for
// them), and the refusals that name the key and the model that would run the case.
#include "core/base/error.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "runner/model_factory.hpp"
#include "runner/tests/runner_test_case.hpp"
#include "tensormass/kernels/averaged_pressure_tet.hpp"
#include "tensormass/kernels/hyperelastic_tl.hpp"
#include "tensormass/kernels/tensor_mass.hpp"
#include "tensormass/kernels/tl_oracle.hpp"
#include "tensormass/materials/law_factory.hpp"
#include "tensormass/viscoelastic/viscoelastic_law.hpp"
#include "tensormass/viscoelastic/viscoelastic_law_anp.hpp"
#include "tensormass/viscoelastic/viscoelastic_model.hpp"

#include <gtest/gtest.h>

namespace tmlab::tm::runner {
namespace {

using json = nlohmann::json;

class ModelFactoryTest : public RunnerTestCase {
 protected:
  /// The model of the uniaxial case with `model` and `material`; `visco` as make_model sets it.
  std::unique_ptr<ElasticModel> build(const std::string& model, const json& material,
                                      const std::string& element = "p1") {
    json j = uniaxial(0.001);
    j["model"] = model;
    j["mesh"]["element"] = element;
    j["material"] = material;
    cfg_ = config(j);
    mesh_ = make_box_mesh(Vec3(0, 0, 0), Vec3(kL, kL, kL), 2, 2, 2);
    const StVenantKirchhoff stvk =
        StVenantKirchhoff::from_young_poisson(cfg_.material.young, cfg_.material.poisson);
    law_ = std::make_unique<Law>(make_law(cfg_.material.law, cfg_.material.parameters, "material"));
    visco_ = nullptr;
    return make_model(cfg_, mesh_, nullptr, stvk, *law_, visco_);
  }
  /// make_model's error for this model and material.
  std::string refusal(const std::string& model, const json& material) {
    try {
      build(model, material);
    } catch (const Error& e) {
      return e.what();
    }
    ADD_FAILURE() << model << " was built";
    return "";
  }

  static json stvk() { return {{"E", 10000.0}, {"nu", 0.3}, {"density", 1000.0}}; }
  static json neo_hookean() {
    return {{"law", "neo_hookean"}, {"E", 10000.0}, {"nu", 0.3}, {"density", 1000.0}};
  }
  static json viscoelastic(json m) {
    m["viscoelastic"] = json::parse(R"({"prony": {"convention": "instantaneous",
                                                  "terms": [{"weight": 0.3, "tau": 0.5}]}})");
    return m;
  }

  CaseConfig cfg_;
  Mesh mesh_;
  std::unique_ptr<Law> law_;
  const ViscoelasticBase* visco_ = nullptr;
};

TEST_F(ModelFactoryTest, EachModelBuildsItsKernel) {
  EXPECT_NE(dynamic_cast<TensorMassStVK*>(build("tensor_mass", stvk()).get()), nullptr);
  EXPECT_NE(dynamic_cast<TotalLagrangianStVK*>(build("tl_oracle", stvk()).get()), nullptr);
  EXPECT_NE(dynamic_cast<HyperelasticTL*>(build("hyperelastic_tl", neo_hookean()).get()), nullptr);
  EXPECT_EQ(visco_, nullptr);
}

TEST_F(ModelFactoryTest, ViscoelasticMaterialsBuildTheViscoelasticModels) {
  const auto tm = build("tensor_mass", viscoelastic(stvk()));
  EXPECT_NE(dynamic_cast<ViscoelasticStVK*>(tm.get()), nullptr);
  EXPECT_EQ(visco_, dynamic_cast<const ViscoelasticBase*>(tm.get()));
  const auto tl = build("hyperelastic_tl", viscoelastic(neo_hookean()));
  EXPECT_NE(dynamic_cast<ViscoelasticHyperelastic*>(tl.get()), nullptr);
  EXPECT_EQ(visco_, dynamic_cast<const ViscoelasticBase*>(tl.get()));
  // the locking-free linear tet: elastic, and its viscoelastic form
  EXPECT_NE(dynamic_cast<AveragedPressureTet*>(build("hyperelastic_tl", neo_hookean(), "p1_anp").get()),
            nullptr);
  EXPECT_EQ(visco_, nullptr);
  const auto anp = build("hyperelastic_tl", viscoelastic(neo_hookean()), "p1_anp");
  EXPECT_NE(dynamic_cast<ViscoelasticAveragedPressureTet*>(anp.get()), nullptr);
  EXPECT_EQ(visco_, dynamic_cast<const ViscoelasticBase*>(anp.get()));
}

TEST_F(ModelFactoryTest, StVKModelsRefuseOtherLawsNamingTheModelThatRunsThem) {
  for (const char* model : {"tensor_mass", "tl_oracle"}) {
    const std::string e = refusal(model, neo_hookean());
    EXPECT_NE(e.find("key 'model'"), std::string::npos) << e;
    EXPECT_NE(e.find("\"model\": \"hyperelastic_tl\""), std::string::npos) << e;
  }
}

TEST_F(ModelFactoryTest, TheOracleIsElasticOnly) {
  const std::string e = refusal("tl_oracle", viscoelastic(stvk()));
  EXPECT_NE(e.find("tl_oracle kernel is elastic only"), std::string::npos) << e;
}

}  // namespace
}  // namespace tmlab::tm::runner
