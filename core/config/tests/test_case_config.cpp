// Case-file parsing: defaults, strictness (unknown keys), and messages naming file and key path.
#include "core/base/error.hpp"
#include "core/config/case_config.hpp"
#include "core/constitutive/law_catalogue.hpp"
#include "core/testing/law_samples.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace tmlab {
namespace {

namespace fs = std::filesystem;

class CaseConfigTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("tmlab_case_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    std::ofstream(dir_ / "m.msh") << "placeholder";  // only existence is checked by parse_case
  }
  void TearDown() override { fs::remove_all(dir_); }
  nlohmann::json minimal() const {
    return nlohmann::json::parse(R"({
      "name": "t", "mesh": {"file": "m.msh"},
      "material": {"E": 1000, "nu": 0.3, "density": 1000},
      "boundary": [{"name": "fixed", "nodes": {"plane": {"axis": "z", "value": 0}}}],
      "solver": {"type": "static"}
    })");
  }
  std::string error_of(const nlohmann::json& j) const {
    try {
      parse_case(j, "case.json", {dir_.string()});
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
};

TEST_F(CaseConfigTest, MinimalCaseGetsDefaults) {
  const CaseConfig c = parse_case(minimal(), "case.json", {dir_.string()});
  EXPECT_EQ(c.model, CaseModel::TensorMass);
  EXPECT_EQ(c.material.law, MaterialLaw::StVK);
  EXPECT_EQ(c.solver.steps, 10);
  EXPECT_DOUBLE_EQ(c.solver.t_end, 1.0);
  ASSERT_EQ(c.boundary.size(), 1u);
  EXPECT_EQ(c.boundary[0].components, (std::array<bool, 3>{true, true, true}));
  EXPECT_TRUE(fs::exists(c.mesh.file));
}

TEST_F(CaseConfigTest, ErrorsNameTheKeyPath) {
  auto j = minimal();
  j["solver"]["stepz"] = 3;
  EXPECT_NE(error_of(j).find("'solver.stepz'"), std::string::npos) << error_of(j);

  j = minimal();
  j["material"]["nu"] = 0.5;
  EXPECT_NE(error_of(j).find("'material.nu'"), std::string::npos) << error_of(j);

  j = minimal();
  j["material"]["E"] = -3;
  EXPECT_NE(error_of(j).find("'material.E' must be > 0"), std::string::npos) << error_of(j);

  j = minimal();
  j["boundary"][0]["components"] = "xw";
  EXPECT_NE(error_of(j).find("'boundary[0].components'"), std::string::npos) << error_of(j);

  j = minimal();
  j["solver"] = {{"type", "explicit"}, {"dt", 2.0}, {"t_end", 1.0}};
  EXPECT_NE(error_of(j).find("'solver.dt'"), std::string::npos) << error_of(j);

  j = minimal();
  j["mesh"]["file"] = "missing.msh";
  EXPECT_NE(error_of(j).find("file not found"), std::string::npos) << error_of(j);

  j = minimal();
  j["loads"] = {{{"type", "gravity"}, {"acceleration", {0, 0}}}};
  EXPECT_NE(error_of(j).find("'loads[0].acceleration'"), std::string::npos) << error_of(j);

  j = minimal();
  j["boundary"][0]["function"] = {{"type", "ramp"}, {"t0", 1.0}, {"t1", 0.5}};
  EXPECT_NE(error_of(j).find("boundary[0].function"), std::string::npos) << error_of(j);

  j = minimal();
  j["extra"] = true;
  EXPECT_NE(error_of(j).find("unknown key 'extra'"), std::string::npos) << error_of(j);
}

TEST_F(CaseConfigTest, ChoicesAreParsedOnceIntoEnums) {
  auto j = minimal();
  j["model"] = "tl_oracle";
  j["material"]["viscoelastic"] = {
      {"history", "nodal_force"},
      {"integration", "backward_euler"},
      {"prony", {{"convention", "instantaneous"}, {"terms", {{{"weight", 0.5}, {"tau", 1.0}}}}}}};
  j["solver"] = {{"type", "implicit"}, {"dt", 0.1}, {"scheme", "backward_euler"}};
  CaseConfig c = parse_case(j, "case.json", {dir_.string()});
  EXPECT_EQ(c.model, CaseModel::TlOracle);
  const ViscoelasticSpec& vs = c.material.viscoelastic;
  EXPECT_TRUE(vs.enabled);
  EXPECT_EQ(vs.history, PronyHistory::NodalForce);
  EXPECT_EQ(vs.integration, PronyIntegration::BackwardEuler);
  EXPECT_EQ(vs.relaxation, PronyRelaxation::Full);
  EXPECT_EQ(vs.convention, PronyConvention::Instantaneous);
  EXPECT_FALSE(vs.scheme);
  EXPECT_EQ(c.solver.scheme, ImplicitScheme::BackwardEuler);
  // A shorthand sets both halves and is remembered.
  j["material"]["viscoelastic"] = {{"scheme", "objective"},
                                   {"relaxation", "deviatoric"},
                                   {"prony", {{"terms", {{{"weight", 0.5}, {"tau", 1.0}}}}}}};
  c = parse_case(j, "case.json", {dir_.string()});
  EXPECT_EQ(c.material.viscoelastic.scheme, PronyScheme::Objective);
  EXPECT_EQ(c.material.viscoelastic.history, PronyHistory::Pk2);
  EXPECT_EQ(c.material.viscoelastic.integration, PronyIntegration::ExactLinear);
  EXPECT_EQ(c.material.viscoelastic.relaxation, PronyRelaxation::Deviatoric);
  EXPECT_EQ(c.material.viscoelastic.convention, PronyConvention::LongTerm);
}

TEST_F(CaseConfigTest, BadChoicesNameTheAcceptedValues) {
  const nlohmann::json prony = {{"terms", {{{"weight", 0.5}, {"tau", 1.0}}}}};
  struct Bad {
    const char* section;
    nlohmann::json value;
    const char* message;
  };
  const Bad cases[] = {
      {"model", "fem", "key 'model' must be 'tensor_mass', 'tl_oracle' or 'hyperelastic_tl' (got 'fem')"},
      {"law", "hooke",
       "key 'material.law' must be 'stvk', 'neo_hookean', 'mooney_rivlin', 'yeoh', 'ogden' or "
       "'veronda_westmann' (got 'hooke')"},
      {"history", "stress",
       "key 'material.viscoelastic.history' must be 'nodal_force' or 'pk2' (got 'stress')"},
      {"integration", "trapezoid",
       "key 'material.viscoelastic.integration' must be 'midpoint', 'exact_linear' or 'backward_euler' (got "
       "'trapezoid')"},
      {"relaxation", "bulk",
       "key 'material.viscoelastic.relaxation' must be 'full' or 'deviatoric' (got 'bulk')"},
      {"scheme", "nava",
       "key 'material.viscoelastic.scheme' unknown scheme 'nava' (expected xu2011, xu2011_exact_linear, "
       "backward_euler "
       "or objective)"},
      {"convention", "nava",
       "key 'material.viscoelastic.prony.convention' must be 'long_term' or 'instantaneous' (got 'nava')"},
      {"solver", "crank", "key 'solver.scheme' must be 'newmark' or 'backward_euler' (got 'crank')"},
      {"linear", "umfpack", "key 'solver.linear' must be 'auto', 'ldlt' or 'cholmod' (got 'umfpack')"},
  };
  for (const Bad& b : cases) {
    auto j = minimal();
    const std::string section = b.section;
    j["material"]["viscoelastic"] = {{"prony", prony}};
    if (section == "model") j["model"] = b.value;
    if (section == "law") j["material"]["law"] = b.value;
    if (section == "history" || section == "integration" || section == "relaxation" || section == "scheme")
      j["material"]["viscoelastic"][section] = b.value;
    if (section == "convention") j["material"]["viscoelastic"]["prony"]["convention"] = b.value;
    if (section == "solver") j["solver"] = {{"type", "implicit"}, {"dt", 0.1}, {"scheme", b.value}};
    if (section == "linear") j["solver"]["linear"] = b.value;
    EXPECT_NE(error_of(j).find(b.message), std::string::npos) << error_of(j);
  }
}

TEST_F(CaseConfigTest, LinearSolverIsAutoByDefaultAndReadsAsWritten) {
  EXPECT_EQ(parse_case(minimal(), "case.json", {dir_.string()}).solver.linear, SolverSpec::Linear::Auto);
  for (const auto& [name, value] :
       {std::pair{"auto", SolverSpec::Linear::Auto}, std::pair{"ldlt", SolverSpec::Linear::Ldlt},
        std::pair{"cholmod", SolverSpec::Linear::Cholmod}}) {
    auto j = minimal();
    j["solver"]["linear"] = name;
    const CaseConfig c = parse_case(j, "case.json", {dir_.string()});
    EXPECT_EQ(c.solver.linear, value) << name;
    EXPECT_EQ(effective_case_json(c)["solver"]["linear"], name);  // the manifest names it as written
  }
  auto j = minimal();
  j["solver"] = {{"type", "explicit"}, {"dt", 1e-3}, {"linear", "auto"}};
  EXPECT_NE(error_of(j).find("key 'solver.linear' is not used by the explicit solver"), std::string::npos)
      << error_of(j);
}

TEST_F(CaseConfigTest, JsonSyntaxErrorNamesFileAndLine) {
  const fs::path p = dir_ / "bad.json";
  std::ofstream(p) << "{\n  \"name\": \"x\",\n  \"mesh\": {\n}}}\n";
  try {
    load_case(p.string(), dir_.string());
    FAIL() << "expected an error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("bad.json"), std::string::npos) << m;
    EXPECT_NE(m.find("line 4"), std::string::npos) << m;
  }
}

TEST_F(CaseConfigTest, EffectiveConfigHasEveryDefaultAndRoundTrips) {
  // The manifest's configuration is what the run used: defaults filled in, shorthands resolved.
  nlohmann::json j = minimal();
  j["material"]["viscoelastic"] = {{"scheme", "xu2011"},
                                   {"prony", {{"terms", {{{"weight", 0.5}, {"tau", 1.0}}}}}}};
  j["loads"] = {
      {{"type", "pressure"}, {"faces", {{"plane", {{"axis", "z"}, {"value", 0}}}}}, {"pressure", 10}}};
  const CaseConfig c = parse_case(j, "case.json", {dir_.string()});
  const nlohmann::json e = effective_case_json(c);
  EXPECT_EQ(e["solver"]["newton"]["line_search"], "energy") << e.dump();
  EXPECT_EQ(e["solver"]["newton"]["max_iterations"], 25);
  EXPECT_EQ(e["solver"]["steps"], 10);
  EXPECT_EQ(e["solver"]["linear"], "auto");  // CHOLMOD with the LDL^T fallback
  EXPECT_EQ(e["output"]["every"], 1);
  EXPECT_EQ(e["material"]["viscoelastic"]["history"], "nodal_force");
  EXPECT_EQ(e["material"]["viscoelastic"]["integration"], "midpoint");
  EXPECT_EQ(e["material"]["viscoelastic"]["prony"]["convention"], "long_term");
  EXPECT_EQ(e["loads"][0]["follower"], false);
  EXPECT_EQ(e["boundary"][0]["components"], "xyz");
  // parse_case(effective) is the same case.
  const CaseConfig again = parse_case(e, "effective.json", {dir_.string()});
  EXPECT_EQ(effective_case_json(again), e);
  // The scheme's former name "seed" still reads, as the same case.
  nlohmann::json old = j;
  old["material"]["viscoelastic"]["scheme"] = "seed";
  const CaseConfig c_old = parse_case(old, "case.json", {dir_.string()});
  EXPECT_EQ(c_old.material.viscoelastic.scheme, PronyScheme::Xu2011);
  EXPECT_EQ(effective_case_json(c_old), e);
  // Dynamics: dt and the damping block, no static steps.
  j["solver"] = {{"type", "implicit"}, {"dt", 0.1}};
  const nlohmann::json d = effective_case_json(parse_case(j, "case.json", {dir_.string()}));
  EXPECT_EQ(d["solver"]["scheme"], "newmark");
  EXPECT_FALSE(d["solver"].contains("steps"));
  EXPECT_EQ(effective_case_json(parse_case(d, "effective.json", {dir_.string()})), d);
}

TEST_F(CaseConfigTest, EveryLawWithItsOwnKeys) {
  struct Case {
    nlohmann::json material;
    MaterialLaw law;
    double shear;  // small-strain shear modulus of the parameters
  };
  const Case cases[] = {
      {{{"law", "neo_hookean"}, {"E", 2600.0}, {"nu", 0.3}}, MaterialLaw::NeoHookean, 1000.0},
      {{{"law", "mooney_rivlin"}, {"c10", 400.0}, {"c01", 100.0}, {"kappa", 1e5}},
       MaterialLaw::MooneyRivlin,
       1000.0},
      {{{"law", "yeoh"}, {"c10", 500.0}, {"c20", 50.0}, {"kappa", 1e5}}, MaterialLaw::Yeoh, 1000.0},
      {{{"law", "ogden"}, {"mu", {600.0, -40.0}}, {"alpha", {2.0, -5.0}}, {"kappa", 1e5}},
       MaterialLaw::Ogden,
       700.0},
      {{{"law", "veronda_westmann"}, {"c1", 250.0}, {"c2", 4.0}, {"kappa", 1e5}},
       MaterialLaw::VerondaWestmann,
       1000.0},
  };
  for (const Case& k : cases) {
    auto j = minimal();
    j["material"] = k.material;
    j["material"]["density"] = 1000.0;
    const CaseConfig c = parse_case(j, "case.json", {dir_.string()});
    EXPECT_EQ(c.material.law, k.law) << k.material.dump();
    const SmallStrainModuli m = small_strain_moduli(c.material.law, c.material.parameters);
    EXPECT_NEAR(m.shear, k.shear, 1e-9 * k.shear) << k.material.dump();
    // E and nu are the small-strain ones: E / (2 (1 + nu)) is the shear modulus.
    EXPECT_NEAR(c.material.young / (2.0 * (1.0 + c.material.poisson)), k.shear, 1e-9 * k.shear);
    // The effective configuration round-trips.
    const nlohmann::json e = effective_case_json(c);
    EXPECT_EQ(e["material"]["law"], to_string(k.law));
    EXPECT_EQ(effective_case_json(parse_case(e, "effective.json", {dir_.string()})), e) << e.dump();
  }
  // nu instead of kappa: kappa = 2 G (1 + nu) / (3 (1 - 2 nu)), and the small-strain nu is that nu.
  auto j = minimal();
  j["material"] = {{"law", "yeoh"}, {"c10", 500.0}, {"nu", 0.45}, {"density", 1000.0}};
  const CaseConfig c = parse_case(j, "case.json", {dir_.string()});
  EXPECT_NEAR(c.material.parameters.kappa, 2.0 * 1000.0 * 1.45 / (3.0 * 0.1), 1e-8);
  EXPECT_NEAR(c.material.poisson, 0.45, 1e-14);
  EXPECT_EQ(c.material.parameters.c20, 0.0);
}

TEST_F(CaseConfigTest, BadLawParametersNameFileAndKey) {
  struct Bad {
    nlohmann::json material;
    const char* message;
  };
  const Bad cases[] = {
      {{{"law", "mooney_rivlin"}, {"E", 1000.0}, {"nu", 0.3}},
       "case.json: key 'material.E' is not a parameter of law 'mooney_rivlin' (its keys: c10, c01, kappa, "
       "nu"},
      {{{"law", "mooney_rivlin"}, {"c10", 400.0}, {"kappa", 1e5}},
       "case.json: key 'material.c01' is required"},
      {{{"law", "yeoh"}, {"c10", 400.0}},
       "key 'material.kappa' or 'nu': law 'yeoh' needs exactly one of the bulk modulus 'kappa'"},
      {{{"law", "yeoh"}, {"c10", 400.0}, {"kappa", 1e5}, {"nu", 0.4}}, "needs exactly one of"},
      {{{"law", "yeoh"}, {"c10", -400.0}, {"kappa", 1e5}},
       "key 'material.c10' must be > 0 (got -400) (law 'yeoh')"},
      {{{"law", "ogden"}, {"mu", {100.0, 50.0}}, {"alpha", {2.0, -5.0}}, {"kappa", 1e5}},
       "case.json: key 'material.mu' violates the Ogden stability condition sum_p mu_p alpha_p > 0"},
      {{{"law", "ogden"}, {"mu", {100.0}}, {"alpha", {2.0, 1.0}}, {"kappa", 1e5}},
       "key 'material.alpha' must have as many terms as mu"},
      {{{"law", "ogden"}, {"mu", {100.0}}, {"alpha", {0.0}}, {"nu", 0.4}}, "key 'material.alpha' term 1"},
      {{{"law", "veronda_westmann"}, {"c1", 100.0}, {"c2", 2.0}, {"kappa", 0.0}},
       "key 'material.kappa' must be > 0"},
      {{{"law", "veronda_westmann"}, {"c1", 100.0}, {"c2", 2.0}, {"nu", 0.5}},
       "key 'material.nu' must satisfy"},
      {{{"law", "neo_hookean"}, {"E", 1000.0}, {"nu", 0.3}, {"kappa", 1e5}},
       "key 'material.kappa' is not a parameter of law 'neo_hookean'"},
      // A key of no law is an unknown key, as anywhere in a case file.
      {{{"law", "ogden"}, {"mu", {100.0}}, {"alpha", {2.0}}, {"kappa", 1e5}, {"colour", 1}},
       "case.json: unknown key 'material.colour'"},
  };
  for (const Bad& b : cases) {
    auto j = minimal();
    j["material"] = b.material;
    j["material"]["density"] = 1000.0;
    EXPECT_NE(error_of(j).find(b.message), std::string::npos) << b.material.dump() << "\n" << error_of(j);
  }
}

// The material section takes exactly the catalogue's laws under their case keys (lists as lists, the
// decoupled laws with kappa), and names every law when the law is unknown.
TEST_F(CaseConfigTest, MaterialLawsAreTheCatalogues) {
  for (const LawDescriptor& d : law_catalogue()) {
    const LawParameters p = testing::sample_parameters(d.law);
    nlohmann::json m = {{"law", d.name}, {"density", 1000.0}};
    for (const LawParameterInfo& info : d.parameters) {
      if (info.list)
        m[info.case_key] = p.*info.values;
      else
        m[info.case_key] = p.*info.scalar;
    }
    if (d.bulk == BulkResponse::KappaOrPoisson) m["kappa"] = p.kappa;
    auto j = minimal();
    j["material"] = m;
    const CaseConfig c = parse_case(j, "case.json", {dir_.string()});
    EXPECT_EQ(c.material.law, d.law);
    EXPECT_EQ(small_strain_moduli(d.law, c.material.parameters).shear, d.shear_modulus(p)) << d.name;
  }
  auto j = minimal();
  j["material"] = {{"law", "hooke"}, {"E", 1000.0}, {"nu", 0.3}, {"density", 1000.0}};
  const std::string e = error_of(j);
  EXPECT_NE(e.find("'material.law'"), std::string::npos) << e;
  for (const std::string& n : law_name_list()) EXPECT_NE(e.find(n), std::string::npos) << e;
}

}  // namespace
}  // namespace tmlab
