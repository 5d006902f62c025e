// Augmented-Lagrangian contact of the deal.II reference (contact.hpp): the terms at the vertices or
// at the boundary faces' quadrature points, the Uzawa update with the fast model's stopping test,
// gluing of bonded points, and the per-body outputs. The vertex rule's line-by-line counterpart is
// tmlab::tm::ContactStaticSolver. Both rules run one loop over Points: a vertex is a point with one
// node, N = 1 and w = 1 (so P1 is bit for bit the former vertex-only code).
#include "reference_fem/dealii/contact.hpp"

#include "core/base/error.hpp"

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
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

RigidContact::RigidContact(const ContactSpec& spec, const std::string& file, const Mesh& mesh,
                           std::vector<std::array<global_dof_index, 3>> node_dofs, std::vector<char> owned,
                           MPI_Comm comm, ContactRule rule)
    : spec_(spec),
      file_(file),
      mesh_(mesh),
      node_dofs_(std::move(node_dofs)),
      owned_(std::move(owned)),
      comm_(comm),
      boundary_(ContactBoundary::extract(mesh)),
      rule_(rule) {
  if (spec_.bodies.empty()) throw Error(file_ + ": key 'contact.bodies': no contact body given");
  for (std::size_t k = 0; k < boundary_.nodes.size(); ++k)
    if (owned_[static_cast<std::size_t>(boundary_.nodes[k])]) mine_.push_back(k);
  gap_tol_ = spec_.gap_tol > 0.0 ? spec_.gap_tol : 1e-8 * boundary_.mean_edge;
  if (rule_ == ContactRule::Vertices)
    for (std::size_t k : mine_) {
      const std::size_t n = static_cast<std::size_t>(boundary_.nodes[k]);
      Site p;
      p.dofs.assign(node_dofs_[n].begin(), node_dofs_[n].end());
      p.N = {1.0};
      p.X = mesh_.points[n];
      p.vertex = k;
      points_.push_back(std::move(p));
    }
  allocate();
}

void RigidContact::allocate() {
  const std::size_t np = points_.size();
  const std::size_t nc = rule_ == ContactRule::Vertices ? np : group_area_.size();
  committed_.assign(spec_.bodies.size(), BodyData{});
  for (BodyData& d : committed_) {
    d.lambda.assign(nc, 0.0);
    d.lambda_b.assign(np, Vec3::Zero());
    d.bonded.assign(nc, 0);
    d.anchor.assign(np, Vec3::Zero());
  }
  trial_ = committed_;
}

void RigidContact::build_face_points(const Solid& solid) {
  // Witherden-Vincent on the reference triangle: 6 points, exact to degree 4 (the rule's face load
  // N_a w_q integrates the P2 shape functions, degree 2, exactly; the tangent's N_a N_b, degree 4).
  const QWitherdenVincentSimplex<2> quad(2);
  const FiniteElement<3>& fe = solid.fe();
  FEFaceValues<3> fv(solid.mapping(), fe, quad,
                     update_values | update_quadrature_points | update_JxW_values | update_normal_vectors);
  std::vector<global_dof_index> cell_dofs(fe.n_dofs_per_cell());
  points_.clear();
  group_ = {0};
  group_area_.clear();
  for (const auto& cell : solid.dof_handler().active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    for (const unsigned f : cell->face_indices()) {
      if (!cell->face(f)->at_boundary()) continue;
      fv.reinit(cell, f);
      cell->get_dof_indices(cell_dofs);
      // The face's nodes: the base-element index of each x-component DoF with support on the face,
      // and the three component DoFs of that node.
      std::vector<unsigned> shape;  // cell shape function of component 0 per face node
      std::vector<global_dof_index> dofs;
      for (unsigned i = 0; i < fe.n_dofs_per_cell(); ++i) {
        const auto ci = fe.system_to_component_index(i);
        if (ci.first != 0 || !fe.has_support_on_face(i, f)) continue;
        shape.push_back(i);
        for (unsigned c = 0; c < 3; ++c)
          dofs.push_back(cell_dofs[fe.component_to_system_index(c, ci.second)]);
      }
      for (unsigned q = 0; q < fv.n_quadrature_points; ++q) {
        Site p;
        p.dofs = dofs;
        for (unsigned i : shape) p.N.push_back(fv.shape_value(i, q));
        const dealii::Point<3> X = fv.quadrature_point(q);
        const Tensor<1, 3> n = fv.normal_vector(q);
        p.X = Vec3(X[0], X[1], X[2]);
        p.normal = Vec3(n[0], n[1], n[2]);
        p.w = fv.JxW(q);
        points_.push_back(std::move(p));
      }
      // The face is one constraint: its points group_.back() .. points_.size().
      double area = 0.0;
      for (std::size_t i = group_.back(); i < points_.size(); ++i) area += points_[i].w;
      group_.push_back(points_.size());
      group_area_.push_back(area);
    }
  }
}

double RigidContact::vertex_stiffness(Solid& solid, double t0) const {
  if (spec_.stiffness > 0.0) return spec_.stiffness;
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
  const double eps = spec_.stiffness_factor * sum / (3.0 * static_cast<double>(boundary_.nodes.size()));
  if (!(eps > 0.0) || !std::isfinite(eps))
    throw Error(file_ +
                ": key 'contact.stiffness': the reference tangent gives no positive stiffness scale; "
                "give contact.stiffness");
  return eps;
}

double RigidContact::face_stiffness(Solid& solid, double t0) const {
  // The face rule's penalty stiffens face node a by eps_a sum_f |G_a|^2 / A_f, G_a = sum_q w_q N_a
  // (at rest): eps_a = nodal * N_b / S, S = sum_f sum_a G_a^2 / A_f, N_b the boundary-face nodes, so
  // that this stiffness averaged over those nodes is the nodal scale, stiffness_factor x the mean
  // diagonal of K_0 over their DoFs (contact.stiffness: that nodal eps given in N/m). The fast
  // model's ContactStaticSolver uses the same definition.
  std::set<global_dof_index> dofs;  // this rank's owned boundary-face DoFs
  double S = 0.0;
  for (std::size_t c = 0; c + 1 < group_.size(); ++c) {
    const std::size_t nn = points_[group_[c]].N.size();
    for (std::size_t a = 0; a < nn; ++a) {
      double G = 0.0;
      for (std::size_t i = group_[c]; i < group_[c + 1]; ++i) G += points_[i].w * points_[i].N[a];
      S += G * G / group_area_[c];
    }
    for (global_dof_index d : points_[group_[c]].dofs)
      if (solid.locally_owned_dofs().is_element(d)) dofs.insert(d);
  }
  double stiffness = 0.0;
  if (spec_.stiffness <= 0.0) {
    TrilinosVector zero(solid.locally_owned_dofs(), solid.communicator()), r;
    TrilinosWrappers::SparseMatrix K0;
    solid.residual_and_tangent(zero, t0, 0.0, r, &K0);
    for (global_dof_index d : dofs) stiffness += K0.diag_element(d);
    stiffness = Utilities::MPI::sum(stiffness, comm_);
  }
  S = Utilities::MPI::sum(S, comm_);
  const double n_dofs = Utilities::MPI::sum(static_cast<double>(dofs.size()), comm_);
  const double nodal = spec_.stiffness > 0.0 ? spec_.stiffness : spec_.stiffness_factor * stiffness / n_dofs;
  const double eps = nodal * (n_dofs / 3.0) / S;
  if (!(eps > 0.0) || !std::isfinite(eps))
    throw Error(file_ +
                ": key 'contact.stiffness': the reference tangent gives no positive stiffness scale; "
                "give contact.stiffness");
  return eps;
}

Vec3 RigidContact::position(const TrilinosVector& u, const Site& p) const {
  Vec3 x = p.X;
  for (std::size_t a = 0; a < p.N.size(); ++a) {
    const global_dof_index* d = &p.dofs[3 * a];
    x += p.N[a] * Vec3(u[d[0]], u[d[1]], u[d[2]]);
  }
  return x;
}

void RigidContact::start(Solid& solid, double t0, double t_end, const std::vector<double>& U0) {
  if (rule_ == ContactRule::FacePoints) {
    build_face_points(solid);
    allocate();
  }
  if (rule_ == ContactRule::Vertices)
    eps_ = vertex_stiffness(solid, t0);
  else
    eps_ = face_stiffness(solid, t0);
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
    // Points touching a bonded body are glued (vertices at U0; faces, when all their points touch,
    // at the solid's solution).
    if (body.mode != ContactBodyMode::Bonded) continue;
    if (rule_ == ContactRule::FacePoints) {
      for (std::size_t c = 0; c + 1 < group_.size(); ++c) {
        bool touches = true;
        for (std::size_t i = group_[c]; i < group_[c + 1] && touches; ++i)
          touches = body_gap(body, position(solid.solution(), points_[i]), t0).g <= gap_tol_;
        if (!touches) continue;
        committed_[b].bonded[c] = 1;
        for (std::size_t i = group_[c]; i < group_[c + 1]; ++i)
          committed_[b].anchor[i] =
              body_gap(body, position(solid.solution(), points_[i]), t0).closest - body.position(t0);
      }
      continue;
    }
    for (std::size_t i = 0; i < points_.size(); ++i) {
      const Site& p = points_[i];
      Vec3 x;
      if (rule_ == ContactRule::Vertices) {
        const std::size_t n = static_cast<std::size_t>(boundary_.nodes[p.vertex]);
        x = mesh_.points[n] + Vec3(U0[3 * n], U0[3 * n + 1], U0[3 * n + 2]);
      } else {
        x = position(solid.solution(), p);
      }
      const GapPoint gp = body_gap(body, x, t0);
      if (gp.g <= gap_tol_) {
        committed_[b].bonded[i] = 1;
        committed_[b].anchor[i] = gp.closest - body.position(t0);
      }
    }
  }
  trial_ = committed_;
}

void RigidContact::check_extent(const ContactBodySpec& body, double g0, double t0, double t_end,
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

double RigidContact::face_gap(const ContactBodySpec& body, const TrilinosVector& u, double t,
                              std::size_t f) const {
  double g = 0.0;
  for (std::size_t i = group_[f]; i < group_[f + 1]; ++i)
    g += points_[i].w * body_gap(body, position(u, points_[i]), t).g;
  return g / group_area_[f];
}

void RigidContact::add_face_terms(const ContactBodySpec& body, const BodyData& d, double t, std::size_t f,
                                  const TrilinosVector& u, TrilinosVector& r,
                                  const AffineConstraints<double>* constraints,
                                  TrilinosWrappers::SparseMatrix* K, TrilinosVector* rhs) const {
  const bool penalty = spec_.method == ContactEnforcement::Penalty;
  // Every point of the face has the face's DoFs and nodes in the same order.
  const std::vector<global_dof_index>& dofs = points_[group_[f]].dofs;
  const unsigned nn = static_cast<unsigned>(points_[group_[f]].N.size());
  Vector<double> vf(3 * nn), minus_f(3 * nn);
  FullMatrix<double> M(3 * nn, 3 * nn);
  if (d.bonded[f]) {
    // Per point: w (lambda . c + eps/2 |c|^2), c = x - (anchor + c(t)).
    const Vec3 c = body.position(t);
    for (std::size_t i = group_[f]; i < group_[f + 1]; ++i) {
      const Site& pt = points_[i];
      const Vec3 force = d.lambda_b[i] + eps_ * (position(u, pt) - (d.anchor[i] + c));
      for (unsigned a = 0; a < nn; ++a)
        for (unsigned k = 0; k < 3; ++k) {
          vf(3 * a + k) += (pt.w * pt.N[a]) * force[k];
          for (unsigned e = 0; e < nn; ++e) M(3 * a + k, 3 * e + k) += pt.w * pt.N[a] * pt.N[e] * eps_;
        }
    }
  } else {
    // Phi = A (<lambda - eps g_f>_+^2 - lambda^2) / (2 eps), g_f = sum_q w_q g_q / A: node a gets
    // -p G_a, G_a = sum_q w_q N_a n_q, and the blocks (eps/A) G_a G_b^T - p sum_q w_q N_a N_b H_q.
    const double A = group_area_[f];
    std::vector<GapPoint> gp;
    double gf = 0.0;
    for (std::size_t i = group_[f]; i < group_[f + 1]; ++i) {
      gp.push_back(body_gap(body, position(u, points_[i]), t));
      gf += points_[i].w * gp.back().g;
    }
    gf /= A;
    const double p = (penalty ? 0.0 : d.lambda[f]) - eps_ * gf;
    if (p <= 0.0) return;
    std::vector<Vec3> G(nn, Vec3::Zero());
    for (std::size_t i = group_[f]; i < group_[f + 1]; ++i)
      for (unsigned a = 0; a < nn; ++a) G[a] += (points_[i].w * points_[i].N[a]) * gp[i - group_[f]].normal;
    for (unsigned a = 0; a < nn; ++a)
      for (unsigned e = 0; e < nn; ++e) {
        Eigen::Matrix3d H = (eps_ / A) * G[a] * G[e].transpose();
        for (std::size_t i = group_[f]; i < group_[f + 1]; ++i)
          H -= (p * points_[i].w * points_[i].N[a] * points_[i].N[e]) * gp[i - group_[f]].hessian;
        for (unsigned k = 0; k < 3; ++k)
          for (unsigned l = 0; l < 3; ++l) M(3 * a + k, 3 * e + l) = H(k, l);
      }
    for (unsigned a = 0; a < nn; ++a)
      for (unsigned k = 0; k < 3; ++k) vf(3 * a + k) = -p * G[a][k];
  }
  for (unsigned i = 0; i < 3 * nn; ++i) minus_f(i) = -vf(i);
  r.add(dofs, vf);
  if (K) constraints->distribute_local_to_global(M, minus_f, dofs, *K, *rhs, true);
}

std::string RigidContact::describe() const {
  std::ostringstream m;
  m << file_ << ": key 'contact' (";
  for (std::size_t b = 0; b < spec_.bodies.size(); ++b) m << (b ? ", " : "") << body_label(spec_.bodies[b]);
  m << "): the " << (spec_.method == ContactEnforcement::Penalty ? "penalty" : "augmented-Lagrangian")
    << " contact (at most " << spec_.max_outer_iterations << " outer iterations per increment, gap_tol "
    << gap_tol_ << " m, last natural residual " << natural_ << " m) did not converge";
  return m.str();
}

void RigidContact::add_terms(const TrilinosVector& u, double t, TrilinosVector& r,
                             const AffineConstraints<double>* constraints, TrilinosWrappers::SparseMatrix* K,
                             TrilinosVector* rhs) const {
  const bool penalty = spec_.method == ContactEnforcement::Penalty;
  FullMatrix<double> M;
  Vector<double> f, minus_f;
  for (std::size_t b = 0; b < spec_.bodies.size(); ++b) {
    const ContactBodySpec& body = spec_.bodies[b];
    const BodyData& d = trial_[b];
    const Vec3 c = body.position(t);
    if (rule_ == ContactRule::FacePoints) {
      for (std::size_t face = 0; face + 1 < group_.size(); ++face)
        add_face_terms(body, d, t, face, u, r, constraints, K, rhs);
      continue;
    }
    for (std::size_t i = 0; i < points_.size(); ++i) {
      const Site& pt = points_[i];
      const Vec3 x = position(u, pt);
      Eigen::Matrix3d H;
      Vec3 force;  // dPhi/dx per unit weight
      if (d.bonded[i]) {
        // Phi = lambda . c + eps/2 |c|^2, c = x - (anchor + c(t)).
        const Vec3 gap = x - (d.anchor[i] + c);
        force = d.lambda_b[i] + eps_ * gap;
        H = eps_ * Eigen::Matrix3d::Identity();
      } else {
        // Phi = (<lambda - eps g>_+^2 - lambda^2) / (2 eps): dPhi/dx = -p n, d2Phi = eps n n^T - p H_g.
        const GapPoint gp = body_gap(body, x, t);
        const double p = (penalty ? 0.0 : d.lambda[i]) - eps_ * gp.g;
        if (p <= 0.0) continue;
        force = -p * gp.normal;
        H = eps_ * gp.normal * gp.normal.transpose() - p * gp.hessian;
      }
      // x = X + sum_a N_a u_a: node a gets w N_a dPhi/dx and the blocks w N_a N_b d2Phi/dx2.
      const unsigned n = static_cast<unsigned>(pt.dofs.size());
      if (f.size() != n) {
        f.reinit(n);
        minus_f.reinit(n);
        M.reinit(n, n);
      }
      for (unsigned a = 0; a < pt.N.size(); ++a)
        for (unsigned k = 0; k < 3; ++k) {
          f(3 * a + k) = (pt.w * pt.N[a]) * force[k];
          minus_f(3 * a + k) = -f(3 * a + k);
          for (unsigned e = 0; e < pt.N.size(); ++e)
            for (unsigned l = 0; l < 3; ++l) M(3 * a + k, 3 * e + l) = (pt.w * pt.N[a] * pt.N[e]) * H(k, l);
        }
      r.add(pt.dofs, f);
      if (K) constraints->distribute_local_to_global(M, minus_f, pt.dofs, *K, *rhs, true);
    }
  }
}

double RigidContact::energy(const TrilinosVector& u, double t) const {
  const bool penalty = spec_.method == ContactEnforcement::Penalty;
  double phi = 0.0;
  for (std::size_t b = 0; b < spec_.bodies.size(); ++b) {
    const ContactBodySpec& body = spec_.bodies[b];
    const BodyData& d = trial_[b];
    const Vec3 c = body.position(t);
    if (rule_ == ContactRule::FacePoints) {
      for (std::size_t f = 0; f + 1 < group_.size(); ++f) {
        if (d.bonded[f]) {
          for (std::size_t i = group_[f]; i < group_[f + 1]; ++i) {
            const Vec3 gap = position(u, points_[i]) - (d.anchor[i] + c);
            phi += points_[i].w * (d.lambda_b[i].dot(gap) + 0.5 * eps_ * gap.squaredNorm());
          }
          continue;
        }
        const double lam = penalty ? 0.0 : d.lambda[f];
        const double pp = std::max(lam - eps_ * face_gap(body, u, t, f), 0.0);
        phi += group_area_[f] * ((pp * pp - lam * lam) / (2.0 * eps_));
      }
      continue;
    }
    for (std::size_t i = 0; i < points_.size(); ++i) {
      const Site& pt = points_[i];
      const Vec3 x = position(u, pt);
      if (d.bonded[i]) {
        const Vec3 gap = x - (d.anchor[i] + c);
        phi += pt.w * (d.lambda_b[i].dot(gap) + 0.5 * eps_ * gap.squaredNorm());
        continue;
      }
      const double lam = penalty ? 0.0 : d.lambda[i];
      const double pp = std::max(lam - eps_ * body_gap(body, x, t).g, 0.0);
      phi += pt.w * ((pp * pp - lam * lam) / (2.0 * eps_));
    }
  }
  return Utilities::MPI::sum(phi, comm_);
}

bool RigidContact::update(const TrilinosVector& u, double t) {
  const bool penalty = spec_.method == ContactEnforcement::Penalty;
  double natural = 0.0;
  int changes = 0;
  for (std::size_t b = 0; b < spec_.bodies.size(); ++b) {
    const ContactBodySpec& body = spec_.bodies[b];
    BodyData& d = trial_[b];
    const Vec3 c = body.position(t);
    if (rule_ == ContactRule::FacePoints) {
      for (std::size_t f = 0; f + 1 < group_.size(); ++f) {
        if (d.bonded[f]) {
          for (std::size_t i = group_[f]; i < group_[f + 1]; ++i) {
            const Vec3 gap = position(u, points_[i]) - (d.anchor[i] + c);
            d.lambda_b[i] += eps_ * gap;
            natural = std::max(natural, gap.lpNorm<Eigen::Infinity>());
          }
          continue;
        }
        const double old = penalty ? 0.0 : d.lambda[f];
        const double next = std::max(0.0, old - eps_ * face_gap(body, u, t, f));
        d.lambda[f] = next;
        if (penalty) continue;
        natural = std::max(natural, std::abs(next - old) / eps_);
        if ((old > 0.0) != (next > 0.0) && std::max(old, next) > eps_ * gap_tol_) ++changes;
      }
      continue;
    }
    for (std::size_t i = 0; i < points_.size(); ++i) {
      const Vec3 x = position(u, points_[i]);
      if (d.bonded[i]) {
        const Vec3 gap = x - (d.anchor[i] + c);
        d.lambda_b[i] += eps_ * gap;
        natural = std::max(natural, gap.lpNorm<Eigen::Infinity>());
        continue;
      }
      const double old = penalty ? 0.0 : d.lambda[i];
      const double next = std::max(0.0, old - eps_ * body_gap(body, x, t).g);
      d.lambda[i] = next;  // penalty: the force eps <-g>_+, kept for the output only
      if (penalty) continue;
      natural = std::max(natural, std::abs(next - old) / eps_);
      if ((old > 0.0) != (next > 0.0) && std::max(old, next) > eps_ * gap_tol_) ++changes;
    }
  }
  natural_ = Utilities::MPI::max(natural, comm_);
  changes = Utilities::MPI::sum(changes, comm_);
  return penalty || (natural_ <= gap_tol_ && changes == 0);
}

void RigidContact::commit(const TrilinosVector& u, double t) {
  committed_ = trial_;
  // Bonded bodies: points that came into contact during the increment are glued where they are,
  // with their force carried over (as the fast model).
  for (std::size_t b = 0; b < spec_.bodies.size(); ++b) {
    const ContactBodySpec& body = spec_.bodies[b];
    if (body.mode != ContactBodyMode::Bonded) continue;
    BodyData& d = committed_[b];
    if (rule_ == ContactRule::FacePoints) {
      for (std::size_t f = 0; f + 1 < group_.size(); ++f) {
        if (d.bonded[f] || !(d.lambda[f] > 0.0)) continue;
        d.bonded[f] = 1;
        for (std::size_t i = group_[f]; i < group_[f + 1]; ++i) {
          const GapPoint gp = body_gap(body, position(u, points_[i]), t);
          d.anchor[i] = gp.closest - body.position(t);
          d.lambda_b[i] = -d.lambda[f] * gp.normal;
        }
        d.lambda[f] = 0.0;
      }
      continue;
    }
    for (std::size_t i = 0; i < points_.size(); ++i) {
      if (d.bonded[i] || !(d.lambda[i] > 0.0)) continue;
      const GapPoint gp = body_gap(body, position(u, points_[i]), t);
      d.bonded[i] = 1;
      d.anchor[i] = gp.closest - body.position(t);
      d.lambda_b[i] = -d.lambda[i] * gp.normal;
      d.lambda[i] = 0.0;
    }
  }
  trial_ = committed_;
}

std::vector<ContactBodyOutput> RigidContact::outputs(const TrilinosVector& u, double t) const {
  std::vector<ContactBodyOutput> out;
  for (std::size_t b = 0; b < spec_.bodies.size(); ++b) {
    const ContactBodySpec& body = spec_.bodies[b];
    const BodyData& d = trial_[b];
    ContactBodyOutput o;
    o.name = body.name;
    o.position = body.position(t);
    double min_lambda = std::numeric_limits<double>::infinity();
    if (rule_ == ContactRule::FacePoints)
      for (std::size_t f = 0; f + 1 < group_.size(); ++f) {
        // A face: active when glued or lambda_f > 0; its points carry the face's pressure.
        if (!d.bonded[f]) {
          const double lam = group_area_[f] * d.lambda[f];
          min_lambda = std::min(min_lambda, lam);
          o.complementarity = std::max(o.complementarity, lam * std::abs(face_gap(body, u, t, f)));
          if (!(lam > 0.0)) continue;
        }
        ++o.active_nodes;
        for (std::size_t i = group_[f]; i < group_[f + 1]; ++i) {
          const Site& pt = points_[i];
          const GapPoint gp = body_gap(body, position(u, pt), t);
          const Vec3 f_q = d.bonded[f] ? Vec3(-pt.w * d.lambda_b[i]) : Vec3(pt.w * d.lambda[f] * gp.normal);
          const double area = pt.w * std::max(0.0, -pt.normal.dot(gp.normal));
          if (area > 0.0) o.max_pressure = std::max(o.max_pressure, f_q.dot(gp.normal) / area);
          o.area += area;
          o.force -= f_q;
          o.moment += (gp.closest - o.position).cross(-f_q);
          o.max_penetration = std::max(o.max_penetration, -gp.g);
          o.radius_max = std::max(o.radius_max, body_radial_distance(body, gp.closest, t));
        }
      }
    for (std::size_t i = 0; rule_ == ContactRule::Vertices && i < points_.size(); ++i) {
      const Site& pt = points_[i];
      const GapPoint gp = body_gap(body, position(u, pt), t);
      Vec3 f;  // force of the body on the sample at this point
      if (d.bonded[i]) {
        f = -pt.w * d.lambda_b[i];
      } else {
        const double lam = pt.w * d.lambda[i];
        min_lambda = std::min(min_lambda, lam);
        o.complementarity = std::max(o.complementarity, lam * std::abs(gp.g));
        if (!(lam > 0.0)) continue;
        f = lam * gp.normal;
      }
      const double area = rule_ == ContactRule::Vertices ? boundary_.contact_area(pt.vertex, gp.normal)
                                                         : pt.w * std::max(0.0, -pt.normal.dot(gp.normal));
      if (area > 0.0) o.max_pressure = std::max(o.max_pressure, f.dot(gp.normal) / area);
      ++o.active_nodes;
      o.area += area;
      o.force -= f;
      o.moment += (gp.closest - o.position).cross(-f);
      o.max_penetration = std::max(o.max_penetration, -gp.g);
      o.radius_max = std::max(o.radius_max, body_radial_distance(body, gp.closest, t));
    }
    // Reductions over ranks (a rank without points contributes zeros and +inf).
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
