#include "tensormass/contact/kinematic_contact.hpp"

#include "core/base/error.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace tmlab::tm {

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string node_label(const Mesh& mesh, Index node) {
  std::string s = "node " + std::to_string(node);
  if (static_cast<std::size_t>(node) < mesh.point_file_ids.size())
    s += " (file id " + std::to_string(mesh.point_file_ids[static_cast<std::size_t>(node)]) + ")";
  return s;
}

}  // namespace

KinematicContact::KinematicContact(const MechanicalSystem& system, const Mesh& mesh,
                                   std::vector<RigidBody> bodies, const ContactOptions& options, double t0,
                                   const VecX& u0)
    : system_(system), mesh_(mesh), bodies_(std::move(bodies)) {
  if (bodies_.empty()) throw Error("contact: no contact body given");
  for (RigidBody& b : bodies_) b.validate();
  surface_ = ContactSurface::extract(mesh_);
  grid_ = SurfaceGrid(mesh_, surface_, u0);
  gap_tol_ = options.gap_tol > 0.0 ? options.gap_tol : 1e-8 * surface_.mean_edge;
  const double tol = options.initial_gap_tol > 0.0 ? options.initial_gap_tol : gap_tol_;
  const std::size_t nb = surface_.nodes.size();
  bonded_.assign(bodies_.size(), std::vector<char>(nb, 0));
  anchor_.assign(bodies_.size(), std::vector<Vec3>(nb, Vec3::Zero()));
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    const RigidBody& body = bodies_[b];
    Vec3 lo, hi;
    body.bounding_box(t0, gap_tol_, lo, hi);
    for (Index k : grid_.query(lo, hi)) {
      const GapPoint gp = body.gap(position(u0, k), t0);
      if (-gp.g > tol) {
        std::ostringstream msg;
        msg << body.label() << " penetrates the sample at t = " << t0 << " by " << -gp.g << " m at "
            << node_label(mesh_, surface_.nodes[static_cast<std::size_t>(k)]) << " (tolerance " << tol
            << " m): place the body clear of, or touching, the surface at the start";
        throw Error(msg.str());
      }
      if (body.mode == ContactMode::Bonded && gp.g <= gap_tol_) {
        bonded_[b][static_cast<std::size_t>(k)] = 1;
        anchor_[b][static_cast<std::size_t>(k)] = gp.closest - body.position(t0);
      }
    }
    ContactBodyState st;
    st.name = body.name;
    st.position = body.position(t0);
    state_.push_back(st);
  }
}

Vec3 KinematicContact::position(const VecX& u, Index k) const {
  const Index n = surface_.nodes[static_cast<std::size_t>(k)];
  return mesh_.points[static_cast<std::size_t>(n)] + u.segment<3>(3 * static_cast<Eigen::Index>(n));
}

VecX KinematicContact::correct(double t, double dt, const VecX& u) {
  VecX du = VecX::Zero(u.size());
  grid_.refit(mesh_, surface_, u);
  const DirichletSet& bc = system_.bc();
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    const RigidBody& body = bodies_[b];
    ContactBodyState st;
    st.name = body.name;
    st.position = body.position(t);
    Vec3 lo, hi;
    body.bounding_box(t, 0.0, lo, hi);
    std::vector<Index> cand = grid_.query(lo, hi);
    // Glued nodes always follow the body, wherever the grid puts them.
    for (std::size_t k = 0; k < surface_.nodes.size(); ++k)
      if (bonded_[b][k]) cand.push_back(static_cast<Index>(k));
    std::sort(cand.begin(), cand.end());
    cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
    for (Index k : cand) {
      const std::size_t kk = static_cast<std::size_t>(k);
      const Index node = surface_.nodes[kk];
      const Eigen::Index dof = 3 * static_cast<Eigen::Index>(node);
      const Vec3 x = position(u, k) + du.segment<3>(dof);  // after earlier bodies' corrections
      const GapPoint gp = body.gap(x, t);
      Vec3 dx;
      if (bonded_[b][kk]) {
        dx = anchor_[b][kk] + st.position - x;
      } else {
        if (!(gp.g < 0.0)) continue;
        if (body.mode == ContactMode::Bonded) {
          bonded_[b][kk] = 1;  // glued from now on, at the point it reached
          anchor_[b][kk] = gp.closest - st.position;
        }
        dx = -gp.g * gp.normal;
      }
      Vec3 nf = gp.normal;
      bool constrained = false;
      for (int c = 0; c < 3; ++c)
        if (bc.is_constrained(dof + c)) {
          dx[c] = 0.0;
          nf[c] = 0.0;
          constrained = true;
        }
      if (constrained && !bonded_[b][kk]) {
        if (nf.squaredNorm() < 1e-6) {
          if (-gp.g <= gap_tol_) continue;
          std::ostringstream msg;
          msg << body.label() << " penetrates " << node_label(mesh_, node) << " at t = " << t << " by "
              << -gp.g << " m along a direction its Dirichlet conditions hold fixed: the contact cannot "
              << "be enforced there";
          throw Error(msg.str());
        }
        dx = -gp.g * nf / nf.squaredNorm();
      }
      du.segment<3>(dof) += dx;
      const double g_after = body.gap(x + dx, t).g;         // ~0: on the surface after the correction
      const Vec3 f = system_.mass()[dof] * dx / (dt * dt);  // force on the sample over the step
      const double area = surface_.contact_area(k, gp.normal);
      st.nodes.push_back(node);
      st.nodal_force.push_back(f);
      st.gap.push_back(g_after);
      st.pressure.push_back(area > 0.0 ? f.dot(gp.normal) / area : 0.0);
      st.area += area;
      st.force -= f;
      st.moment += (gp.closest - st.position).cross(-f);
      st.max_penetration = std::max(st.max_penetration, -g_after);
      st.radius_max = std::max(st.radius_max, body.radial_distance(gp.closest, t));
    }
    st.active_nodes = static_cast<int>(st.nodes.size());
    st.radius_equivalent = body.axisymmetric() ? std::sqrt(st.area / kPi) : 0.0;
    state_[b] = std::move(st);
  }
  return du;
}

// Layout per body (nb surface nodes): bonded [nb], anchor [3 nb].
std::vector<double> KinematicContact::committed_state() const {
  std::vector<double> out;
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    for (const char g : bonded_[b]) out.push_back(g ? 1.0 : 0.0);
    for (const Vec3& a : anchor_[b]) out.insert(out.end(), {a.x(), a.y(), a.z()});
  }
  return out;
}

void KinematicContact::restore_committed_state(const std::vector<double>& data,
                                               std::vector<ContactBodyState> outputs) {
  const std::size_t nb = surface_.nodes.size();
  if (data.size() != bodies_.size() * 4 * nb || outputs.size() != bodies_.size())
    throw Error("contact checkpoint does not fit this contact surface and these bodies");
  std::size_t at = 0;
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    for (char& g : bonded_[b]) g = data[at++] != 0.0 ? 1 : 0;
    for (Vec3& a : anchor_[b])
      for (int c = 0; c < 3; ++c) a[c] = data[at++];
  }
  state_ = std::move(outputs);
}

}  // namespace tmlab::tm
