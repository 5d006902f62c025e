// Homogeneous closed forms of the platen tests for any hyperelastic law of the fast model: the
// check of the FE rigs (to round-off with frictionless platens) and a fast forward model for
// fitting compression and tension data (docs/theory/indentation-closed-forms.md).
//
// Unconfined compression or uniaxial tension between frictionless platens: the sample stretches
// homogeneously, F = diag(l_t, l_t, l) with l = 1 - d/H (d > 0 shortens the sample, d < 0 stretches
// it) and the lateral stretch l_t found from the free lateral faces, S_xx(l_t, l) = 0 (PK2 and
// Cauchy vanish together when F is diagonal). Confined compression: frictionless rigid walls keep
// l_t = 1. The platen force is the first Piola-Kirchhoff stress times the reference area,
//   force = -P_zz A_0 = -l S_zz A_0   (positive when the sample pushes back on a compressing platen).
//
// Where it stops being valid: bonded (glued) platens make the sample barrel, so the deformation is
// not homogeneous and the closed form is only the frictionless bound (the rig measures the
// difference); St Venant-Kirchhoff in compression has no lateral root or a falling force beyond its
// limit point (l = 1/sqrt(3) at nu = 0): the solver then throws, naming the stretch.
#pragma once

#include "tensormass/materials/law.hpp"

#include <vector>

namespace tmlab::closed_forms {

enum class PlatenTest { Unconfined, Confined };

struct PlatenState {
  double stretch = 1.0;          ///< l = 1 - d/H along the loading axis
  double lateral_stretch = 1.0;  ///< l_t
  double force = 0.0;            ///< N, positive in compression
  double nominal_stress = 0.0;   ///< force / A_0, Pa
};

/// The homogeneous state of a sample of height H (m) and reference cross-section A0 (m^2) whose
/// platen has moved by d (m, positive into the sample). Throws tmlab::Error when d >= H, when no
/// lateral stretch in (0, 10] frees the lateral faces, or for non-positive H or A0.
PlatenState platen_state(const tm::Law& law, PlatenTest test, double height, double area, double d);

/// platen_state() at every platen displacement of `d`.
std::vector<PlatenState> platen_curve(const tm::Law& law, PlatenTest test, double height, double area,
                                      const std::vector<double>& d);

}  // namespace tmlab::closed_forms
