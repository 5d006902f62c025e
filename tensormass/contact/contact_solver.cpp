#include "tensormass/contact/contact_solver.hpp"
#include "tensormass/solvers/load_increments.hpp"

#include "core/base/error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace tmlab::tm {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// The static residual plus the contact terms of the current outer iteration (multipliers fixed):
/// R = f_int - f_ext + dPhi/du, J = K - df_ext/du + d^2Phi/du^2, Pi = W - f_ext.u + Phi.
class ContactResidual final : public NonlinearSystem {
 public:
  ContactResidual(std::unique_ptr<NonlinearSystem> inner, const ContactStaticSolver& contact, double t,
                  const VecX& u0)
      : inner_(std::move(inner)), contact_(contact), t_(t) {
    VecX r = VecX::Zero(u0.size());
    contact_.add_contact_terms(u0, t_, &r, nullptr, nullptr);
    // The contact forces at u0 set the scale when the body's own motion is the only load.
    scale_ = std::max(inner_->force_scale(), r.norm());
  }
  void residual(const VecX& u, VecX& r) override {
    inner_->residual(u, r);
    contact_.add_contact_terms(u, t_, &r, nullptr, nullptr);
  }
  void jacobian(const VecX& u, SpMat& J) override {
    inner_->jacobian(u, J);
    contact_.add_contact_terms(u, t_, nullptr, &J, nullptr);
  }
  bool symmetric() const override { return inner_->symmetric(); }
  double force_scale() const override { return scale_; }
  bool potential(const VecX& u, double& value) override {
    if (!inner_->potential(u, value)) return false;
    double phi = 0.0;
    contact_.add_contact_terms(u, t_, nullptr, nullptr, &phi);
    value += phi;
    return true;
  }

 private:
  std::unique_ptr<NonlinearSystem> inner_;
  const ContactStaticSolver& contact_;
  double t_;
  double scale_ = 0.0;
};

std::vector<Index> sorted_union(const std::vector<Index>& a, const std::vector<Index>& b) {
  std::vector<Index> out;
  out.reserve(a.size() + b.size());
  std::set_union(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

std::string node_label(const Mesh& mesh, Index node) {
  if (node >= mesh.num_points()) return "midside node " + std::to_string(node);
  std::string s = "node " + std::to_string(node);
  if (static_cast<std::size_t>(node) < mesh.point_file_ids.size())
    s += " (file id " + std::to_string(mesh.point_file_ids[static_cast<std::size_t>(node)]) + ")";
  return s;
}

/// A contact point in messages: its node (nodal points) or its face's vertices.
std::string point_label(const Mesh& mesh, const ContactPoints& points, Index k) {
  const std::size_t kk = static_cast<std::size_t>(k);
  if (points.nodal) return node_label(mesh, points.node[kk]);
  const std::size_t s = static_cast<std::size_t>(points.start[kk]);
  return "the quadrature point " + std::to_string(k) + " of the boundary face with " +
         node_label(mesh, points.node[s]) + ", " + node_label(mesh, points.node[s + 1]) + ", " +
         node_label(mesh, points.node[s + 2]);
}

}  // namespace

ContactStaticSolver::ContactStaticSolver(const MechanicalSystem& system, const Mesh& mesh,
                                         std::vector<RigidBody> bodies, ContactOptions options,
                                         NewtonOptions newton, double t0, const VecX& u0, int max_cutbacks)
    : ContactStaticSolver(system, mesh, nullptr, std::move(bodies), options, newton, t0, u0, max_cutbacks) {}

ContactStaticSolver::ContactStaticSolver(const MechanicalSystem& system, const Mesh& mesh,
                                         const QuadraticMesh* quadratic, std::vector<RigidBody> bodies,
                                         ContactOptions options, NewtonOptions newton, double t0,
                                         const VecX& u0, int max_cutbacks)
    : system_(system),
      mesh_(mesh),
      quadratic_(quadratic),
      bodies_(std::move(bodies)),
      options_(options),
      newton_(newton),
      max_cutbacks_(max_cutbacks),
      linear_(std::make_unique<ConstrainedLinearSolver>(newton.linear_solver)) {
  if ((quadratic ? quadratic->num_points() : mesh_.num_points()) != system_.model().num_nodes())
    throw Error("contact: the mesh and the mechanical system have different node counts");
  if (quadratic && quadratic->num_vertices != mesh_.num_points())
    throw Error("contact: the quadratic mesh was not made from this mesh");
  if (u0.size() != system_.num_dofs()) throw Error("contact: initial displacement has the wrong size");
  if (bodies_.empty()) throw Error("contact: no contact body given");
  for (RigidBody& b : bodies_) b.validate();
  if (!(options_.max_outer_iterations >= 1)) throw Error("contact: max_outer_iterations must be >= 1");
  if (!(options_.stiffness_factor > 0.0) || !std::isfinite(options_.stiffness_factor))
    throw Error("contact: stiffness_factor must be > 0");
  if (!(options_.stiffness >= 0.0) || !std::isfinite(options_.stiffness))
    throw Error("contact: stiffness must be >= 0 (0: from stiffness_factor)");
  if (!(options_.gap_tol >= 0.0) || !(options_.initial_gap_tol >= 0.0) || !(options_.search_margin >= 0.0))
    throw Error("contact: gap_tol, initial_gap_tol and search_margin must be >= 0");

  surface_ = ContactSurface::extract(mesh_);
  points_ = quadratic ? ContactPoints::at_face_quadrature(*quadratic, surface_)
                      : ContactPoints::at_nodes(mesh_, surface_);
  grid_ = SurfaceGrid(points_.positions(u0), surface_.mean_edge);
  gap_tol_ = options_.gap_tol > 0.0 ? options_.gap_tol : 1e-8 * surface_.mean_edge;

  if (options_.stiffness > 0.0) {
    eps_ = options_.stiffness;
  } else {
    // A nodal stiffness scale of the sample: the mean diagonal of K_0 over the boundary DOFs (the
    // boundary vertices; quadratic faces: all face nodes).
    const VecX diag = system_.reference_tangent().diagonal();
    const std::vector<Index>& over = points_.nodal ? surface_.nodes : points_.nodes;
    double sum = 0.0;
    for (Index n : over)
      for (int c = 0; c < 3; ++c) sum += diag[3 * static_cast<Eigen::Index>(n) + c];
    eps_ = options_.stiffness_factor * sum / (3.0 * static_cast<double>(over.size()));
    if (!(eps_ > 0.0) || !std::isfinite(eps_))
      throw Error("contact: the reference tangent gives no positive stiffness scale; give contact.stiffness");
  }
  if (!points_.nodal) {
    // Faces: eps_a such that the penalty's stiffness eps_a |G_a|^2 / A_f, summed over the faces of
    // node a and averaged over the face nodes, is the nodal eps (G_a = sum_q w_q N_a at rest).
    double S = 0.0;
    for (Index c = 0; c < points_.num_constraints(); ++c) {
      const std::size_t cc = static_cast<std::size_t>(c);
      const Index q0 = points_.group[cc], n0 = points_.start[static_cast<std::size_t>(q0)];
      const Index nn = points_.start[static_cast<std::size_t>(q0) + 1] - n0;
      for (Index a = 0; a < nn; ++a) {
        double G = 0.0;
        for (Index q = q0; q < points_.group[cc + 1]; ++q)
          G += points_.weight[static_cast<std::size_t>(q)] *
               points_.shape[static_cast<std::size_t>(points_.start[static_cast<std::size_t>(q)] + a)];
        S += G * G / points_.group_area[cc];
      }
    }
    face_scale_ = static_cast<double>(points_.nodes.size()) / S;
    eps_ *= face_scale_;
  }

  const std::size_t nb = static_cast<std::size_t>(points_.size());
  const std::size_t nc = static_cast<std::size_t>(points_.num_constraints());
  committed_.resize(bodies_.size());
  for (BodyData& d : committed_) {
    d.lambda.assign(nc, 0.0);
    d.lambda_b.assign(nb, Vec3::Zero());
    d.bonded.assign(nc, 0);
    d.anchor.assign(nb, Vec3::Zero());
  }
  check_initial(t0, u0);
  trial_ = committed_;
  state_ = evaluate_state(t0, u0);
}

Vec3 ContactStaticSolver::position(const VecX& u, Index k) const { return points_.position(u, k); }

void ContactStaticSolver::check_initial(double t0, const VecX& u0) {
  const double tol = options_.initial_gap_tol > 0.0 ? options_.initial_gap_tol : gap_tol_;
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    const RigidBody& body = bodies_[b];
    Vec3 lo, hi;
    body.bounding_box(t0, gap_tol_, lo, hi);
    double worst = 0.0;
    Index worst_node = -1;
    for (Index k : grid_.query(lo, hi)) {
      const GapPoint gp = body.gap(position(u0, k), t0);
      if (-gp.g > worst) {
        worst = -gp.g;
        worst_node = k;
      }
      // Nodes touching a bonded body at t0 are glued where they touch (faces: below).
      if (points_.nodal && body.mode == ContactMode::Bonded && gp.g <= gap_tol_) {
        BodyData& d = committed_[b];
        d.bonded[static_cast<std::size_t>(k)] = 1;
        d.anchor[static_cast<std::size_t>(k)] = gp.closest - body.position(t0);
        d.candidates.push_back(k);
      }
    }
    if (worst > tol) {
      std::ostringstream msg;
      msg << body.label() << " penetrates the sample at t = " << t0 << " by " << worst << " m at "
          << point_label(mesh_, points_, worst_node) << " (tolerance " << tol
          << " m): place the body clear of, or touching, the surface at the start";
      throw Error(msg.str());
    }
    // Faces touching a bonded body at t0 (all their points) are glued where their points touch.
    if (points_.nodal || body.mode != ContactMode::Bonded) continue;
    BodyData& d = committed_[b];
    for (Index c = 0; c < points_.num_constraints(); ++c) {
      const std::size_t cc = static_cast<std::size_t>(c);
      bool touches = true;
      for (Index q = points_.group[cc]; q < points_.group[cc + 1] && touches; ++q)
        touches = body.gap(position(u0, q), t0).g <= gap_tol_;
      if (!touches) continue;
      d.bonded[cc] = 1;
      for (Index q = points_.group[cc]; q < points_.group[cc + 1]; ++q)
        d.anchor[static_cast<std::size_t>(q)] = body.gap(position(u0, q), t0).closest - body.position(t0);
      d.candidates.push_back(c);
    }
  }
}

double ContactStaticSolver::face_gap(const RigidBody& body, double t, Index c, const VecX& u) const {
  const std::size_t cc = static_cast<std::size_t>(c);
  double g = 0.0;
  for (Index q = points_.group[cc]; q < points_.group[cc + 1]; ++q)
    g += points_.weight[static_cast<std::size_t>(q)] * body.gap(position(u, q), t).g;
  return g / points_.group_area[cc];
}

void ContactStaticSolver::add_face_terms(const RigidBody& body, const BodyData& d, double t, Index c,
                                         const VecX& u, VecX* r, SpMat* J, double* energy) const {
  const bool penalty = options_.method == ContactMethod::Penalty;
  const std::size_t cc = static_cast<std::size_t>(c);
  const Index q0 = points_.group[cc], q1 = points_.group[cc + 1];
  // Every point of the face lists the face's nodes in the same order: node a of the face is the
  // entry start[q] + a of each point q.
  const Index n0 = points_.start[static_cast<std::size_t>(q0)];
  const int nn = static_cast<int>(points_.start[static_cast<std::size_t>(q0) + 1] - n0);
  const auto node_dof = [&](int a) {
    return 3 * static_cast<Eigen::Index>(points_.node[static_cast<std::size_t>(n0 + a)]);
  };
  const auto shape = [&](Index q, int a) {
    return points_.shape[static_cast<std::size_t>(points_.start[static_cast<std::size_t>(q)] + a)];
  };
  const auto add_block = [&](int a, int b, const Eigen::Matrix3d& K) {
    const Eigen::Index da = node_dof(a), db = node_dof(b);
    for (int p = 0; p < 3; ++p)
      for (int q = 0; q < 3; ++q) J->coeffRef(da + p, db + q) += K(p, q);
  };
  if (d.bonded[cc]) {
    // Per point: w (lambda . c + eps/2 |c|^2) with c = x - (anchor + c(t)).
    const Vec3 ct = body.position(t);
    for (Index q = q0; q < q1; ++q) {
      const std::size_t qq = static_cast<std::size_t>(q);
      const double w = points_.weight[qq];
      const Vec3 gap = position(u, q) - (d.anchor[qq] + ct);
      if (energy) *energy += w * (d.lambda_b[qq].dot(gap) + 0.5 * eps_ * gap.squaredNorm());
      if (r)
        for (int a = 0; a < nn; ++a)
          r->segment<3>(node_dof(a)) += (w * shape(q, a)) * (d.lambda_b[qq] + eps_ * gap);
      if (J)
        for (int a = 0; a < nn; ++a)
          for (int b = 0; b < nn; ++b)
            add_block(a, b, (w * shape(q, a) * shape(q, b) * eps_) * Eigen::Matrix3d::Identity());
    }
    return;
  }
  // Phi = A (<lambda - eps g_f>_+^2 - lambda^2) / (2 eps), g_f = sum_q w_q g_q / A.
  const double A = points_.group_area[cc];
  std::vector<GapPoint> gp;
  gp.reserve(static_cast<std::size_t>(q1 - q0));
  double gf = 0.0;
  for (Index q = q0; q < q1; ++q) {
    gp.push_back(body.gap(position(u, q), t));
    gf += points_.weight[static_cast<std::size_t>(q)] * gp.back().g;
  }
  gf /= A;
  const double lam = penalty ? 0.0 : d.lambda[cc];
  const double p = lam - eps_ * gf;
  const double pp = std::max(p, 0.0);
  if (energy) *energy += A * ((pp * pp - lam * lam) / (2.0 * eps_));
  if (p <= 0.0) return;
  // G_a = sum_q w_q N_a n_q: dg_f/dx_a = G_a / A, so dPhi/dx_a = -p G_a.
  std::vector<Vec3> G(static_cast<std::size_t>(nn), Vec3::Zero());
  for (Index q = q0; q < q1; ++q)
    for (int a = 0; a < nn; ++a)
      G[static_cast<std::size_t>(a)] += (points_.weight[static_cast<std::size_t>(q)] * shape(q, a)) *
                                        gp[static_cast<std::size_t>(q - q0)].normal;
  if (r)
    for (int a = 0; a < nn; ++a) r->segment<3>(node_dof(a)) -= p * G[static_cast<std::size_t>(a)];
  if (J)
    for (int a = 0; a < nn; ++a)
      for (int b = 0; b < nn; ++b) {
        Eigen::Matrix3d K =
            (eps_ / A) * G[static_cast<std::size_t>(a)] * G[static_cast<std::size_t>(b)].transpose();
        for (Index q = q0; q < q1; ++q)
          K -= (p * points_.weight[static_cast<std::size_t>(q)] * shape(q, a) * shape(q, b)) *
               gp[static_cast<std::size_t>(q - q0)].hessian;
        add_block(a, b, K);
      }
}

void ContactStaticSolver::add_contact_terms(const VecX& u, double t, VecX* r, SpMat* J,
                                            double* energy) const {
  const bool penalty = options_.method == ContactMethod::Penalty;
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    const RigidBody& body = bodies_[b];
    const BodyData& d = trial_[b];
    const Vec3 c = body.position(t);
    if (!points_.nodal) {
      for (Index k : d.candidates) add_face_terms(body, d, t, k, u, r, J, energy);
      continue;
    }
    for (Index k : d.candidates) {
      const std::size_t kk = static_cast<std::size_t>(k);
      const double w = points_.weight[kk];
      const Index n0 = points_.start[kk], n1 = points_.start[kk + 1];
      const Vec3 x = position(u, k);
      // The point's force f and stiffness K per unit weight reach nodes a, b as w N_a f and
      // w N_a N_b K (a nodal point: w = N = 1, exactly the node's own terms).
      const auto add_force = [&](const Vec3& f) {
        for (Index i = n0; i < n1; ++i) {
          const std::size_t ii = static_cast<std::size_t>(i);
          r->segment<3>(3 * static_cast<Eigen::Index>(points_.node[ii])) += (w * points_.shape[ii]) * f;
        }
      };
      const auto add_stiffness = [&](const Eigen::Matrix3d& K) {
        for (Index i = n0; i < n1; ++i)
          for (Index j = n0; j < n1; ++j) {
            const std::size_t ii = static_cast<std::size_t>(i), jj = static_cast<std::size_t>(j);
            const Eigen::Index da = 3 * static_cast<Eigen::Index>(points_.node[ii]);
            const Eigen::Index db = 3 * static_cast<Eigen::Index>(points_.node[jj]);
            const Eigen::Matrix3d Kab = (w * points_.shape[ii] * points_.shape[jj]) * K;
            for (int p = 0; p < 3; ++p)
              for (int q = 0; q < 3; ++q) J->coeffRef(da + p, db + q) += Kab(p, q);
          }
      };
      if (d.bonded[kk]) {
        // Phi = w (lambda . c + eps/2 |c|^2) with c = x - (anchor + c(t)).
        const Vec3 gap = x - (d.anchor[kk] + c);
        if (r && points_.nodal)  // the node's own terms, in the expression P1 always used (bit for bit:
                                 // GCC may fuse r + eps gap into one rounding)
          r->segment<3>(3 * static_cast<Eigen::Index>(points_.node[kk])) += d.lambda_b[kk] + eps_ * gap;
        else if (r)
          add_force(d.lambda_b[kk] + eps_ * gap);
        if (J) add_stiffness(eps_ * I);
        if (energy) *energy += w * (d.lambda_b[kk].dot(gap) + 0.5 * eps_ * gap.squaredNorm());
        continue;
      }
      // Phi = w (<lambda - eps g>_+^2 - lambda^2) / (2 eps); dPhi/dx = -w p n; d2Phi = w (eps n n^T - p H).
      const GapPoint gp = body.gap(x, t);
      const double lam = penalty ? 0.0 : d.lambda[kk];
      const double p = lam - eps_ * gp.g;
      const double pp = std::max(p, 0.0);
      if (energy) *energy += w * ((pp * pp - lam * lam) / (2.0 * eps_));
      if (p <= 0.0) continue;
      if (r && points_.nodal)  // as above: r - p n may be fused; (1 * (-p n)) added is not
        r->segment<3>(3 * static_cast<Eigen::Index>(points_.node[kk])) -= p * gp.normal;
      else if (r)
        add_force(-p * gp.normal);
      if (J) add_stiffness(eps_ * gp.normal * gp.normal.transpose() - p * gp.hessian);
    }
  }
}

void ContactStaticSolver::find_candidates(double t, double margin, const VecX& u) {
  grid_.refit(points_.positions(u));
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    const RigidBody& body = bodies_[b];
    BodyData& d = trial_[b];
    Vec3 lo, hi;
    body.bounding_box(t, margin, lo, hi);
    std::vector<Index> near;
    for (Index k : grid_.query(lo, hi))
      if (body.gap(position(u, k), t).g <= margin) near.push_back(k);
    if (!points_.nodal) {  // the faces of those points
      for (Index& k : near) k = points_.face[static_cast<std::size_t>(k)];
      std::sort(near.begin(), near.end());
      near.erase(std::unique(near.begin(), near.end()), near.end());
    }
    // Keep every node that carries a multiplier or is glued (their force must stay in the residual).
    std::vector<Index> keep;
    for (Index k : d.candidates) {
      const std::size_t kk = static_cast<std::size_t>(k);
      if (d.bonded[kk] || d.lambda[kk] > 0.0) keep.push_back(k);
    }
    d.candidates = sorted_union(near, keep);
  }
}

bool ContactStaticSolver::solve(double t, double t_from, VecX& u, ContactStepReport& report,
                                const InnerResidualFactory& inner) {
  trial_ = committed_;
  const bool penalty = options_.method == ContactMethod::Penalty;
  double margin = options_.search_margin;
  if (!(margin > 0.0)) {
    double travel = 0.0;
    for (const RigidBody& b : bodies_) travel = std::max(travel, (b.position(t) - b.position(t_from)).norm());
    margin = std::max(2.0 * travel, 2.0 * surface_.mean_edge);
  }
  report.outer_iterations = 0;
  report.active_changes.clear();
  report.active_counts.clear();
  find_candidates(t, margin, u);
  for (int outer = 0; outer < options_.max_outer_iterations; ++outer) {
    ContactResidual residual(inner(t, u), *this, t, u);
    const NewtonResult nr = newton_solve(residual, system_.bc(), t, u, newton_, *linear_);
    report.solver.newton_iterations += nr.iterations;
    report.solver.newton = nr;
    report.solver.at_roundoff = report.solver.at_roundoff || nr.at_roundoff;
    ++report.outer_iterations;
    ++report.outer_iterations_total;
    if (!nr.converged) return false;

    // Multiplier update, natural residual and active-set changes.
    double natural = 0.0;
    int changes = 0, active = 0;
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
      const RigidBody& body = bodies_[b];
      BodyData& d = trial_[b];
      const Vec3 c = body.position(t);
      if (!points_.nodal) {
        for (Index k : d.candidates) {
          const std::size_t kk = static_cast<std::size_t>(k);
          if (d.bonded[kk]) {
            for (Index q = points_.group[kk]; q < points_.group[kk + 1]; ++q) {
              const std::size_t qq = static_cast<std::size_t>(q);
              const Vec3 gap = position(u, q) - (d.anchor[qq] + c);
              d.lambda_b[qq] += eps_ * gap;
              natural = std::max(natural, gap.lpNorm<Eigen::Infinity>());
            }
            ++active;
            continue;
          }
          const double g = face_gap(body, t, k, u);
          const double old = penalty ? 0.0 : d.lambda[kk];
          const double next = std::max(0.0, old - eps_ * g);
          d.lambda[kk] = next;
          if (next > 0.0) ++active;
          if (penalty) continue;
          natural = std::max(natural, std::abs(next - old) / eps_);
          if ((old > 0.0) != (next > 0.0) && std::max(old, next) > eps_ * gap_tol_) ++changes;
        }
        continue;
      }
      for (Index k : d.candidates) {
        const std::size_t kk = static_cast<std::size_t>(k);
        const Vec3 x = position(u, k);
        if (d.bonded[kk]) {
          const Vec3 gap = x - (d.anchor[kk] + c);
          d.lambda_b[kk] += eps_ * gap;
          natural = std::max(natural, gap.lpNorm<Eigen::Infinity>());
          ++active;
          continue;
        }
        const double g = body.gap(x, t).g;
        const double old = penalty ? 0.0 : d.lambda[kk];
        const double next = std::max(0.0, old - eps_ * g);
        d.lambda[kk] = next;  // penalty: the force eps <-g>_+, kept for the output only
        if (next > 0.0) ++active;
        if (penalty) continue;
        natural = std::max(natural, std::abs(next - old) / eps_);
        if ((old > 0.0) != (next > 0.0) && std::max(old, next) > eps_ * gap_tol_) ++changes;
      }
    }
    // Detection check: no boundary node outside the candidate sets may penetrate.
    int missed = 0;
    grid_.refit(points_.positions(u));
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
      const RigidBody& body = bodies_[b];
      BodyData& d = trial_[b];
      Vec3 lo, hi;
      body.bounding_box(t, 0.0, lo, hi);
      std::vector<Index> add;
      for (Index k : grid_.query(lo, hi)) {
        const Index ck = points_.nodal ? k : points_.face[static_cast<std::size_t>(k)];
        if (body.gap(position(u, k), t).g < -gap_tol_ &&
            !std::binary_search(d.candidates.begin(), d.candidates.end(), ck))
          add.push_back(ck);
      }
      if (!points_.nodal) {
        std::sort(add.begin(), add.end());
        add.erase(std::unique(add.begin(), add.end()), add.end());
      }
      missed += static_cast<int>(add.size());
      d.candidates = sorted_union(d.candidates, add);
    }
    report.active_changes.push_back(changes + missed);
    report.active_counts.push_back(active);
    report.natural_residual = natural;
    if (missed == 0 && (penalty || (natural <= gap_tol_ && changes == 0))) return true;
    find_candidates(t, margin, u);
  }
  return false;
}

void ContactStaticSolver::accept(double t, const VecX& u) {
  state_ = evaluate_state(t, u);
  committed_ = trial_;
  // Bonded bodies: nodes that came into contact during the increment are glued where they are.
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    if (bodies_[b].mode != ContactMode::Bonded) continue;
    BodyData& d = committed_[b];
    for (Index k : d.candidates) {
      const std::size_t kk = static_cast<std::size_t>(k);
      if (d.bonded[kk] || !(d.lambda[kk] > 0.0)) continue;
      if (!points_.nodal) {  // a face: its points glued where they are, each with the face's pressure
        d.bonded[kk] = 1;
        for (Index q = points_.group[kk]; q < points_.group[kk + 1]; ++q) {
          const std::size_t qq = static_cast<std::size_t>(q);
          const GapPoint gq = bodies_[b].gap(position(u, q), t);
          d.anchor[qq] = gq.closest - bodies_[b].position(t);
          d.lambda_b[qq] = -d.lambda[kk] * gq.normal;
        }
        d.lambda[kk] = 0.0;
        continue;
      }
      const GapPoint gp = bodies_[b].gap(position(u, k), t);
      d.bonded[kk] = 1;
      d.anchor[kk] = gp.closest - bodies_[b].position(t);
      d.lambda_b[kk] = -d.lambda[kk] * gp.normal;  // the same force on the sample
      d.lambda[kk] = 0.0;
    }
  }
}

void ContactStaticSolver::add_mass_scale(double c_a) {
  if (options_.stiffness > 0.0) return;
  double sum = 0.0;
  for (Index n : surface_.nodes)
    for (int c = 0; c < 3; ++c) sum += system_.mass()[3 * static_cast<Eigen::Index>(n) + c];
  const double add = options_.stiffness_factor * c_a * sum / (3.0 * static_cast<double>(surface_.size()));
  eps_ += points_.nodal ? add : add * face_scale_;
}

ContactStepReport ContactStaticSolver::advance(double t_prev, double t_next, VecX& u) {
  ContactStepReport report;
  const InnerResidualFactory statics = [this](double t, const VecX& u0) {
    return std::make_unique<StaticResidual>(system_, t, u0);
  };
  LoadIncrements inc(t_prev, t_next, max_cutbacks_);
  while (inc.more()) {
    const double t_try = inc.next();
    VecX u_try = u;
    bool ok = false;
    system_.model().begin_step(t_try - inc.done());
    try {
      ok = solve(t_try, inc.done(), u_try, report, statics);
    } catch (const Error&) {
      ok = false;  // a non-finite residual in a too-large increment: cut back
      if (inc.exhausted()) throw;
    }
    if (ok) {
      system_.model().commit_step(u_try);
      u.swap(u_try);
      accept(t_try, u);
      inc.accept(t_try);
      ++report.solver.sub_increments;
      continue;
    }
    if (inc.exhausted()) {
      std::ostringstream msg;
      msg << "static solve with contact did not converge at t = " << t_try << " after " << max_cutbacks_
          << " cut-backs (outer iterations " << report.outer_iterations
          << ", natural complementarity residual " << report.natural_residual << " m against gap_tol "
          << gap_tol_ << " m, last Newton residual " << report.solver.newton.residual_final << "; bodies:";
      for (const RigidBody& b : bodies_) msg << " " << b.label();
      msg << "); a node held by a Dirichlet condition inside a body, or "
          << "a body driven too far for the model, prevents a solution (raise contact.max_outer_iterations, "
             "or solver.steps)";
      throw Error(msg.str());
    }
    inc.cut_back();
    ++report.solver.cutbacks;
  }
  report.bodies = state_;
  return report;
}

std::vector<ContactBodyState> ContactStaticSolver::evaluate_state(double t, const VecX& u) const {
  std::vector<ContactBodyState> out;
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    const RigidBody& body = bodies_[b];
    const BodyData& d = trial_[b];
    ContactBodyState st;
    st.name = body.name;
    st.position = body.position(t);
    if (!points_.nodal) {
      add_point_state(body, d, t, u, st);
      out.push_back(std::move(st));
      continue;
    }
    double min_lambda = std::numeric_limits<double>::infinity();
    for (Index k : d.candidates) {
      const std::size_t kk = static_cast<std::size_t>(k);
      const GapPoint gp = body.gap(position(u, k), t);
      Vec3 f;  // force of the body on the sample at this node
      if (d.bonded[kk]) {
        f = -d.lambda_b[kk];
      } else {
        const double lam = d.lambda[kk];
        min_lambda = std::min(min_lambda, lam);
        st.complementarity = std::max(st.complementarity, lam * std::abs(gp.g));
        if (!(lam > 0.0)) continue;
        f = lam * gp.normal;
      }
      const double area = points_.contact_area(surface_, k, gp.normal);
      st.nodes.push_back(surface_.nodes[kk]);
      st.nodal_force.push_back(f);
      st.gap.push_back(gp.g);
      st.pressure.push_back(area > 0.0 ? f.dot(gp.normal) / area : 0.0);
      st.area += area;
      st.force -= f;
      st.moment += (gp.closest - st.position).cross(-f);
      st.max_penetration = std::max(st.max_penetration, -gp.g);
      st.radius_max = std::max(st.radius_max, body.radial_distance(gp.closest, t));
    }
    st.active_nodes = static_cast<int>(st.nodes.size());
    st.min_multiplier = std::isfinite(min_lambda) ? min_lambda : 0.0;
    st.radius_equivalent = body.axisymmetric() ? std::sqrt(st.area / kPi) : 0.0;
    out.push_back(std::move(st));
  }
  return out;
}

void ContactStaticSolver::add_point_state(const RigidBody& body, const BodyData& d, double t, const VecX& u,
                                          ContactBodyState& st) const {
  // Quadratic faces: the totals from the points of the active faces (force sum_q w_q lambda_f n_q);
  // the nodal outputs on the nodes those points load: force sum_q w_q N_a f_q, the gap at the node,
  // and as pressure the area-weighted mean of lambda_f over the active faces around the node.
  double min_lambda = std::numeric_limits<double>::infinity();
  const std::size_t nn = static_cast<std::size_t>(points_.num_nodes);
  std::vector<Vec3> nodal(nn, Vec3::Zero());
  std::vector<double> wsum(nn, 0.0), psum(nn, 0.0);
  std::vector<char> loaded(nn, 0);
  int active = 0;
  for (Index c : d.candidates) {
    const std::size_t cc = static_cast<std::size_t>(c);
    if (!d.bonded[cc]) {
      const double lam = d.lambda[cc];
      min_lambda = std::min(min_lambda, lam);
      st.complementarity =
          std::max(st.complementarity, points_.group_area[cc] * lam * std::abs(face_gap(body, t, c, u)));
      if (!(lam > 0.0)) continue;
    }
    ++active;
    for (Index k = points_.group[cc]; k < points_.group[cc + 1]; ++k) {
      const std::size_t kk = static_cast<std::size_t>(k);
      const double w = points_.weight[kk];
      const GapPoint gp = body.gap(position(u, k), t);
      // force of the body on the sample per unit weight (a traction)
      const Vec3 f = d.bonded[cc] ? Vec3(-d.lambda_b[kk]) : Vec3(d.lambda[cc] * gp.normal);
      st.area += points_.contact_area(surface_, k, gp.normal);
      st.force -= w * f;
      st.moment += (gp.closest - st.position).cross(-w * f);
      st.max_penetration = std::max(st.max_penetration, -gp.g);
      st.radius_max = std::max(st.radius_max, body.radial_distance(gp.closest, t));
      for (Index i = points_.start[kk]; i < points_.start[kk + 1]; ++i) {
        const std::size_t n = static_cast<std::size_t>(points_.node[static_cast<std::size_t>(i)]);
        nodal[n] += (w * points_.shape[static_cast<std::size_t>(i)]) * f;
        wsum[n] += w;
        psum[n] += w * f.dot(gp.normal);
        loaded[n] = 1;
      }
    }
  }
  for (std::size_t n = 0; n < nn; ++n) {
    if (!loaded[n]) continue;
    const Vec3 x = quadratic_->points[n] + u.segment<3>(3 * static_cast<Eigen::Index>(n));
    st.nodes.push_back(static_cast<Index>(n));
    st.nodal_force.push_back(nodal[n]);
    st.gap.push_back(body.gap(x, t).g);
    st.pressure.push_back(wsum[n] > 0.0 ? psum[n] / wsum[n] : 0.0);
  }
  st.active_nodes = active;
  st.min_multiplier = std::isfinite(min_lambda) ? min_lambda : 0.0;
  st.radius_equivalent = body.axisymmetric() ? std::sqrt(st.area / kPi) : 0.0;
}

// Layout per body (nb contact points, nc constraints; nodal nc = nb): lambda [nc], lambda_b [3 nb],
// bonded [nc], anchor [3 nb], the number of candidates and the candidates (constraint indices;
// exact as doubles below 2^53).
std::vector<double> ContactStaticSolver::committed_state() const {
  std::vector<double> out;
  for (const BodyData& d : committed_) {
    out.insert(out.end(), d.lambda.begin(), d.lambda.end());
    for (const Vec3& l : d.lambda_b) out.insert(out.end(), {l.x(), l.y(), l.z()});
    for (const char b : d.bonded) out.push_back(b ? 1.0 : 0.0);
    for (const Vec3& a : d.anchor) out.insert(out.end(), {a.x(), a.y(), a.z()});
    out.push_back(static_cast<double>(d.candidates.size()));
    for (const Index k : d.candidates) out.push_back(static_cast<double>(k));
  }
  return out;
}

void ContactStaticSolver::restore_committed_state(const std::vector<double>& data,
                                                  std::vector<ContactBodyState> outputs) {
  const std::size_t nb = static_cast<std::size_t>(points_.size());
  const std::size_t nc = static_cast<std::size_t>(points_.num_constraints());
  const auto bad = [] {
    return Error("contact checkpoint does not fit this contact surface and these bodies");
  };
  if (outputs.size() != bodies_.size()) throw bad();
  std::size_t at = 0;
  const auto take = [&]() {
    if (at >= data.size()) throw bad();
    return data[at++];
  };
  std::vector<BodyData> restored(bodies_.size());
  for (BodyData& d : restored) {
    d.lambda.resize(nc);
    d.lambda_b.resize(nb);
    d.bonded.resize(nc);
    d.anchor.resize(nb);
    for (double& l : d.lambda) l = take();
    for (Vec3& l : d.lambda_b)
      for (int c = 0; c < 3; ++c) l[c] = take();
    for (char& b : d.bonded) b = take() != 0.0 ? 1 : 0;
    for (Vec3& a : d.anchor)
      for (int c = 0; c < 3; ++c) a[c] = take();
    const double n = take();
    if (!(n >= 0.0 && n <= static_cast<double>(nc))) throw bad();
    d.candidates.resize(static_cast<std::size_t>(n));
    for (Index& k : d.candidates) {
      const double v = take();
      if (!(v >= 0.0 && v < static_cast<double>(nc))) throw bad();
      k = static_cast<Index>(v);
    }
  }
  if (at != data.size()) throw bad();
  committed_ = std::move(restored);
  trial_ = committed_;
  state_ = std::move(outputs);
}

}  // namespace tmlab::tm
