// mesh.element: parsed strictly (the default p1, each accepted name, an unknown name refused with
// the key and the accepted values), recorded in the effective case, and the combinations the
// kernels cannot run refused naming both keys.
#include "core/base/error.hpp"
#include "core/config/case_config.hpp"
#include "core/config/element_kind.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace tmlab {
namespace {

namespace fs = std::filesystem;

class ElementKindTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("tmlab_element_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    std::ofstream(dir_ / "m.msh") << "placeholder";  // only existence is checked by parse_case
  }
  void TearDown() override { fs::remove_all(dir_); }
  nlohmann::json minimal() const {
    return nlohmann::json::parse(R"({
      "name": "t", "model": "hyperelastic_tl", "mesh": {"file": "m.msh"},
      "material": {"law": "neo_hookean", "E": 1000, "nu": 0.3, "density": 1000},
      "boundary": [{"name": "fixed", "nodes": {"plane": {"axis": "z", "value": 0}}}],
      "solver": {"type": "static"}
    })");
  }
  CaseConfig parse(const nlohmann::json& j) const { return parse_case(j, "case.json", {dir_.string()}); }
  std::string error_of(const nlohmann::json& j, CaseModel model = CaseModel::HyperelasticTL) const {
    try {
      check_element_support(parse(j), model);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
};

TEST_F(ElementKindTest, DefaultIsP1AndEveryNameParses) {
  EXPECT_EQ(parse(minimal()).mesh.element, ElementKind::P1);
  for (const std::string& name : element_kind_names()) {
    auto j = minimal();
    j["mesh"]["element"] = name;
    const CaseConfig c = parse(j);
    EXPECT_EQ(to_string(c.mesh.element), name);
    EXPECT_EQ(effective_case_json(c)["mesh"]["element"], name);
    // The effective case parses back to the same element.
    nlohmann::json eff = effective_case_json(c);
    EXPECT_EQ(parse(eff).mesh.element, c.mesh.element);
  }
  EXPECT_TRUE(is_quadratic(ElementKind::P2));
  EXPECT_TRUE(is_quadratic(ElementKind::P2MeanDilatation));
  EXPECT_FALSE(is_quadratic(ElementKind::P1Anp));
}

TEST_F(ElementKindTest, UnknownNameNamesTheKeyAndTheChoices) {
  auto j = minimal();
  j["mesh"]["element"] = "q2";
  std::string msg;
  try {
    parse(j);
  } catch (const Error& e) {
    msg = e.what();
  }
  EXPECT_NE(msg.find("'mesh.element'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'p2_mean_dilatation'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'q2'"), std::string::npos) << msg;
  j["mesh"]["element"] = 2;
  EXPECT_THROW(parse(j), Error);
}

TEST_F(ElementKindTest, OtherElementsNeedTheFBasedKernel) {
  auto j = minimal();
  j["mesh"]["element"] = "p2";
  EXPECT_EQ(error_of(j), "");
  for (CaseModel m : {CaseModel::TensorMass, CaseModel::TlOracle}) {
    const std::string msg = error_of(j, m);
    EXPECT_NE(msg.find("'mesh.element'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'model'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("hyperelastic_tl"), std::string::npos) << msg;
  }
  j["mesh"]["element"] = "p1";
  EXPECT_EQ(error_of(j, CaseModel::TensorMass), "");
}

TEST_F(ElementKindTest, UnsupportedCombinationsNameBothKeys) {
  auto j = minimal();
  j["material"]["viscoelastic"] = nlohmann::json::parse(
      R"({"scheme": "objective", "prony": {"convention": "long_term", "terms": [{"weight": 0.5, "tau": 1.0}]}})");
  for (const char* e : {"p2", "p1_anp"}) {  // the elements with a viscoelastic form
    j["mesh"]["element"] = e;
    EXPECT_EQ(error_of(j), "") << e;
  }
  for (const char* e : {"p2_mean_dilatation"}) {
    j["mesh"]["element"] = e;
    const std::string msg = error_of(j);
    EXPECT_NE(msg.find("'mesh.element'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'material.viscoelastic'"), std::string::npos) << msg;
  }
  auto f = minimal();
  f["mesh"]["element"] = "p2";
  f["loads"] = nlohmann::json::parse(
      R"([{"name": "p", "type": "pressure", "faces": {"plane": {"axis": "z", "value": 1}}, "pressure": 10, "follower": true}])");
  std::string msg = error_of(f);
  EXPECT_NE(msg.find("'loads[0].follower'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'mesh.element'"), std::string::npos) << msg;
  f["mesh"]["element"] = "p1_anp";
  EXPECT_EQ(error_of(f), "");
}

}  // namespace
}  // namespace tmlab
