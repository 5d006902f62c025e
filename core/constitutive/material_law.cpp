#include "core/constitutive/material_law.hpp"

#include "core/constitutive/law_catalogue.hpp"

#include <string>

namespace tmlab {

SmallStrainModuli small_strain_moduli(MaterialLaw law, const LawParameters& p) {
  const LawDescriptor& d = law_descriptor(law);
  SmallStrainModuli m;
  m.shear = d.shear_modulus(p);
  m.bulk = d.bulk == BulkResponse::YoungPoisson ? p.young / (3.0 * (1.0 - 2.0 * p.poisson)) : p.kappa;
  return m;
}

LawParameterProblem law_parameter_problem(MaterialLaw law, const LawParameters& p) {
  const LawDescriptor& d = law_descriptor(law);
  if (d.bulk == BulkResponse::KappaOrPoisson) {
    const LawParameterInfo& kappa = bulk_modulus_parameter();
    if (std::string why = parameter_refusal(kappa, p.kappa); !why.empty()) return {kappa.case_key, why};
  }
  // Single numbers in order; the lists (one value per term) after, term by term.
  const LawParameterInfo* first_list = nullptr;
  for (const LawParameterInfo& info : d.parameters) {
    if (info.list) {
      const std::vector<double>& v = p.*info.values;
      if (!first_list) {
        first_list = &info;
        if (v.empty())
          return {info.case_key,
                  std::string("must be a non-empty list (one ") + info.case_key + "_p per term)"};
      } else if (v.size() != (p.*first_list->values).size()) {
        return {info.case_key, std::string("must have as many terms as ") + first_list->case_key + " (" +
                                   std::to_string((p.*first_list->values).size()) + ", got " +
                                   std::to_string(v.size()) + ")"};
      }
      continue;
    }
    if (std::string why = parameter_refusal(info, p.*info.scalar); !why.empty()) return {info.case_key, why};
  }
  if (first_list) {
    for (std::size_t k = 0; k < (p.*first_list->values).size(); ++k)
      for (const LawParameterInfo& info : d.parameters)
        if (info.list)
          if (std::string why = parameter_refusal(info, (p.*info.values)[k], k + 1); !why.empty())
            return {info.case_key, why};
  }
  if (d.joint_problem) return d.joint_problem(p);
  return {};
}

}  // namespace tmlab
