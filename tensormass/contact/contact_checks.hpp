// Checks of a contact set-up against its sample before a run (docs/contact.md, "Bad input"): each
// throws tmlab::Error naming the body's case-file key (RigidBody::origin) and what is wrong. The
// penetration at t0 is checked by the solvers themselves (initial_gap_tol).
#pragma once

#include "tensormass/contact/rigid_body.hpp"
#include "tensormass/contact/surface_grid.hpp"

#include <vector>

namespace tmlab::tm {

/// The smallest gap between `body` at time t and the surface nodes at X + u (a signed distance, m).
double min_surface_gap(const Mesh& mesh, const ContactSurface& surface, const RigidBody& body, double t,
                       const VecX& u);

/// Refuses, for each body:
///  - a body farther from the sample at t0 than max_initial_gap (0: 1e-3 * the mesh's bounding-box
///    diagonal): it would not touch at the start (a wrong position or units);
///  - a rig larger than its mesh: a punch whose radius reaches the sample's extent from the punch's
///    axis (no free surface beyond its edge), or a sphere whose Hertz contact radius sqrt(R d_max)
///    at its deepest travel d_max (sampled over [t0, t_end]) reaches that extent.
void check_contact_rig(const Mesh& mesh, const ContactSurface& surface, const std::vector<RigidBody>& bodies,
                       double max_initial_gap, double t0, double t_end, const VecX& u0);

}  // namespace tmlab::tm
