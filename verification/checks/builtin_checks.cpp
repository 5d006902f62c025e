// register_builtin_checks: see builtin_checks.hpp.
#include "verification/checks/builtin_checks.hpp"

namespace tmlab::verify {

void register_builtin_checks(CheckRegistry& registry) {
  register_kernel_checks(registry);
  register_analytic_homogeneous_checks(registry);
  register_analytic_prony_checks(registry);
  register_analytic_hertz_checks(registry);
  register_analytic_mms_checks(registry);
  register_model_checks(registry);
  register_sundials_checks(registry);
  register_contact_checks(registry);
  register_law_checks(registry);
  register_reference_checks(registry);
  register_fit_checks(registry);
  register_element_checks(registry);
}

}  // namespace tmlab::verify
