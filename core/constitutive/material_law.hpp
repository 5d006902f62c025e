// The names of the hyperelastic laws, one vocabulary for the case file (core/config) and the deal.II
// reference (reference_fem/dealii/materials.hpp). The tensor-mass model has St Venant-Kirchhoff only.
#pragma once

#include "core/base/enum_names.hpp"

#include <optional>
#include <string>

namespace tmlab {

/// stvk: St Venant-Kirchhoff; neo_hookean: compressible neo-Hookean; yeoh: decoupled Yeoh.
enum class MaterialLaw { StVK, NeoHookean, Yeoh };

inline constexpr const char* kMaterialLawNames[] = {"stvk", "neo_hookean", "yeoh"};  ///< in declaration order

inline std::string to_string(MaterialLaw law) { return enum_name(kMaterialLawNames, law); }

/// The law a name denotes ("stvk", "neo_hookean", "yeoh"), or nothing.
inline std::optional<MaterialLaw> material_law_from_string(const std::string& name) {
  return enum_from_name<MaterialLaw>(kMaterialLawNames, name);
}

}  // namespace tmlab
