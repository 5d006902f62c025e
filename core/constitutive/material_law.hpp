// The hyperelastic laws, one vocabulary for the case file (core/config), the fast model
// (tensormass/materials/law_factory.hpp builds a tm::Law from these values) and the deal.II
// reference (reference_fem/dealii/materials.hpp): their names, their parameters in plain form, and
// the small-strain moduli each law linearises to. Energies, stresses and tangents live with the
// models; docs/theory/hyperelastic-laws.md has the equations, docs/case-files.md the keys.
#pragma once

#include "core/base/enum_names.hpp"

#include <optional>
#include <string>
#include <vector>

namespace tmlab {

/// stvk: St Venant-Kirchhoff; neo_hookean: compressible neo-Hookean; mooney_rivlin, yeoh, ogden,
/// veronda_westmann: decoupled (isochoric + kappa/2 (ln J)^2) laws.
enum class MaterialLaw { StVK, NeoHookean, MooneyRivlin, Yeoh, Ogden, VerondaWestmann };

inline constexpr const char* kMaterialLawNames[] = {"stvk",  "neo_hookean",     "mooney_rivlin", "yeoh",
                                                    "ogden", "veronda_westmann"};  ///< in declaration order

inline std::string to_string(MaterialLaw law) { return enum_name(kMaterialLawNames, law); }

/// The law a name denotes (one of kMaterialLawNames), or nothing.
inline std::optional<MaterialLaw> material_law_from_string(const std::string& name) {
  return enum_from_name<MaterialLaw>(kMaterialLawNames, name);
}

/// True for the laws given by Young's modulus and Poisson's ratio (stvk, neo_hookean); the others
/// are given by their own coefficients and a bulk modulus kappa.
inline bool law_takes_young_poisson(MaterialLaw law) {
  return law == MaterialLaw::StVK || law == MaterialLaw::NeoHookean;
}

/// The parameters of a law in plain form (SI units). Only those of the law in use are meaningful:
///   stvk, neo_hookean   young (E, Pa), poisson (nu)
///   mooney_rivlin       c10, c01, kappa          W = c10 (I1b-3) + c01 (I2b-3) + kappa/2 (ln J)^2
///   yeoh                c10, c20, c30, kappa     W = sum_i c_i0 (I1b-3)^i + kappa/2 (ln J)^2
///   ogden               mu[p], alpha[p], kappa   W = sum_p mu_p/alpha_p (sum_i lb_i^alpha_p - 3) + ...
///   veronda_westmann    c1, c2 (dimensionless), kappa
///                       W = c1 (exp(c2 (I1b-3)) - 1) - c1 c2/2 (I2b-3) + kappa/2 (ln J)^2
struct LawParameters {
  double young = 0.0, poisson = 0.0;
  double c10 = 0.0, c01 = 0.0, c20 = 0.0, c30 = 0.0;
  double c1 = 0.0, c2 = 0.0;
  std::vector<double> mu, alpha;
  double kappa = 0.0;  ///< bulk modulus of the decoupled laws, Pa
};

/// The small-strain (linearised) moduli of a law: every law here linearises to isotropic linear
/// elasticity with shear modulus G and bulk modulus K:
///   stvk, neo_hookean: G = E / (2 (1 + nu)), K = E / (3 (1 - 2 nu));
///   mooney_rivlin G = 2 (c10 + c01); yeoh G = 2 c10; ogden G = 1/2 sum_p mu_p alpha_p;
///   veronda_westmann G = c1 c2; K = kappa for the decoupled laws.
struct SmallStrainModuli {
  double shear = 0.0, bulk = 0.0;
  double young() const { return 9.0 * bulk * shear / (3.0 * bulk + shear); }
  double poisson() const { return (3.0 * bulk - 2.0 * shear) / (2.0 * (3.0 * bulk + shear)); }
  double lambda() const { return bulk - 2.0 * shear / 3.0; }
};
SmallStrainModuli small_strain_moduli(MaterialLaw law, const LawParameters& p);

/// The bulk modulus that gives a decoupled law of small-strain shear modulus G the Poisson's ratio
/// nu: K = 2 G (1 + nu) / (3 (1 - 2 nu)) (for -1 < nu < 0.5).
inline double bulk_from_poisson(double shear, double nu) {
  return 2.0 * shear * (1.0 + nu) / (3.0 * (1.0 - 2.0 * nu));
}

/// Why the parameters are impossible for the law (empty when they are valid): E > 0 and
/// -1 < nu < 0.5; mooney_rivlin c10 + c01 > 0; yeoh c10 > 0; ogden mu and alpha of equal, non-zero
/// length, every alpha_p != 0 and the stability condition sum_p mu_p alpha_p > 0; veronda_westmann
/// c1 > 0, c2 > 0; kappa > 0 for the decoupled laws; every value finite. The first element names the
/// parameter at fault (e.g. "mu"), the second the reason. Case files and the models share this test.
struct LawParameterProblem {
  std::string key, reason;
  bool empty() const { return key.empty(); }
};
LawParameterProblem law_parameter_problem(MaterialLaw law, const LawParameters& p);

}  // namespace tmlab
