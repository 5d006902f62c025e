// The model a fit identifies, named on the command line by a SPEC (docs/identification.md):
//
//   SPEC  = LAW [":" N] ["+prony:" M] { "," NAME "=" VALUE }
//   LAW   = a law of core/constitutive/law_catalogue.hpp: stvk | neo_hookean | mooney_rivlin | yeoh |
//           ogden | veronda_westmann
//   N     = the number of terms of an N-term law (ogden only; default 1)
//   M     = the number of Prony terms of the relaxation modulus (default 0: elastic)
//   NAME=VALUE fixes that parameter at VALUE (SI units: Pa, s, dimensionless)
//
// e.g. "neo_hookean", "ogden:2,poisson=0.49", "stvk+prony:2,poisson=0.45".
//
// The parameters of each law, in physical units, in the law catalogue's order with its bounds and fit
// starts (core/constitutive/law_catalogue.hpp; a list parameter "mu" becomes mu1..muN) (every law carries its
// small-strain Poisson's ratio instead of a bulk modulus, so one fixed value, poisson=0.49, makes any law
// nearly incompressible: kappa = 2 mu0 (1 + nu) / (3 (1 - 2 nu)) with mu0 the law's small-strain shear
// modulus):
//   stvk, neo_hookean   young (Pa, > 0), poisson (0 .. 0.4999)
//   mooney_rivlin       c10, c01 (Pa, c10 + c01 > 0), poisson
//   yeoh                c10 (Pa, > 0), c20, c30 (Pa), poisson
//   ogden:N             mu1..muN (Pa), alpha1..alphaN (-40 .. 40, nonzero), poisson
//   veronda_westmann    c1 (Pa, > 0), c2 (> 0), poisson
//   +prony:M            e1..eM (Pa, > 0), tau1..tauM (s, > 0); "young" is then E_inf, the long-term modulus
#pragma once

#include "calibration/fit/parameter.hpp"
#include "core/constitutive/material_law.hpp"
#include "tensormass/materials/law.hpp"

#include <string>
#include <utility>
#include <vector>

namespace tmlab::fit {

struct ModelSpec {
  std::string text;  ///< the SPEC as given
  MaterialLaw law = MaterialLaw::StVK;
  int ogden_terms = 1;  ///< the number of terms of an N-term law (ogden)
  int prony_terms = 0;
  std::vector<std::pair<std::string, double>> fixed;  ///< NAME=VALUE, in order
};

/// Parses a SPEC; tmlab::Error naming the SPEC and the offending part. Every number follows tmlab's
/// one grammar (core/base/number.hpp: decimal, finite; N and M whole numbers 1..9); a NAME fixed
/// twice is refused with both values.
ModelSpec parse_model_spec(const std::string& text);

/// `v` in the shortest decimal text that reads back to the same double ("0.45", "1e-06"): how a
/// refusal quotes a value the user gave.
std::string shortest(double v);

/// The law's parameters (and the Prony terms), free, with starting values and start ranges scaled
/// by `modulus` (an estimate of the small-strain Young's modulus from the data, Pa) and `duration`
/// (the longest test, s, for the relaxation times). The SPEC's fixed values are not applied here.
std::vector<Parameter> law_parameters(const ModelSpec& spec, double modulus, double duration);

/// The small-strain Young's modulus and Poisson's ratio the values `x` (in the order of
/// law_parameters()) give the law; tmlab::Error if the small-strain shear modulus is not positive.
std::pair<double, double> small_strain_young_poisson(const ModelSpec& spec, const std::vector<double>& x);

/// The law at the values `x` (in the order of law_parameters()); tmlab::Error when the law refuses them.
tm::Law build_law(const ModelSpec& spec, const std::vector<double>& x);

/// The Prony terms at `x`: E_i and tau_i (empty without Prony terms).
std::pair<std::vector<double>, std::vector<double>> prony_terms(const ModelSpec& spec,
                                                                const std::vector<double>& x);

}  // namespace tmlab::fit
