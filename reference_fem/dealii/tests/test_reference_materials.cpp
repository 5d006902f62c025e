// Constitutive laws of the reference: S = dW/dE and D = dS/dE against central finite differences
// for every law, St VK identical to the tensor-mass material, the small-strain limit of every law,
// and the Prony update (factors, consistent tangent, instantaneous-weight conversion); the laws
// added for issue 13 (Mooney-Rivlin, Ogden, Veronda-Westmann) by finite differences, and every law
// of the fast model (tensormass/materials/) equal to the reference's pointwise (W, S and D).
#include "reference_fem/dealii/materials.hpp"

#include "core/base/error.hpp"
#include "tensormass/materials/law.hpp"
#include "tensormass/materials/stvk_material.hpp"

#include <Eigen/LU>

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

using namespace tmlab::ref;
using tmlab::PronyConvention;
using tmlab::PronyIntegration;
using tmlab::PronyRelaxation;

namespace {

SymTensor2 random_strain(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> d(-scale, scale);
  SymTensor2 E;
  for (unsigned i = 0; i < 3; ++i)
    for (unsigned j = i; j < 3; ++j) E[i][j] = d(rng);
  return E;
}

double max_abs(const SymTensor2& A) {
  double m = 0.0;
  for (unsigned i = 0; i < 3; ++i)
    for (unsigned j = 0; j < 3; ++j) m = std::max(m, std::abs(A[i][j]));
  return m;
}

/// Checks S against dW/dE and D against dS/dE by central differences along random directions.
void check_derivatives(const Material& m, const SymTensor2& E, std::mt19937& rng) {
  const double h = 1e-6;
  for (int trial = 0; trial < 5; ++trial) {
    const SymTensor2 dE = random_strain(rng, 1.0);
    // dW = S : dE (the symmetric-tensor product counts off-diagonal entries twice, as it must).
    const double fd_w = (m.energy(E + h * dE) - m.energy(E - h * dE)) / (2 * h);
    const double an_w = m.stress(E) * dE;
    EXPECT_NEAR(fd_w, an_w, 1e-7 * (std::abs(an_w) + m.mu)) << m.name();
    const SymTensor2 fd_s = (m.stress(E + h * dE) - m.stress(E - h * dE)) / (2 * h);
    const SymTensor2 an_s = m.tangent(E) * dE;
    EXPECT_LE(max_abs(fd_s - an_s), 1e-7 * (max_abs(an_s) + m.mu)) << m.name();
  }
}

}  // namespace

TEST(ReferenceMaterials, StressAndTangentMatchFiniteDifferences) {
  std::mt19937 rng(42);
  for (const std::string law : {"stvk", "neo_hookean", "yeoh"}) {
    const Material m = Material::make(law, 5000.0, 0.45, 2.0, 0.5);
    for (int k = 0; k < 10; ++k) check_derivatives(m, random_strain(rng, 0.15), rng);
  }
}

TEST(ReferenceMaterials, StVenantKirchhoffIsTheTensorMassMaterial) {
  const Material m = Material::make("stvk", 5000.0, 0.45);
  const auto tm = tmlab::tm::StVenantKirchhoff::from_young_poisson(5000.0, 0.45);
  EXPECT_EQ(m.lambda, tm.lambda);
  EXPECT_EQ(m.mu, tm.mu);
  std::mt19937 rng(1);
  for (int k = 0; k < 10; ++k) {
    const SymTensor2 E = random_strain(rng, 0.3);
    tmlab::tm::Mat3 Em;
    for (unsigned i = 0; i < 3; ++i)
      for (unsigned j = 0; j < 3; ++j) Em(i, j) = E[i][j];
    EXPECT_NEAR(m.energy(E), tm.energy_density(Em), 1e-13 * tm.energy_density(Em));
    const auto Sm = tm.pk2_stress(Em);
    const SymTensor2 S = m.stress(E);
    for (unsigned i = 0; i < 3; ++i)
      for (unsigned j = 0; j < 3; ++j) EXPECT_NEAR(S[i][j], Sm(i, j), 1e-12 * Sm.norm());
  }
}

TEST(ReferenceMaterials, EveryLawLinearisesToTheLameConstants) {
  const Material stvk = Material::make("stvk", 3000.0, 0.3);
  for (const std::string law : {"neo_hookean", "yeoh"}) {
    const Material m = Material::make(law, 3000.0, 0.3, 5.0, 3.0);
    const SymTensor4 D = m.tangent(SymTensor2()), D0 = stvk.tangent(SymTensor2());
    EXPECT_LE((D - D0).norm(), 1e-10 * D0.norm()) << law;
    EXPECT_NEAR(m.energy(SymTensor2()), 0.0, 1e-12) << law;
    EXPECT_LE(max_abs(m.stress(SymTensor2())), 1e-12) << law;
  }
}

TEST(ReferenceMaterials, YeohStiffensInShearBeyondNeoHookean) {
  // Simple shear, F = I + g e1 (x) e2: J = 1, I1 = 3 + g^2; the Yeoh shear stress is
  // 2 Psi'(I1 - 3) g with Psi' = C10 + 2 C20 x + 3 C30 x^2 (closed form).
  const Material y = Material::make("yeoh", 3000.0, 0.3, 2.0, 0.5);
  for (double g : {0.1, 0.5, 1.0}) {
    dealii::Tensor<2, 3> F = dealii::unit_symmetric_tensor<3>();
    F[0][1] = g;
    const SymTensor2 E =
        0.5 * (dealii::symmetrize(dealii::transpose(F) * F) - dealii::unit_symmetric_tensor<3>());
    const dealii::Tensor<2, 3> sigma = F * dealii::Tensor<2, 3>(y.stress(E)) * dealii::transpose(F);
    const double x = g * g, c10 = y.yeoh.c10;
    const double expect = 2.0 * (c10 + 2.0 * y.yeoh.c20 * x + 3.0 * y.yeoh.c30 * x * x) * g;
    EXPECT_NEAR(sigma[0][1], expect, 1e-10 * expect);
  }
}

TEST(ReferenceMaterials, PronyFactorsAndConversion) {
  const PronySeries p = PronySeries::make(PronyConvention::Instantaneous, {0.3, 0.2}, {0.5, 5.0},
                                          PronyIntegration::ExactLinear, PronyRelaxation::Full);
  EXPECT_NEAR(p.alpha[0], 0.3 / 0.5, 1e-15);
  EXPECT_NEAR(p.alpha[1], 0.2 / 0.5, 1e-15);
  double a = 0, c = 0;
  p.factors(0, 0.1, a, c);
  EXPECT_NEAR(a, std::exp(-0.2), 1e-15);
  EXPECT_NEAR(c, (1 - std::exp(-0.2)) / 0.2, 1e-15);
  PronySeries m = p;
  m.integration = PronySeries::Integration::Midpoint;
  m.factors(0, 0.1, a, c);
  EXPECT_NEAR(c, std::exp(-0.1), 1e-15);
  m.integration = PronySeries::Integration::BackwardEuler;
  m.factors(0, 0.1, a, c);
  EXPECT_NEAR(a, 1 / 1.2, 1e-15);
  EXPECT_NEAR(c, 1 / 1.2, 1e-15);
  EXPECT_THROW(PronySeries::make(PronyConvention::Instantaneous, {0.6, 0.5}, {1, 2},
                                 PronyIntegration::ExactLinear, PronyRelaxation::Full),
               tmlab::Error);
  EXPECT_THROW(PronySeries::make(PronyConvention::LongTerm, {-0.6}, {1}, PronyIntegration::ExactLinear,
                                 PronyRelaxation::Full),
               tmlab::Error);
}

TEST(ReferenceMaterials, PronyTangentIsConsistent) {
  std::mt19937 rng(7);
  for (const std::string law : {"stvk", "neo_hookean"})
    for (const PronyRelaxation relax : {PronyRelaxation::Full, PronyRelaxation::Deviatoric}) {
      if (relax == PronyRelaxation::Deviatoric && law != "stvk") continue;
      const Material m = Material::make(law, 4000.0, 0.4);
      const PronySeries p = PronySeries::make(PronyConvention::LongTerm, {0.7, 1.3}, {0.2, 3.0},
                                              PronyIntegration::ExactLinear, relax);
      PronyState st;
      st.resize(2);
      // Some committed history.
      SymTensor2 S;
      prony_update(m, p, random_strain(rng, 0.1), 0.05, st, S, nullptr);
      st.commit();
      const SymTensor2 E = random_strain(rng, 0.1), dE = random_strain(rng, 1.0);
      const double h = 1e-6, dt = 0.1;
      SymTensor2 Sp, Sm, S0;
      SymTensor4 D;
      PronyState a = st, b = st, c = st;
      prony_update(m, p, E + h * dE, dt, a, Sp, nullptr);
      prony_update(m, p, E - h * dE, dt, b, Sm, nullptr);
      prony_update(m, p, E, dt, c, S0, &D);
      const SymTensor2 fd = (Sp - Sm) / (2 * h), an = D * dE;
      EXPECT_LE(max_abs(fd - an), 1e-7 * max_abs(an)) << law << " " << to_string(relax);
      // Deviatoric relaxation leaves a purely volumetric strain's stress unrelaxed.
      if (relax == PronyRelaxation::Deviatoric) {
        PronyState v;
        v.resize(2);
        SymTensor2 Sv;
        prony_update(m, p, 0.01 * dealii::unit_symmetric_tensor<3>(), dt, v, Sv, nullptr);
        EXPECT_LE(max_abs(Sv - m.stress(0.01 * dealii::unit_symmetric_tensor<3>())), 1e-12 * max_abs(Sv));
      }
    }
}

// ---- The laws of the fast model against the reference's, pointwise (issue 13) ----

namespace {

SymTensor2 to_dealii(const tmlab::tm::Mat3& A) {
  SymTensor2 T;
  for (unsigned i = 0; i < 3; ++i)
    for (unsigned j = i; j < 3; ++j) T[i][j] = A(i, j);
  return T;
}

tmlab::tm::Mat6 to_voigt6(const SymTensor4& D) {
  tmlab::tm::Mat6 M;
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b)
      M(a, b) = D[tmlab::tm::kVoigtI[a]][tmlab::tm::kVoigtJ[a]][tmlab::tm::kVoigtI[b]][tmlab::tm::kVoigtJ[b]];
  return M;
}

/// Deformation gradients: random (J = 1, 0.3, 1.6), simple shear 1.5, uniaxial compression to
/// J = 0.3, pure dilation (three equal stretches), two equal stretches.
std::vector<tmlab::tm::Mat3> test_deformations(std::mt19937& rng) {
  using tmlab::tm::Mat3;
  std::uniform_real_distribution<double> d(-0.4, 0.4);
  std::vector<Mat3> out;
  for (double J : {1.0, 0.3, 1.6})
    for (int k = 0; k < 2; ++k) {
      Mat3 A = Mat3::Identity();
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) A(i, j) += d(rng);
      if (A.determinant() < 0.2) continue;
      out.push_back(std::cbrt(J / A.determinant()) * A);
    }
  Mat3 shear = Mat3::Identity();
  shear(0, 1) = 1.5;
  out.push_back(shear);
  out.push_back(Eigen::Vector3d(0.3, 1.0, 1.0).asDiagonal());
  out.push_back(std::cbrt(0.3) * Mat3::Identity());
  out.push_back(Eigen::Vector3d(0.7, 0.7, 1.4).asDiagonal());
  return out;
}

/// The reference law `ref` and the fast model's `law` agree in W, S and D at every test deformation.
template <class RefLaw>
void expect_same_law(const RefLaw& ref, const tmlab::tm::Law& law, const std::string& name) {
  std::mt19937 rng(17);
  const double scale = law.small_strain().mu + std::abs(law.small_strain().lambda);
  double ew = 0.0, es = 0.0, ed = 0.0;  // largest relative differences, printed for the docs
  for (const auto& F : test_deformations(rng)) {
    const tmlab::tm::Mat3 Em = 0.5 * (F.transpose() * F - tmlab::tm::Mat3::Identity());
    const SymTensor2 E = to_dealii(Em);
    double w = 0.0;
    tmlab::tm::Mat3 S;
    tmlab::tm::Mat6 D;
    law.evaluate(Em, &w, &S, &D);
    EXPECT_NEAR(ref.energy(E), w, 1e-12 * (std::abs(w) + scale)) << name;
    const SymTensor2 Sr = ref.stress(E);
    EXPECT_LE(max_abs(Sr - to_dealii(S)), 1e-12 * (S.cwiseAbs().maxCoeff() + scale)) << name;
    const tmlab::tm::Mat6 Dr = to_voigt6(ref.tangent(E));
    EXPECT_LE((Dr - D).cwiseAbs().maxCoeff(), 1e-11 * (D.cwiseAbs().maxCoeff() + scale)) << name;
    ew = std::max(ew, std::abs(ref.energy(E) - w) / (std::abs(w) + scale));
    es = std::max(es, max_abs(Sr - to_dealii(S)) / (S.cwiseAbs().maxCoeff() + scale));
    ed = std::max(ed, (Dr - D).cwiseAbs().maxCoeff() / (D.cwiseAbs().maxCoeff() + scale));
  }
  std::printf("%-20s reference vs fast model, max relative difference: W %.1e  S %.1e  D %.1e\n",
              name.c_str(), ew, es, ed);
}

/// S against dW/dE and D against dS/dE (central differences), for a law without Material's wrapper.
template <class RefLaw>
void check_law_derivatives(const RefLaw& law, double scale, const std::string& name) {
  std::mt19937 rng(23);
  const double h = 1e-6;
  for (int k = 0; k < 10; ++k) {
    const SymTensor2 E = random_strain(rng, 0.15), dE = random_strain(rng, 1.0);
    const double fd_w = (law.energy(E + h * dE) - law.energy(E - h * dE)) / (2 * h);
    const double an_w = law.stress(E) * dE;
    EXPECT_NEAR(fd_w, an_w, 1e-7 * (std::abs(an_w) + scale)) << name;
    const SymTensor2 fd_s = (law.stress(E + h * dE) - law.stress(E - h * dE)) / (2 * h);
    const SymTensor2 an_s = law.tangent(E) * dE;
    EXPECT_LE(max_abs(fd_s - an_s), 1e-7 * (max_abs(an_s) + scale)) << name;
  }
}

}  // namespace

TEST(ReferenceMaterials, NewLawsStressAndTangentMatchFiniteDifferences) {
  check_law_derivatives(MooneyRivlinLaw{700.0, 300.0, 2e4}, 1000.0, "mooney_rivlin");
  check_law_derivatives(VerondaWestmannLaw{200.0, 5.0, 2e4}, 1000.0, "veronda_westmann");
  check_law_derivatives(OgdenLaw{{630.0, 1.2, -10.0}, {1.3, 5.0, -2.0}, 1e5}, 400.0, "ogden");
}

TEST(ReferenceMaterials, FastModelLawsEqualTheReferenceLawsPointwise) {
  namespace tm = tmlab::tm;
  const double young = 3000.0, nu = 0.45;
  // St VK, neo-Hookean and Yeoh through the reference's own Material::make (the case-file path).
  const Material stvk = Material::make("stvk", young, nu), neo = Material::make("neo_hookean", young, nu);
  const Material yeoh = Material::make("yeoh", young, nu, 2.0, 0.5);
  expect_same_law(stvk, tm::StVenantKirchhoff::from_young_poisson(young, nu), "stvk");
  expect_same_law(neo, tm::NeoHookean::from_young_poisson(young, nu), "neo_hookean");
  expect_same_law(yeoh, tm::Yeoh(yeoh.yeoh.c10, yeoh.yeoh.c20, yeoh.yeoh.c30, yeoh.yeoh.kappa), "yeoh");
  expect_same_law(MooneyRivlinLaw{700.0, 300.0, 2e4}, tm::MooneyRivlin(700.0, 300.0, 2e4), "mooney_rivlin");
  expect_same_law(MooneyRivlinLaw{700.0, -100.0, 2e4}, tm::MooneyRivlin(700.0, -100.0, 2e4),
                  "mooney_rivlin c01<0");
  expect_same_law(VerondaWestmannLaw{200.0, 5.0, 2e4}, tm::VerondaWestmann(200.0, 5.0, 2e4),
                  "veronda_westmann");
  expect_same_law(OgdenLaw{{630.0, 1.2, -10.0}, {1.3, 5.0, -2.0}, 1e5},
                  tm::Ogden({630.0, 1.2, -10.0}, {1.3, 5.0, -2.0}, 1e5), "ogden");
  expect_same_law(OgdenLaw{{2.0, -0.5}, {0.5, -3.5}, 3.0}, tm::Ogden({2.0, -0.5}, {0.5, -3.5}, 3.0),
                  "ogden 2");
}

TEST(ReferenceMaterials, EveryLawFromTheCaseFileParameters) {
  // Material::make(law, parameters): the case file's plain parameters (core/constitutive) build
  // every law; the wrapper dispatches to it (S and D against differences of W and S through the
  // wrapper) and its small-strain Lame constants are the parameters' (D(0) = lambda I(x)I + 2 mu II).
  using tmlab::LawParameters, tmlab::MaterialLaw, tmlab::SmallStrainModuli;
  LawParameters p;
  p.young = 5000.0, p.poisson = 0.45;
  p.c10 = 700.0, p.c01 = 300.0, p.c20 = 100.0, p.c30 = 10.0, p.c1 = 200.0, p.c2 = 5.0;
  p.mu = {630.0, 1.2, -10.0}, p.alpha = {1.3, 5.0, -2.0}, p.kappa = 2e4;
  std::mt19937 rng(7);
  for (const char* name : tmlab::kMaterialLawNames) {
    const MaterialLaw law = tmlab::material_law_from_string(name).value();
    const Material m = Material::make(law, p);
    EXPECT_EQ(m.name(), name);
    for (int k = 0; k < 5; ++k) check_derivatives(m, random_strain(rng, 0.15), rng);
    const SmallStrainModuli s = tmlab::small_strain_moduli(law, p);
    const Material lame = Material::make(MaterialLaw::StVK, s.young(), s.poisson());
    const SymTensor4 D = m.tangent(SymTensor2()), D0 = lame.tangent(SymTensor2());
    EXPECT_LE((D - D0).norm(), 1e-10 * D0.norm()) << name;
    EXPECT_NEAR(m.mu, s.shear, 1e-12 * s.shear) << name;
  }
  // Refused parameters name the key; the E/nu override refuses the laws that have their own keys.
  p.mu = {100.0, 50.0}, p.alpha = {2.0, -5.0};
  try {
    Material::make(MaterialLaw::Ogden, p);
    FAIL() << "unstable Ogden accepted";
  } catch (const tmlab::Error& e) {
    EXPECT_NE(std::string(e.what()).find("key 'mu'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(Material::make("ogden", 5000.0, 0.45), tmlab::Error);
  EXPECT_THROW(Material::make(MaterialLaw::MooneyRivlin, 5000.0, 0.45), tmlab::Error);
}
