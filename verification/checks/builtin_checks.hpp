// The check functions this build provides, registered explicitly (no static initialisers).
#pragma once

#include "verification/harness/registry.hpp"

namespace tmlab::verify {

/// All check functions of this build (the deal.II ones only when the reference was built).
void register_builtin_checks(CheckRegistry& registry);

// One registration function per family (verification/checks/<family>_checks.cpp).
void register_kernel_checks(CheckRegistry& registry);
void register_analytic_homogeneous_checks(CheckRegistry& registry);
void register_analytic_prony_checks(CheckRegistry& registry);
void register_analytic_hertz_checks(CheckRegistry& registry);
void register_analytic_mms_checks(CheckRegistry& registry);
void register_model_checks(CheckRegistry& registry);
void register_sundials_checks(CheckRegistry& registry);
void register_contact_checks(CheckRegistry& registry);
void register_law_checks(CheckRegistry& registry);        ///< laws beyond St VK (law_checks.cpp)
void register_reference_checks(CheckRegistry& registry);  ///< no-op without deal.II
void register_fit_checks(CheckRegistry& registry);        ///< identification (calibration/fit)
void register_element_checks(CheckRegistry& registry);    ///< the element kinds (mesh.element)

}  // namespace tmlab::verify
