// The deal.II reference's own closed choices (cells, time integration, linear solver, law), named
// once: each is an enum with one table of names (core/base/enum_names.hpp), parsed from a string
// once where a user gives it (tmlab_reference's options, verify parameters, the tmlab CLI) with an
// error that lists the accepted names, and written back by to_string() into the manifest and the
// summary. Deal.II-free and header-only: the CLI includes it without deal.II.
#pragma once

#include "core/base/enum_names.hpp"
#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/constitutive/material_law.hpp"

#include <string>

namespace tmlab::ref {

/// tet: the case's mesh (FE_SimplexP); hex: the bounding box cut into hexahedra (FE_Q).
enum class CellType { Tet, Hex };
/// fixed_step: the Prony recursion on solver.steps increments; ida: the quasi-static DAE by IDA.
enum class TimeIntegration { FixedStep, Ida };
/// direct: MUMPS through Trilinos Amesos; direct_klu: KLU (serial); cg_amg: CG + ML AMG.
enum class LinearSolver { Direct, DirectKlu, CgAmg };

inline constexpr const char* kCellTypeNames[] = {"tet", "hex"};
inline constexpr const char* kTimeIntegrationNames[] = {"fixed_step", "ida"};
inline constexpr const char* kLinearSolverNames[] = {"direct", "direct_klu", "cg_amg"};

inline std::string to_string(CellType c) { return enum_name(kCellTypeNames, c); }
inline std::string to_string(TimeIntegration t) { return enum_name(kTimeIntegrationNames, t); }
inline std::string to_string(LinearSolver s) { return enum_name(kLinearSolverNames, s); }

namespace detail {
template <class E, std::size_t N>
E parse_choice(const char* const (&names)[N], const std::string& name, const std::string& what) {
  if (const auto v = enum_from_name<E>(names, name)) return *v;
  throw Error("reference: " + what + " must be " + choice_list(enum_names(names)) + " (got '" + name + "')");
}
}  // namespace detail

/// The choice `name` denotes; otherwise tmlab::Error "reference: <what> must be 'a', 'b' or 'c'
/// (got 'x')" (`what` names the option as the caller's user wrote it, e.g. "--cells").
inline CellType parse_cell_type(const std::string& name, const std::string& what = "cells") {
  return detail::parse_choice<CellType>(kCellTypeNames, name, what);
}
inline TimeIntegration parse_time_integration(const std::string& name,
                                              const std::string& what = "time_integration") {
  return detail::parse_choice<TimeIntegration>(kTimeIntegrationNames, name, what);
}
inline LinearSolver parse_linear_solver(const std::string& name, const std::string& what = "linear_solver") {
  return detail::parse_choice<LinearSolver>(kLinearSolverNames, name, what);
}
/// The laws the --law override can build from a case's E and nu (Material::make(law, E, nu)); the
/// others are given by their own keys in the case file's material section.
inline constexpr const char* kLawOverrideNames[] = {"stvk", "neo_hookean", "yeoh"};
inline MaterialLaw parse_law(const std::string& name, const std::string& what = "law") {
  (void)detail::parse_choice<int>(kLawOverrideNames, name, what);  // refuses the non-override laws
  return *material_law_from_string(name);
}

}  // namespace tmlab::ref
