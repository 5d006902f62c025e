// Nodal augmented-Lagrangian contact of the deal.II reference (contact.hpp): the terms at the
// vertices, the Uzawa update with the fast model's stopping test, gluing of bonded vertices, and the
// per-body outputs. The line-by-line counterpart is tmlab::tm::ContactStaticSolver.
#include "reference_fem/dealii/contact.hpp"

#include "core/base/error.hpp"

#include <deal.II/base/mpi.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace tmlab::ref {

using namespace dealii;
using TrilinosVector = TrilinosWrappers::MPI::Vector;

namespace {
constexpr double kPi = 3.14159265358979323846;

/// As the fast model's RigidBody::label(): "key 'contact.bodies[0]' (sphere 'indenter')".
std::string body_label(const ContactBodySpec& b) {
  const std::string what = "(" + to_string(b.shape) + " '" + b.name + "')";
  return b.key.empty() ? "contact body " + what : "key '" + b.key + "' " + what;
}
}  // namespace

NodalContact::NodalContact(const ContactSpec& spec, const std::string& file, const Mesh& mesh,
                           std::vector<std::array<global_dof_index, 3>> node_dofs, std::vector<char> owned,
                           MPI_Comm comm)
    : spec_(spec),
      file_(file),
      mesh_(mesh),
      node_dofs_(std::move(node_dofs)),
      owned_(std::move(owned)),
      comm_(comm),
      boundary_(ContactBoundary::extract(mesh)) {
  if (spec_.bodies.empty()) throw Error(file_ + ": key 'contact.bodies': no contact body given");
  for (std::size_t k = 0; k < boundary_.nodes.size(); ++k)
    if (owned_[static_cast<std::size_t>(boundary_.nodes[k])]) mine_.push_back(k);
  gap_tol_ = spec_.gap_tol > 0.0 ? spec_.gap_tol : 1e-8 * boundary_.mean_edge;
  const std::size_t nb = boundary_.nodes.size();
  committed_.resize(spec_.bodies.size());
  for (BodyData& d : committed_) {
    d.lambda.assign(nb, 0.0);
    d.lambda_b.assign(nb, Vec3::Zero());
    d.bonded.assign(nb, 0);
    d.anchor.assign(nb, Vec3::Zero());
  }
  trial_ = committed_;
}

Vec3 NodalContact::position(const TrilinosVector& u, std::size_t k) const {
  const std::size_t n = static_cast<std::size_t>(boundary_.nodes[k]);
  const auto& d = node_dofs_[n];
  return mesh_.points[n] + Vec3(u[d[0]], u[d[1]], u[d[2]]);
}

void NodalContact::start(Solid& solid, double t0, double t_end, const std::vector<double>& U0) {
  if (spec_.stiffness > 0.0) {
    eps_ = spec_.stiffness;
  } else {
    // The fast model's scale: the mean diagonal of the reference tangent K_0 (u = 0) over the
    // boundary vertex DoFs, times stiffness_factor.
    TrilinosVector zero(solid.locally_owned_dofs(), solid.communicator()), r;
    TrilinosWrappers::SparseMatrix K0;
    solid.residual_and_tangent(zero, t0, 0.0, r, &K0);
    double sum = 0.0;
    for (std::size_t k : mine_)
      for (global_dof_index d : node_dofs_[static_cast<std::size_t>(boundary_.nodes[k])])
        sum += K0.diag_element(d);
    sum = Utilities::MPI::sum(sum, comm_);
    eps_ = spec_.stiffness_factor * sum / (3.0 * static_cast<double>(boundary_.nodes.size()));
    if (!(eps_ > 0.0) || !std::isfinite(eps_))
      throw Error(file_ +
                  ": key 'contact.stiffness': the reference tangent gives no positive stiffness scale; "
                  "give contact.stiffness");
  }
  // The initial configuration (every rank: all vertices): penetration, distance, glue.
  const double tol = spec_.initial_gap_tol > 0.0 ? spec_.initial_gap_tol : gap_tol_;
  Vec3 lo = mesh_.points.front(), hi = lo;
  for (const Vec3& x : mesh_.points) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  const double limit = spec_.max_initial_gap > 0.0 ? spec_.max_initial_gap : 1e-3 * (hi - lo).norm();
  for (std::size_t b = 0; b < spec_.bodies.size(); ++b) {
    const ContactBodySpec& body = spec_.bodies[b];
    double deepest = 0.0, nearest = std::numeric_limits<double>::infinity();
    Index worst = -1;
    for (std::size_t k = 0; k < boundary_.nodes.size(); ++k) {
      const std::size_t n = static_cast<std::size_t>(boundary_.nodes[k]);
      const Vec3 x = mesh_.points[n] + Vec3(U0[3 * n], U0[3 * n + 1], U0[3 * n + 2]);
      const GapPoint gp = body_gap(body, x, t0);
      nearest = std::min(nearest, gp.g);
      if (-gp.g > deepest) {
        deepest = -gp.g;
        worst = static_cast<Index>(n);
      }
      if (body.mode == ContactBodyMode::Bonded && gp.g <= gap_tol_) {
        committed_[b].bonded[k] = 1;
        committed_[b].anchor[k] = gp.closest - body.position(t0);
      }
    }
    if (deepest > tol) {
      std::ostringstream m;
      m << file_ << ": " << body_label(body) << " penetrates the sample at t = " << t0 << " by " << deepest
        << " m at node " << worst << " (tolerance " << tol
        << " m): place the body clear of, or touching, the surface at the start";
      throw Error(m.str());
    }
    if (nearest > limit) {
      std::ostringstream m;
      m << file_ << ": " << body_label(body) << " does not touch the sample at t = " << t0
        << ": its smallest gap is " << nearest << " m, more than max_initial_gap = " << limit << " m"
        << (spec_.max_initial_gap > 0.0 ? "" : " (1e-3 of the mesh's bounding-box diagonal)")
        << "; check its position and units, or raise contact.max_initial_gap for an approach phase";
      throw Error(m.str());
    }
    check_extent(body, nearest, t0, t_end, U0);
  }
  trial_ = committed_;
}

void NodalContact::check_extent(const ContactBodySpec& body, double g0, double t0, double t_end,
                                const std::vector<double>& U0) const {
  if (body.shape == ContactShape::Plane) return;
  // The sample's extent seen from the body's axis: the largest radial distance of a boundary vertex.
  double extent = 0.0;
  for (Index node : boundary_.nodes) {
    const std::size_t n = static_cast<std::size_t>(node);
    const Vec3 x = mesh_.points[n] + Vec3(U0[3 * n], U0[3 * n + 1], U0[3 * n + 2]);
    extent = std::max(extent, body_radial_distance(body, x, t0));
  }
  double reach = body.radius;  // punch: its face
  const char* what = "radius";
  if (body.shape == ContactShape::Sphere) {
    // Deepest travel along the axis over the run (the initial overlap is within tolerance).
    const Vec3 axis = body_axis(body);
    double depth = 0.0;
    const int samples = 2000;
    for (int i = 0; i <= samples; ++i) {
      const double t = t0 + (t_end - t0) * i / samples;
      depth = std::max(depth, (body.position(t) - body.position(t0)).dot(axis) - g0);
    }
    reach = std::sqrt(body.radius * std::max(depth, 0.0));
    what = "Hertz contact radius sqrt(R d) at its deepest travel";
  }
  if (reach >= extent) {
    std::ostringstream m;
    m << file_ << ": " << body_label(body) << " is larger than its mesh: its " << what << " is " << reach
      << " m, but the sample extends only " << extent
      << " m from the body's axis; use a larger sample or a smaller body (or travel)";
    throw Error(m.str());
  }
}

std::string NodalContact::describe() const {
  std::ostringstream m;
  m << file_ << ": key 'contact' (";
  for (std::size_t b = 0; b < spec_.bodies.size(); ++b) m << (b ? ", " : "") << body_label(spec_.bodies[b]);
  m << "): the " << (spec_.method == ContactEnforcement::Penalty ? "penalty" : "augmented-Lagrangian")
    << " contact (at most " << spec_.max_outer_iterations << " outer iterations per increment, gap_tol "
    << gap_tol_ << " m, last natural residual " << natural_ << " m) did not converge";
  return m.str();
}

void NodalContact::add_terms(const TrilinosVector& u, double t, TrilinosVector& r,
                             const AffineConstraints<double>* constraints, TrilinosWrappers::SparseMatrix* K,
                             TrilinosVector* rhs) const {
  const bool penalty = spec_.method == ContactEnforcement::Penalty;
  FullMatrix<double> M(3, 3);
  Vector<double> f(3), minus_f(3);
  std::vector<global_dof_index> dofs(3);
  for (std::size_t b = 0; b < spec_.bodies.size(); ++b) {
    const ContactBodySpec& body = spec_.bodies[b];
    const BodyData& d = trial_[b];
    const Vec3 c = body.position(t);
    for (std::size_t k : mine_) {
      const auto& nd = node_dofs_[static_cast<std::size_t>(boundary_.nodes[k])];
      const Vec3 x = position(u, k);
      Eigen::Matrix3d H;
      Vec3 force;  // dPhi/dx
      if (d.bonded[k]) {
        // Phi = lambda . c + eps/2 |c|^2, c = x - (anchor + c(t)).
        const Vec3 gap = x - (d.anchor[k] + c);
        force = d.lambda_b[k] + eps_ * gap;
        H = eps_ * Eigen::Matrix3d::Identity();
      } else {
        // Phi = (<lambda - eps g>_+^2 - lambda^2) / (2 eps): dPhi/dx = -p n, d2Phi = eps n n^T - p H_g.
        const GapPoint gp = body_gap(body, x, t);
        const double p = (penalty ? 0.0 : d.lambda[k]) - eps_ * gp.g;
        if (p <= 0.0) continue;
        force = -p * gp.normal;
        H = eps_ * gp.normal * gp.normal.transpose() - p * gp.hessian;
      }
      for (unsigned a = 0; a < 3; ++a) {
        dofs[a] = nd[a];
        f(a) = force[a];
        minus_f(a) = -force[a];
        for (unsigned e = 0; e < 3; ++e) M(a, e) = H(a, e);
      }
      r.add(dofs, f);
      if (K) constraints->distribute_local_to_global(M, minus_f, dofs, *K, *rhs, true);
    }
  }
}

double NodalContact::energy(const TrilinosVector& u, double t) const {
  const bool penalty = spec_.method == ContactEnforcement::Penalty;
  double phi = 0.0;
  for (std::size_t b = 0; b < spec_.bodies.size(); ++b) {
    const ContactBodySpec& body = spec_.bodies[b];
    const BodyData& d = trial_[b];
    const Vec3 c = body.position(t);
    for (std::size_t k : mine_) {
      const Vec3 x = position(u, k);
      if (d.bonded[k]) {
        const Vec3 gap = x - (d.anchor[k] + c);
        phi += d.lambda_b[k].dot(gap) + 0.5 * eps_ * gap.squaredNorm();
        continue;
      }
      const double lam = penalty ? 0.0 : d.lambda[k];
      const double pp = std::max(lam - eps_ * body_gap(body, x, t).g, 0.0);
      phi += (pp * pp - lam * lam) / (2.0 * eps_);
    }
  }
  return Utilities::MPI::sum(phi, comm_);
}

bool NodalContact::update(const TrilinosVector& u, double t) {
  const bool penalty = spec_.method == ContactEnforcement::Penalty;
  double natural = 0.0;
  int changes = 0;
  for (std::size_t b = 0; b < spec_.bodies.size(); ++b) {
    const ContactBodySpec& body = spec_.bodies[b];
    BodyData& d = trial_[b];
    const Vec3 c = body.position(t);
    for (std::size_t k : mine_) {
      const Vec3 x = position(u, k);
      if (d.bonded[k]) {
        const Vec3 gap = x - (d.anchor[k] + c);
        d.lambda_b[k] += eps_ * gap;
        natural = std::max(natural, gap.lpNorm<Eigen::Infinity>());
        continue;
      }
      const double old = penalty ? 0.0 : d.lambda[k];
      const double next = std::max(0.0, old - eps_ * body_gap(body, x, t).g);
      d.lambda[k] = next;  // penalty: the force eps <-g>_+, kept for the output only
      if (penalty) continue;
      natural = std::max(natural, std::abs(next - old) / eps_);
      if ((old > 0.0) != (next > 0.0) && std::max(old, next) > eps_ * gap_tol_) ++changes;
    }
  }
  natural_ = Utilities::MPI::max(natural, comm_);
  changes = Utilities::MPI::sum(changes, comm_);
  return penalty || (natural_ <= gap_tol_ && changes == 0);
}

void NodalContact::commit(const TrilinosVector& u, double t) {
  committed_ = trial_;
  // Bonded bodies: vertices that came into contact during the increment are glued where they are,
  // with their force carried over (as the fast model).
  for (std::size_t b = 0; b < spec_.bodies.size(); ++b) {
    const ContactBodySpec& body = spec_.bodies[b];
    if (body.mode != ContactBodyMode::Bonded) continue;
    BodyData& d = committed_[b];
    for (std::size_t k : mine_) {
      if (d.bonded[k] || !(d.lambda[k] > 0.0)) continue;
      const GapPoint gp = body_gap(body, position(u, k), t);
      d.bonded[k] = 1;
      d.anchor[k] = gp.closest - body.position(t);
      d.lambda_b[k] = -d.lambda[k] * gp.normal;
      d.lambda[k] = 0.0;
    }
  }
  trial_ = committed_;
}

std::vector<ContactBodyOutput> NodalContact::outputs(const TrilinosVector& u, double t) const {
  std::vector<ContactBodyOutput> out;
  for (std::size_t b = 0; b < spec_.bodies.size(); ++b) {
    const ContactBodySpec& body = spec_.bodies[b];
    const BodyData& d = trial_[b];
    ContactBodyOutput o;
    o.name = body.name;
    o.position = body.position(t);
    double min_lambda = std::numeric_limits<double>::infinity();
    for (std::size_t k : mine_) {
      const GapPoint gp = body_gap(body, position(u, k), t);
      Vec3 f;  // force of the body on the sample at this vertex
      if (d.bonded[k]) {
        f = -d.lambda_b[k];
      } else {
        const double lam = d.lambda[k];
        min_lambda = std::min(min_lambda, lam);
        o.complementarity = std::max(o.complementarity, lam * std::abs(gp.g));
        if (!(lam > 0.0)) continue;
        f = lam * gp.normal;
      }
      const double area = boundary_.contact_area(k, gp.normal);
      if (area > 0.0) o.max_pressure = std::max(o.max_pressure, f.dot(gp.normal) / area);
      ++o.active_nodes;
      o.area += area;
      o.force -= f;
      o.moment += (gp.closest - o.position).cross(-f);
      o.max_penetration = std::max(o.max_penetration, -gp.g);
      o.radius_max = std::max(o.radius_max, body_radial_distance(body, gp.closest, t));
    }
    // Reductions over ranks (a rank without vertices contributes zeros and +inf).
    for (int c = 0; c < 3; ++c) {
      o.force[c] = Utilities::MPI::sum(o.force[c], comm_);
      o.moment[c] = Utilities::MPI::sum(o.moment[c], comm_);
    }
    o.area = Utilities::MPI::sum(o.area, comm_);
    o.active_nodes = Utilities::MPI::sum(o.active_nodes, comm_);
    o.max_pressure = Utilities::MPI::max(o.max_pressure, comm_);
    o.max_penetration = Utilities::MPI::max(o.max_penetration, comm_);
    o.complementarity = Utilities::MPI::max(o.complementarity, comm_);
    o.radius_max = Utilities::MPI::max(o.radius_max, comm_);
    min_lambda = Utilities::MPI::min(min_lambda, comm_);
    o.min_multiplier = std::isfinite(min_lambda) ? min_lambda : 0.0;
    o.radius_equivalent = body.shape != ContactShape::Plane ? std::sqrt(o.area / kPi) : 0.0;
    out.push_back(std::move(o));
  }
  return out;
}

}  // namespace tmlab::ref
