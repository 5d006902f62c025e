// The law factory: every law from its keys, errors naming the key (missing, non-numeric, unknown,
// refused by the law), and the name list.
#include "core/base/error.hpp"
#include "core/constitutive/law_catalogue.hpp"
#include "core/testing/law_samples.hpp"
#include "tensormass/materials/law_factory.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace tmlab::tm {
namespace {

using nlohmann::json;

std::string error_of(const std::string& name, const json& p) {
  try {
    make_law(name, p, "case.json: material");
  } catch (const Error& e) {
    return e.what();
  }
  return {};
}

TEST(LawFactory, BuildsEveryLawWithItsParameters) {
  const Law stvk = make_law("stvk", json{{"young", 3000.0}, {"poisson", 0.45}}, "m");
  EXPECT_EQ(stvk.name(), "stvk");
  EXPECT_NEAR(stvk.small_strain().mu, 3000.0 / 2.9, 1e-12);
  const Law stvk2 = make_law("stvk", json{{"lambda", 2.0}, {"mu", 1.0}, {"law", "stvk"}}, "m");
  EXPECT_EQ(stvk2.get_if<StVenantKirchhoff>()->lambda, 2.0);

  const Law nh = make_law("neo_hookean", json{{"young", 3000.0}, {"poisson", 0.45}}, "m");
  EXPECT_NEAR(nh.get_if<NeoHookean>()->lambda(), stvk.small_strain().lambda, 1e-9);

  const Law mr = make_law("mooney_rivlin", json{{"c10", 1.0}, {"c01", 0.5}, {"kappa", 10.0}}, "m");
  EXPECT_EQ(mr.get_if<MooneyRivlin>()->c01(), 0.5);

  const Law y = make_law("yeoh", json{{"c10", 1.0}, {"kappa", 10.0}, {"c30", 0.2}}, "m");
  EXPECT_EQ(y.get_if<Yeoh>()->c20(), 0.0);
  EXPECT_EQ(y.get_if<Yeoh>()->c30(), 0.2);

  const Law o = make_law("ogden", json{{"mu", {1.0, -0.1}}, {"alpha", {2.0, -1.0}}, {"kappa", 10.0}}, "m");
  EXPECT_EQ(o.get_if<Ogden>()->num_terms(), 2u);
  EXPECT_NEAR(o.small_strain().mu, 0.5 * (2.0 + 0.1), 1e-15);

  const Law vw = make_law("veronda_westmann", json{{"c1", 0.5}, {"c2", 3.0}, {"kappa", 10.0}}, "m");
  EXPECT_NEAR(vw.small_strain().mu, 1.5, 1e-15);
  for (const auto& n : law_names()) EXPECT_FALSE(n.empty());
  EXPECT_EQ(law_names().size(), 6u);
}

TEST(LawFactory, ErrorsNameTheKey) {
  EXPECT_NE(error_of("hookean", json::object()).find("case.json: material.law 'hookean' is unknown"),
            std::string::npos);
  EXPECT_NE(error_of("yeoh", json::array()).find("must be a JSON object"), std::string::npos);
  EXPECT_NE(error_of("yeoh", json{{"c10", 1.0}}).find("case.json: material.kappa is missing"),
            std::string::npos);
  EXPECT_NE(error_of("yeoh", json{{"c10", "1"}, {"kappa", 1.0}}).find("material.c10 must be a number"),
            std::string::npos);
  EXPECT_NE(error_of("yeoh", json{{"c10", 1.0}, {"kappa", 1.0}, {"c02", 1.0}})
                .find("material.c02 is not a parameter"),
            std::string::npos);
  EXPECT_NE(
      error_of("ogden", json{{"mu", 1.0}, {"alpha", {2.0}}, {"kappa", 1.0}}).find("material.mu must be a"),
      std::string::npos);
  EXPECT_NE(error_of("ogden", json{{"mu", {1.0, "x"}}, {"alpha", {2.0, 1.0}}, {"kappa", 1.0}})
                .find("material.mu[1]"),
            std::string::npos);
  EXPECT_NE(error_of("stvk", json{{"young", 1.0}, {"mu", 1.0}}).find("not both"), std::string::npos);
  EXPECT_NE(error_of("stvk", json{{"lambda", 1.0}, {"mu", -1.0}}).find("mu > 0"), std::string::npos);
}

TEST(LawFactory, RefusedParametersNameTheCaseKeys) {
  // Ogden stability: the message names the location, the law, the keys and the condition.
  const std::string e = error_of("ogden", json{{"mu", {1.0, -3.0}}, {"alpha", {2.0, 2.0}}, {"kappa", 1.0}});
  EXPECT_NE(e.find("case.json: material (law 'ogden', keys \"mu\", \"alpha\", \"kappa\")"), std::string::npos)
      << e;
  EXPECT_NE(e.find("sum_p mu_p alpha_p > 0"), std::string::npos) << e;
  const std::string k = error_of("mooney_rivlin", json{{"c10", 1.0}, {"c01", 0.0}, {"kappa", 0.0}});
  EXPECT_NE(k.find("bulk modulus"), std::string::npos) << k;
  EXPECT_NE(k.find("kappa = 0"), std::string::npos) << k;
  EXPECT_NE(error_of("neo_hookean", json{{"young", 1.0}, {"poisson", 0.5}}).find("Poisson's ratio"),
            std::string::npos);
  EXPECT_NE(error_of("veronda_westmann", json{{"c1", 1.0}, {"c2", 0.0}, {"kappa", 1.0}}).find("c2 = 0"),
            std::string::npos);
}

TEST(LawFactory, PlainParametersOfTheCaseFileGiveTheSameLaw) {
  // One vocabulary: core's law names are the factory's, in the same order.
  ASSERT_EQ(law_names().size(), std::size(kMaterialLawNames));
  for (std::size_t k = 0; k < law_names().size(); ++k) EXPECT_EQ(law_names()[k], kMaterialLawNames[k]);
  LawParameters p;
  p.young = 3000.0, p.poisson = 0.45;
  p.c10 = 400.0, p.c01 = 100.0, p.c20 = 30.0, p.c30 = 5.0, p.c1 = 200.0, p.c2 = 2.5;
  p.mu = {600.0, -40.0}, p.alpha = {2.0, -5.0}, p.kappa = 2e4;
  const Mat3 E = (Mat3() << 0.05, 0.01, -0.02, 0.01, -0.03, 0.015, -0.02, 0.015, 0.02).finished();
  for (const char* name : kMaterialLawNames) {
    const MaterialLaw law = material_law_from_string(name).value();
    const Law plain = make_law(law, p, "case.json: material");
    EXPECT_EQ(plain.name(), name);
    // The small-strain moduli core computes are the law's.
    const SmallStrainModuli m = small_strain_moduli(law, p);
    EXPECT_NEAR(plain.small_strain().mu, m.shear, 1e-12 * m.shear) << name;
    EXPECT_NEAR(plain.small_strain().lambda, m.lambda(), 1e-9 * m.bulk) << name;
    // And the law is the one the JSON parameters build.
    json j;
    if (law_takes_young_poisson(law))
      j = {{"young", p.young}, {"poisson", p.poisson}};
    else if (law == MaterialLaw::MooneyRivlin)
      j = {{"c10", p.c10}, {"c01", p.c01}, {"kappa", p.kappa}};
    else if (law == MaterialLaw::Yeoh)
      j = {{"c10", p.c10}, {"c20", p.c20}, {"c30", p.c30}, {"kappa", p.kappa}};
    else if (law == MaterialLaw::Ogden)
      j = {{"mu", p.mu}, {"alpha", p.alpha}, {"kappa", p.kappa}};
    else
      j = {{"c1", p.c1}, {"c2", p.c2}, {"kappa", p.kappa}};
    EXPECT_EQ(plain.pk2_stress(E), make_law(name, j, "m").pk2_stress(E)) << name;
  }
  p.mu = {600.0, 40.0}, p.alpha = {2.0, -50.0};  // sum mu_p alpha_p = 1200 - 2000 < 0
  try {
    make_law(MaterialLaw::Ogden, p, "case.json: material");
    FAIL() << "expected the stability error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("case.json: material (law 'ogden'"), std::string::npos) << e.what();
  }
}

// The law catalogue and the laws agree: every row builds from its sample values (the fit's starting
// values, defaults where given) by both factories, is the variant alternative of its enum, and
// linearises to the catalogue's small-strain shear modulus: the central difference of S_12 under a
// tiny simple shear F = I + g e1 (x) e2 (S_12 = G g + O(g^3) at F = I).
TEST(LawFactory, EveryCatalogueLawBuildsAndLinearisesToItsShearModulus) {
  for (const LawDescriptor& d : law_catalogue()) {
    const LawParameters p = testing::sample_parameters(d.law);
    const Law law = make_law(d.law, p, "catalogue");
    EXPECT_EQ(law.kind(), d.law);
    EXPECT_EQ(law.name(), d.name);
    const double G = small_strain_moduli(d.law, p).shear;
    EXPECT_EQ(G, d.shear_modulus(p)) << d.name;
    EXPECT_NEAR(law.small_strain().mu, G, 1e-12 * G) << d.name;
    const double g = 1e-5;
    auto s12 = [&](double shear) {
      Mat3 F = Mat3::Identity();
      F(0, 1) = shear;
      const Mat3 E = 0.5 * (F.transpose() * F - Mat3::Identity());
      return law.pk2_stress(E)(0, 1);
    };
    const double G_fd = (s12(g) - s12(-g)) / (2.0 * g);
    EXPECT_NEAR(G_fd, G, 1e-6 * G) << d.name;
    // The parameter object under the catalogue's names gives the same law.
    json j = json::object();
    for (const LawParameterInfo& info : d.parameters) {
      if (info.list)
        j[info.name] = p.*info.values;
      else
        j[info.name] = p.*info.scalar;
    }
    if (d.bulk == BulkResponse::KappaOrPoisson) j["kappa"] = p.kappa;
    EXPECT_EQ(make_law(d.name, j, "catalogue").small_strain().mu, law.small_strain().mu) << d.name;
  }
  // Exactly the catalogue's names: another is refused with the list.
  EXPECT_EQ(law_names(), law_name_list());
  const std::string e = error_of("hooke", json::object());
  for (const LawDescriptor& d : law_catalogue())
    EXPECT_NE(e.find(std::string("\"") + d.name + "\""), std::string::npos) << e;
}

}  // namespace
}  // namespace tmlab::tm
