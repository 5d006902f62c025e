#include "core/constitutive/law_catalogue.hpp"

#include "core/base/format.hpp"

#include <cassert>
#include <cmath>
#include <iterator>
#include <limits>

namespace tmlab {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr LawBound kOpenLow{-kInf, false}, kOpenHigh{kInf, false}, kAboveZero{0.0, false};

constexpr const char* name_of(MaterialLaw law) { return kMaterialLawNames[static_cast<int>(law)]; }

// Fit starts (calibration/fit/model_spec.cpp, law_parameters).
constexpr LawFit decade(bool of_young, double scale) {
  return {FitStart::Decade, of_young, scale, 0.0, 0.0, 0.0, 0.0, kInf};
}
constexpr LawFit spread(double scale, double width) {
  return {FitStart::Spread, false, scale, width, 0.0, 0.0, -kInf, kInf};
}
constexpr LawFit absolute(double value, double lo, double hi, double box_lo, double box_hi) {
  return {FitStart::Absolute, false, value, 0.0, lo, hi, box_lo, box_hi};
}

// Parameters, in each law's order.
constexpr LawParameterInfo scalar(const char* name, const char* unit, LawBound lo, LawBound hi,
                                  double LawParameters::*field, const char* description, LawFit fit,
                                  bool has_default = false) {
  return {name, name, unit, lo, hi, false, has_default, 0.0, false, field, nullptr, description, fit};
}

constexpr LawParameterInfo kYoung{"young",
                                  "E",
                                  "Pa",
                                  kAboveZero,
                                  kOpenHigh,
                                  false,
                                  false,
                                  0.0,
                                  false,
                                  &LawParameters::young,
                                  nullptr,
                                  "Young's modulus (long-term with Prony terms)",
                                  decade(true, 1.0)};
constexpr LawParameterInfo kPoisson{"poisson",
                                    "nu",
                                    "1",
                                    LawBound{-1.0, false},
                                    LawBound{0.5, false},
                                    false,
                                    false,
                                    0.0,
                                    false,
                                    &LawParameters::poisson,
                                    nullptr,
                                    "Poisson's ratio",
                                    absolute(0.45, 0.05, 0.495, 0.0, 0.4999)};
constexpr LawParameterInfo kKappa = scalar("kappa", "Pa", kAboveZero, kOpenHigh, &LawParameters::kappa,
                                           "bulk modulus of the decoupled laws", decade(false, 1.0));

constexpr LawParameterInfo kYoungPoissonParameters[] = {kYoung, kPoisson};
constexpr LawParameterInfo kMooneyRivlinParameters[] = {
    scalar("c10", "Pa", kOpenLow, kOpenHigh, &LawParameters::c10, "coefficient of (I1b - 3)",
           spread(0.35, 0.5)),
    scalar("c01", "Pa", kOpenLow, kOpenHigh, &LawParameters::c01, "coefficient of (I2b - 3)",
           spread(0.15, 0.5))};
constexpr LawParameterInfo kYeohParameters[] = {
    scalar("c10", "Pa", kAboveZero, kOpenHigh, &LawParameters::c10, "coefficient of (I1b - 3)",
           decade(false, 0.5)),
    scalar("c20", "Pa", kOpenLow, kOpenHigh, &LawParameters::c20, "coefficient of (I1b - 3)^2",
           spread(0.0, 0.1), true),
    scalar("c30", "Pa", kOpenLow, kOpenHigh, &LawParameters::c30, "coefficient of (I1b - 3)^3",
           spread(0.0, 0.02), true)};
constexpr LawParameterInfo kOgdenParameters[] = {
    {"mu", "mu", "Pa", kOpenLow, kOpenHigh, false, false, 0.0, true, nullptr, &LawParameters::mu,
     "moduli mu_p, one per term", LawFit{FitStart::TermModulus, false, 0.0, 0.0, 0.0, 0.0, -kInf, kInf}},
    {"alpha", "alpha", "1", kOpenLow, kOpenHigh, true, false, 0.0, true, nullptr, &LawParameters::alpha,
     "exponents alpha_p (non-zero), one per term",
     LawFit{FitStart::TermExponent, false, 0.0, 1.5, 0.0, 0.0, -40.0, 40.0}}};
constexpr LawParameterInfo kVerondaWestmannParameters[] = {
    scalar("c1", "Pa", kAboveZero, kOpenHigh, &LawParameters::c1, "modulus c1", decade(false, 1.0)),
    scalar("c2", "1", kAboveZero, kOpenHigh, &LawParameters::c2, "exponential stiffening c2 (dimensionless)",
           absolute(1.0, 0.1, 10.0, 0.0, kInf))};

// Small-strain shear moduli (the arithmetic small_strain_moduli has used: keep it bit for bit; the
// fit keeps its own Ogden loop, see calibration/fit/model_spec.cpp shear_modulus_at).
double shear_young_poisson(const LawParameters& p) { return p.young / (2.0 * (1.0 + p.poisson)); }
double shear_mooney_rivlin(const LawParameters& p) { return 2.0 * (p.c10 + p.c01); }
double shear_yeoh(const LawParameters& p) { return 2.0 * p.c10; }
double shear_ogden(const LawParameters& p) {
  double shear = 0.0;
  for (std::size_t k = 0; k < p.mu.size() && k < p.alpha.size(); ++k) shear += 0.5 * p.mu[k] * p.alpha[k];
  return shear;
}
double shear_veronda_westmann(const LawParameters& p) { return p.c1 * p.c2; }

// Conditions on several parameters (each one's bounds are checked before).
LawParameterProblem mooney_rivlin_problem(const LawParameters& p) {
  if (!(p.c10 + p.c01 > 0.0))
    return {"c01", "c10 + c01 must be > 0 (the small-strain shear modulus is 2 (c10 + c01); got c10 = " +
                       significant(p.c10, 6) + ", c01 = " + significant(p.c01, 6) + ")"};
  return {};
}
LawParameterProblem ogden_problem(const LawParameters& p) {
  double sum = 0.0;
  for (std::size_t k = 0; k < p.mu.size(); ++k) sum += p.mu[k] * p.alpha[k];
  if (!(sum > 0.0))
    return {"mu",
            "violates the Ogden stability condition sum_p mu_p alpha_p > 0 (positive shear modulus "
            "1/2 sum_p mu_p alpha_p; got sum = " +
                significant(sum, 6) + ")"};
  return {};
}

constexpr const char* kFastElements =
    "fast model: P1 tetrahedra; deal.II reference: P1/P2 tetrahedra, Q1/Q2 hexahedra";

constexpr LawDescriptor kLaws[] = {
    {MaterialLaw::StVK, name_of(MaterialLaw::StVK), "St Venant-Kirchhoff", "W = lambda/2 (tr E)^2 + mu E:E",
     kYoungPoissonParameters, BulkResponse::YoungPoisson, shear_young_poisson, nullptr, true, true, true,
     kFastElements},
    {MaterialLaw::NeoHookean, name_of(MaterialLaw::NeoHookean), "compressible neo-Hookean",
     "W = mu/2 (I1 - 3) + volumetric", kYoungPoissonParameters, BulkResponse::YoungPoisson,
     shear_young_poisson, nullptr, false, true, true, kFastElements},
    {MaterialLaw::MooneyRivlin, name_of(MaterialLaw::MooneyRivlin), "Mooney-Rivlin",
     "W = c10 (I1 - 3) + c01 (I2 - 3) + volumetric", kMooneyRivlinParameters, BulkResponse::KappaOrPoisson,
     shear_mooney_rivlin, mooney_rivlin_problem, false, true, true, kFastElements},
    {MaterialLaw::Yeoh, name_of(MaterialLaw::Yeoh), "Yeoh",
     "W = c10 (I1-3) + c20 (I1-3)^2 + c30 (I1-3)^3 + volumetric", kYeohParameters,
     BulkResponse::KappaOrPoisson, shear_yeoh, nullptr, false, true, true, kFastElements},
    {MaterialLaw::Ogden, name_of(MaterialLaw::Ogden), "Ogden",
     "W = sum mu_p/alpha_p (l1^a + l2^a + l3^a - 3) + volumetric", kOgdenParameters,
     BulkResponse::KappaOrPoisson, shear_ogden, ogden_problem, false, true, true, kFastElements},
    {MaterialLaw::VerondaWestmann, name_of(MaterialLaw::VerondaWestmann), "Veronda-Westmann",
     "W = c1 (exp(c2 (I1 - 3)) - 1) - c1 c2 / 2 (I2 - 3) + volumetric", kVerondaWestmannParameters,
     BulkResponse::KappaOrPoisson, shear_veronda_westmann, nullptr, false, true, true, kFastElements},
};

constexpr bool rows_in_enum_order() {
  for (std::size_t k = 0; k < std::size(kLaws); ++k)
    if (static_cast<std::size_t>(kLaws[k].law) != k) return false;
  return std::size(kLaws) == std::size(kMaterialLawNames);
}
static_assert(rows_in_enum_order(), "one row per MaterialLaw, in declaration order");

bool below(const LawBound& b, double x) { return b.closed ? !(x >= b.value) : !(x > b.value); }
bool above(const LawBound& b, double x) { return b.closed ? !(x <= b.value) : !(x < b.value); }

}  // namespace

bool LawDescriptor::has_terms() const {
  for (const LawParameterInfo& info : parameters)
    if (info.list) return true;
  return false;
}

ConstRange<LawDescriptor> law_catalogue() { return kLaws; }

const LawDescriptor& law_descriptor(MaterialLaw law) {
  const auto k = static_cast<std::size_t>(law);
  assert(k < std::size(kLaws));
  return kLaws[k];
}

std::vector<std::string> law_name_list() {
  std::vector<std::string> names;
  for (const LawDescriptor& d : kLaws) names.emplace_back(d.name);
  return names;
}

const LawParameterInfo& bulk_modulus_parameter() { return kKappa; }
const LawParameterInfo& poisson_parameter() { return kPoisson; }

std::vector<std::string> law_case_keys(MaterialLaw law) {
  const LawDescriptor& d = law_descriptor(law);
  std::vector<std::string> keys;
  for (const LawParameterInfo& info : d.parameters) keys.emplace_back(info.case_key);
  if (d.bulk == BulkResponse::KappaOrPoisson) {
    keys.emplace_back(kKappa.case_key);
    keys.emplace_back(kPoisson.case_key);
  }
  return keys;
}

std::string parameter_refusal(const LawParameterInfo& info, double value, std::size_t term) {
  const std::string lead = term > 0 ? "term " + std::to_string(term) + " must " : std::string("must ");
  const std::string got = " (got " + significant(value, 6) + ")";
  const bool has_low = std::isfinite(info.lower.value), has_high = std::isfinite(info.upper.value);
  const bool out = !std::isfinite(value) || (has_low && below(info.lower, value)) ||
                   (has_high && above(info.upper, value)) || (info.nonzero && value == 0.0);
  if (!out) return "";
  const std::string lo = significant(info.lower.value, 6), hi = significant(info.upper.value, 6);
  const std::string lo_op = info.lower.closed ? " <= " : " < ", hi_op = info.upper.closed ? " <= " : " < ";
  if (has_low && has_high) return lead + "satisfy " + lo + lo_op + info.case_key + hi_op + hi + got;
  if (has_low) return lead + "be " + (info.lower.closed ? ">= " : "> ") + lo + got;
  if (has_high) return lead + "be " + (info.upper.closed ? "<= " : "< ") + hi + got;
  if (info.nonzero) return lead + "be finite and non-zero" + got;
  return lead + "be finite";
}

}  // namespace tmlab
