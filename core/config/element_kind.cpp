// The fast model's element kinds: see element_kind.hpp.
#include "core/config/element_kind.hpp"

#include "core/base/enum_names.hpp"
#include "core/base/error.hpp"

namespace tmlab {

namespace {

const char* const kElementNames[] = {"p1", "p1_anp", "p2", "p2_mean_dilatation"};  ///< ElementKind order

}  // namespace

std::vector<std::string> element_kind_names() { return enum_names(kElementNames); }

std::string to_string(ElementKind e) { return enum_name(kElementNames, e); }

std::optional<ElementKind> element_kind_from_string(const std::string& name) {
  return enum_from_name<ElementKind>(kElementNames, name);
}

void check_element_support(const CaseConfig& cfg, CaseModel model) {
  const ElementKind e = cfg.mesh.element;
  if (e == ElementKind::P1) return;
  const std::string elem = "key 'mesh.element' '" + to_string(e) + "'";
  if (model != CaseModel::HyperelasticTL)
    throw Error(cfg.file + ": " + elem + " runs on the F-based kernel only, and key 'model' is '" +
                to_string(model) +
                "' (tensor_mass and tl_oracle are linear-tet St Venant-Kirchhoff models): set \"model\": "
                "\"hyperelastic_tl\" (or --model hyperelastic_tl), or \"element\": \"p1\"");
  if (cfg.material.viscoelastic.enabled && e == ElementKind::P2MeanDilatation)
    throw Error(cfg.file + ": " + elem +
                " has no viscoelastic form, and key 'material.viscoelastic' is given: use \"element\": "
                "\"p2\" for a viscoelastic material");
  if (is_quadratic(e)) {
    for (std::size_t i = 0; i < cfg.loads.size(); ++i)
      if (cfg.loads[i].type == LoadSpec::Type::Pressure && cfg.loads[i].follower)
        throw Error(cfg.file + ": " + elem + " has no follower pressure, and key 'loads[" +
                    std::to_string(i) +
                    "].follower' is true: use a dead pressure (\"follower\": false) or \"element\": \"p1\"");
    if (cfg.contact.enabled && cfg.solver.type == SolverSpec::Type::Explicit)
      throw Error(cfg.file + ": " + elem +
                  " has no contact in explicit dynamics (the kinematic contact is nodal), and key "
                  "'solver.type' is 'explicit' with a 'contact' section: use a static or implicit solver, "
                  "or \"element\": \"p1\"");
  }
}

}  // namespace tmlab
