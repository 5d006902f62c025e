#include "tensormass/contact/contact_checks.hpp"

#include "core/base/error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace tmlab::tm {

namespace {

Vec3 node_position(const Mesh& mesh, const ContactSurface& surface, const VecX& u, std::size_t k) {
  const Index n = surface.nodes[k];
  Vec3 x = mesh.points[static_cast<std::size_t>(n)];
  if (u.size() > 0) x += u.segment<3>(3 * static_cast<Eigen::Index>(n));
  return x;
}

}  // namespace

double min_surface_gap(const Mesh& mesh, const ContactSurface& surface, const RigidBody& body, double t,
                       const VecX& u) {
  double g = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < surface.nodes.size(); ++k)
    g = std::min(g, body.gap(node_position(mesh, surface, u, k), t).g);
  return g;
}

void check_contact_rig(const Mesh& mesh, const ContactSurface& surface, const std::vector<RigidBody>& bodies,
                       double max_initial_gap, double t0, double t_end, const VecX& u0) {
  Vec3 lo = mesh.points.front(), hi = mesh.points.front();
  for (const Vec3& x : mesh.points) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  const double diagonal = (hi - lo).norm();
  const double gap_limit = max_initial_gap > 0.0 ? max_initial_gap : 1e-3 * diagonal;
  for (const RigidBody& b : bodies) {
    const double g0 = min_surface_gap(mesh, surface, b, t0, u0);
    if (g0 > gap_limit) {
      std::ostringstream m;
      m << b.label() << " does not touch the sample at t = " << t0 << ": its smallest gap is " << g0
        << " m, more than max_initial_gap = " << gap_limit << " m"
        << (max_initial_gap > 0.0 ? "" : " (1e-3 of the mesh's bounding-box diagonal)")
        << "; check its position and units, or raise contact.max_initial_gap for an approach phase";
      throw Error(m.str());
    }
    if (!b.axisymmetric()) continue;
    // The sample's extent seen from the body's axis: the largest radial distance of a surface node.
    double extent = 0.0;
    for (std::size_t k = 0; k < surface.nodes.size(); ++k)
      extent = std::max(extent, b.radial_distance(node_position(mesh, surface, u0, k), t0));
    double reach = b.radius;  // punch: its face
    const char* what = "radius";
    if (b.shape == RigidShape::Sphere) {
      // Deepest travel along the axis over the run (the initial overlap is within tolerance).
      double depth = 0.0;
      const int samples = 2000;
      for (int i = 0; i <= samples; ++i) {
        const double t = t0 + (t_end - t0) * i / samples;
        depth = std::max(depth, (b.position(t) - b.position(t0)).dot(b.axis) - g0);
      }
      reach = std::sqrt(b.radius * std::max(depth, 0.0));
      what = "Hertz contact radius sqrt(R d) at its deepest travel";
    }
    if (reach >= extent) {
      std::ostringstream m;
      m << b.label() << " is larger than its mesh: its " << what << " is " << reach
        << " m, but the sample extends only " << extent
        << " m from the body's axis; use a larger sample or a smaller body (or travel)";
      throw Error(m.str());
    }
  }
}

}  // namespace tmlab::tm
