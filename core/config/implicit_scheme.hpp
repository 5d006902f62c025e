// The implicit time integrator, one vocabulary for the case file (solver.scheme), the tensor-mass
// solvers (tensormass/solvers/implicit_dynamics.hpp) and the summary.
#pragma once

#include "core/base/enum_names.hpp"

#include <optional>
#include <string>

namespace tmlab {

/// backward_euler: first order, dissipative; newmark: average acceleration (beta = 1/4, gamma = 1/2).
enum class ImplicitScheme { BackwardEuler, Newmark };

inline constexpr const char* kImplicitSchemeNames[] = {"backward_euler",
                                                       "newmark"};  ///< in declaration order

inline std::string to_string(ImplicitScheme s) { return enum_name(kImplicitSchemeNames, s); }

/// The scheme a name denotes ("newmark", "backward_euler"), or nothing.
inline std::optional<ImplicitScheme> implicit_scheme_from_string(const std::string& name) {
  return enum_from_name<ImplicitScheme>(kImplicitSchemeNames, name);
}

}  // namespace tmlab
