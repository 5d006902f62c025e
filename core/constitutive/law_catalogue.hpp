// The hyperelastic laws declared once: one descriptor per law (its name, its parameters with units,
// admissible bounds, defaults and the start a fit gives them, how its bulk response is set, its
// small-strain shear modulus, the kernels and elements that run it). Every reader of a law drives
// from this table: the case file's material section (core/config), the fast model's factory
// (tensormass/materials/law_factory), the fit's SPEC (calibration/fit/model_spec), the discovery
// library's law effects (calibration/discover/effects) and the parameter checks and small-strain
// moduli of core/constitutive/material_law.hpp. docs/architecture.md ("Adding a law") lists the
// files a new law touches; docs/theory/hyperelastic-laws.md has the equations.
#pragma once

#include "core/constitutive/material_law.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace tmlab {

/// A view of a constant array (the catalogue's rows and each row's parameters).
template <class T>
struct ConstRange {
  template <std::size_t N>
  constexpr ConstRange(const T (&a)[N]) : first(a), count(N) {}  // NOLINT: implicit, an array is a range
  const T* first;
  std::size_t count;
  constexpr const T* begin() const { return first; }
  constexpr const T* end() const { return first + count; }
  constexpr std::size_t size() const { return count; }
  constexpr bool empty() const { return count == 0; }
  constexpr const T& operator[](std::size_t k) const { return first[k]; }
};

/// How a law's bulk (volumetric) response is given.
enum class BulkResponse {
  /// Young's modulus and Poisson's ratio are the law's own parameters (case keys "E", "nu"; a
  /// parameter object for make_law gives "young" and "poisson", or the Lame constants "lambda", "mu").
  YoungPoisson,
  /// A decoupled law: the bulk modulus "kappa" (Pa) or, in its place in a case file, Poisson's ratio
  /// "nu" of the small-strain limit, kappa = bulk_from_poisson(G, nu); a fit SPEC always carries
  /// "poisson".
  KappaOrPoisson,
};

/// One end of a parameter's admissible interval (+-infinity: unbounded on that side).
struct LawBound {
  double value;
  bool closed;  ///< the end itself is admissible
};

/// How a fit starts a parameter (calibration/fit/model_spec.hpp, law_parameters). E is the data's
/// estimate of the small-strain Young's modulus, G0 = E / 3 the nearly incompressible shear modulus.
enum class FitStart {
  Decade,        ///< value = scale * (E or G0), starts sampled over a factor 10 either way
  Spread,        ///< value = scale * G0, starts in value +- spread * G0
  Absolute,      ///< value = scale, starts in [start_low, start_high]
  TermExponent,  ///< term k (0-based) of N: 2 + 2k (k even) or -2k (k odd); starts in value +- spread
  TermModulus,   ///< term k of N: 2 G0 / (N exponent_k), so that the shear modulus is G0; value +- |value|
};

struct LawFit {
  FitStart start;
  bool of_young;  ///< Decade: scale multiplies E (true) or G0 (false)
  double scale, spread, start_low, start_high;
  double lower, upper;  ///< the box a fit searches (inside the admissible bounds)
};

/// One parameter of a law.
struct LawParameterInfo {
  const char* name;      ///< key of make_law's parameter object and of a fit SPEC (lists: name1 .. nameN)
  const char* case_key;  ///< key of a case file's material section
  const char* unit;      ///< "Pa" or "1"
  LawBound lower, upper;
  bool nonzero;      ///< zero is refused (Ogden's exponents)
  bool has_default;  ///< may be omitted: then default_value
  double default_value;
  bool list;                                   ///< one value per term (N-term laws), else a single number
  double LawParameters::*scalar;               ///< where a single number goes (list == false)
  std::vector<double> LawParameters::*values;  ///< where a list goes (list == true)
  const char* description;
  LawFit fit;
};

/// One law.
struct LawDescriptor {
  MaterialLaw law;
  const char* name;    ///< kMaterialLawNames entry: case files, SPECs, summaries
  const char* title;   ///< e.g. "Mooney-Rivlin"
  const char* energy;  ///< the strain energy in plain text (docs/theory/hyperelastic-laws.md)
  /// The law's own parameters in order (for YoungPoisson laws: young, poisson; the decoupled laws'
  /// kappa / nu apart, see `bulk`).
  ConstRange<LawParameterInfo> parameters;
  BulkResponse bulk;
  /// The small-strain shear modulus G of the parameters (every law linearises to isotropic linear
  /// elasticity with G and the bulk modulus of `bulk`).
  double (*shear_modulus)(const LawParameters&);
  /// The condition on several parameters beyond each one's bounds (e.g. G > 0), or nullptr.
  LawParameterProblem (*joint_problem)(const LawParameters&);
  bool tensor_mass;       ///< the paper's tensor-mass kernel and its tl_oracle (St VK only)
  bool hyperelastic_tl;   ///< the fast model's F-based P1 kernel (`model: hyperelastic_tl`)
  bool dealii_reference;  ///< the deal.II reference (reference_fem/dealii/materials.hpp)
  const char* elements;   ///< the elements that run it

  /// True for an N-term law (a parameter given as one value per term).
  bool has_terms() const;
};

/// Every law, in MaterialLaw declaration order (a view of constant data).
ConstRange<LawDescriptor> law_catalogue();

/// The descriptor of `law`.
const LawDescriptor& law_descriptor(MaterialLaw law);

/// Every law's name, in order (for messages listing the known laws).
std::vector<std::string> law_name_list();

/// The bulk modulus "kappa" and Poisson's ratio "nu"/"poisson" as parameters (bounds, units, fit start).
const LawParameterInfo& bulk_modulus_parameter();
const LawParameterInfo& poisson_parameter();

/// The keys of `law` in a case file's material section (besides "law", "density", "viscoelastic"):
/// its parameters' case keys, then "kappa" and "nu" for the decoupled laws (exactly one of them).
std::vector<std::string> law_case_keys(MaterialLaw law);

/// Why `value` is outside the admissible values of `info` (empty reason when it is admissible);
/// `term` > 0 names term `term` of a list. The reason starts with "must ..." or "term k must ...".
std::string parameter_refusal(const LawParameterInfo& info, double value, std::size_t term = 0);

}  // namespace tmlab
