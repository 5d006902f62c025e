// The finite element a case's fast model runs on (case key `mesh.element`, docs/elements.md):
//   p1                  linear 4-node tets (every model; the default, unchanged results),
//   p1_anp              linear tets with an averaged nodal pressure (the locking-free linear tet),
//   p2                  quadratic 10-node tets on the linear mesh's geometry (midside nodes added),
//   p2_mean_dilatation  the same with a mean-dilatation (per-tet constant) volumetric part.
// The elements other than p1 run on the F-based kernel (model hyperelastic_tl) only.
#pragma once

#include "core/config/case_config.hpp"

#include <optional>
#include <string>
#include <vector>

namespace tmlab {

/// The names accepted by `mesh.element`, in ElementKind order.
std::vector<std::string> element_kind_names();
std::string to_string(ElementKind e);
std::optional<ElementKind> element_kind_from_string(const std::string& name);
/// True for the 10-node elements (the model and its outputs live on the quadratic mesh's points).
inline bool is_quadratic(ElementKind e) { return e == ElementKind::P2 || e == ElementKind::P2MeanDilatation; }

/// Refuses a case whose element the chosen model or material cannot run (tmlab::Error naming the
/// case file and both keys): an element other than p1 with a model other than hyperelastic_tl,
/// p2_mean_dilatation with a viscoelastic material, follower pressure on a quadratic element, contact in
/// explicit dynamics on a quadratic element. `model` is the model that will run (a command line's
/// --model may override the case's).
void check_element_support(const CaseConfig& cfg, CaseModel model);

}  // namespace tmlab
