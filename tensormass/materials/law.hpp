// Law: one of the hyperelastic laws of the fast model, chosen at run time, with the triad every law
// offers (energy density, PK2 stress, tangent) as functions of the Green-Lagrange strain E.
//
// A closed set as a std::variant (no virtual calls, value semantics, the kernels hold one by
// value), its alternatives in MaterialLaw order (core/constitutive/law_catalogue.hpp); a new law is one
// more alternative here and one case in Law::of (law.cpp; docs/architecture.md, "Adding a law"). St
// Venant-Kirchhoff keeps its own historical interface (tangent(dE) without E: it is constant); Law adapts it.
// Theory of each law: docs/theory/hyperelastic-laws.md.
#pragma once

#include "core/constitutive/material_law.hpp"
#include "tensormass/materials/mooney_rivlin.hpp"
#include "tensormass/materials/neo_hookean.hpp"
#include "tensormass/materials/ogden.hpp"
#include "tensormass/materials/stvk_material.hpp"
#include "tensormass/materials/tensor_algebra.hpp"
#include "tensormass/materials/veronda_westmann.hpp"
#include "tensormass/materials/yeoh.hpp"

#include <iterator>
#include <string>
#include <type_traits>
#include <variant>

namespace tmlab::tm {

class Law {
 public:
  using Variant = std::variant<StVenantKirchhoff, NeoHookean, MooneyRivlin, Yeoh, Ogden, VerondaWestmann>;

  Law(StVenantKirchhoff m) : v_(m) {}  // NOLINT: implicit, a law is a Law
  Law(NeoHookean m) : v_(m) {}         // NOLINT
  Law(MooneyRivlin m) : v_(m) {}       // NOLINT
  Law(Yeoh m) : v_(m) {}               // NOLINT
  Law(Ogden m) : v_(std::move(m)) {}   // NOLINT
  Law(VerondaWestmann m) : v_(m) {}    // NOLINT

  /// The law `kind` from its plain parameters: `p` for the decoupled laws, `lame` (the Lame constants
  /// of the small-strain limit) for the laws given by E and nu (core/constitutive/law_catalogue.hpp,
  /// BulkResponse). The one switch from MaterialLaw to the value types; throws tmlab::Error with the
  /// value type's refusal (law_factory.hpp adds the location and the keys).
  static Law of(MaterialLaw kind, const LawParameters& p, const LameConstants& lame);

  /// Which law this is (the variant's alternatives are in MaterialLaw order).
  MaterialLaw kind() const { return static_cast<MaterialLaw>(v_.index()); }
  /// Its name in the law catalogue (core/constitutive/law_catalogue.hpp), e.g. "mooney_rivlin".
  std::string name() const { return to_string(kind()); }
  const Variant& variant() const { return v_; }
  template <class T>
  const T* get_if() const {
    return std::get_if<T>(&v_);
  }
  bool is_stvk() const { return std::holds_alternative<StVenantKirchhoff>(v_); }

  /// Lame constants of the small-strain limit (every law linearises to isotropic linear elasticity).
  LameConstants small_strain() const;

  /// W(E), J/m^3. E is the symmetric Green-Lagrange strain; outside det(I + 2E) > 0 the result is not finite.
  double energy_density(const Mat3& E) const;
  /// S = dW/dE.
  Mat3 pk2_stress(const Mat3& E) const;
  /// dS = D(E) : dE, D = d^2 W / dE^2.
  Mat3 tangent(const Mat3& E, const Mat3& dE) const;
  /// D(E) as a symmetric 6x6 Voigt matrix (tensor_algebra.hpp).
  Mat6 tangent_matrix(const Mat3& E) const;
  /// W, S and D in one pass (any pointer may be null): what the kernels call.
  void evaluate(const Mat3& E, double* W, Mat3* S, Mat6* D) const;

 private:
  Variant v_;
};

static_assert(
    std::is_same_v<std::variant_alternative_t<static_cast<std::size_t>(MaterialLaw::StVK), Law::Variant>,
                   StVenantKirchhoff> &&
        std::is_same_v<
            std::variant_alternative_t<static_cast<std::size_t>(MaterialLaw::NeoHookean), Law::Variant>,
            NeoHookean> &&
        std::is_same_v<
            std::variant_alternative_t<static_cast<std::size_t>(MaterialLaw::MooneyRivlin), Law::Variant>,
            MooneyRivlin> &&
        std::is_same_v<std::variant_alternative_t<static_cast<std::size_t>(MaterialLaw::Yeoh), Law::Variant>,
                       Yeoh> &&
        std::is_same_v<std::variant_alternative_t<static_cast<std::size_t>(MaterialLaw::Ogden), Law::Variant>,
                       Ogden> &&
        std::is_same_v<
            std::variant_alternative_t<static_cast<std::size_t>(MaterialLaw::VerondaWestmann), Law::Variant>,
            VerondaWestmann> &&
        std::variant_size_v<Law::Variant> == std::size(kMaterialLawNames),
    "Law's alternatives follow MaterialLaw");

}  // namespace tmlab::tm
