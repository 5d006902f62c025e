// Kernel checks: the element-level building blocks of the tensor-mass model.
//
//   kernel.finite_difference   f = dW/du and K = df/du by central differences (and their O(eps^2) rate)
//   kernel.tensor_mass_vs_tl   TensorMassStVK (relative-displacement tensors) = total-Lagrangian StVK
//   kernel.rigid_invariance    W(Q(x) + c) = W(x), f rotates with Q, rigid motions give no force
//   kernel.patch_test          an affine displacement on the boundary of an irregular mesh is
//                              reproduced exactly in the interior (static Newton solve)
#include "verification/checks/check_support.hpp"

#include "tensormass/kernels/tensor_mass.hpp"
#include "tensormass/kernels/tl_oracle.hpp"
#include "tensormass/solvers/static_solver.hpp"
#include "tensormass/system/dirichlet.hpp"
#include "tensormass/system/external_loads.hpp"
#include "tensormass/system/lumped_mass.hpp"
#include "tensormass/system/mechanical_system.hpp"
#include "tensormass/viscoelastic/viscoelastic_model.hpp"

#include "core/mesh/mesh_ops.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <memory>
#include <ostream>
#include <random>

namespace tmlab::verify {

namespace {

using tm::ElasticModel;
using tm::StVenantKirchhoff;
using tm::VecX;

StVenantKirchhoff material_from(ConfigReader& p) {
  const double E = p.positive("young");
  const double nu = p.require<double>("poisson");
  if (!(nu > -1.0 && nu < 0.5)) throw p.error("poisson", "must be in (-1, 0.5)");
  return StVenantKirchhoff::from_young_poisson(E, nu);
}

/// A model by name; viscoelastic ones are given a committed history (three steps along u_hist)
/// and a trial step, so the check sees the history terms too.
std::unique_ptr<ElasticModel> make_model(const std::string& name, const Mesh& mesh,
                                         const StVenantKirchhoff& mat, const VecX& u_hist, ConfigReader& p) {
  if (name == "tensor_mass") return std::make_unique<tm::TensorMassStVK>(mesh, mat);
  if (name == "tl_oracle") return std::make_unique<tm::TotalLagrangianStVK>(mesh, mat);
  if (name == "viscoelastic_pk2" || name == "viscoelastic_nodal_force") {
    tm::ViscoelasticOptions o;
    o.history = name == "viscoelastic_pk2" ? tm::ViscoelasticOptions::History::Pk2
                                           : tm::ViscoelasticOptions::History::NodalForce;
    auto m = std::make_unique<tm::ViscoelasticStVK>(
        mesh, mat, tm::PronySeries::from_long_term({0.8, 0.5}, {0.05, 0.5}), o);
    const double dt = 0.01;
    for (int k = 1; k <= 3; ++k) {
      m->begin_step(dt);
      m->commit_step((k / 3.0) * u_hist);
    }
    m->begin_step(dt);
    return m;
  }
  throw p.error("model", "unknown model '" + name +
                             "' (tensor_mass | tl_oracle | viscoelastic_pk2 | viscoelastic_nodal_force)");
}

/// The potential whose gradient the model's internal_force is (the trial potential for viscoelastic models).
double potential(const ElasticModel& m, const VecX& u) {
  if (const auto* v = dynamic_cast<const tm::ViscoelasticStVK*>(&m)) return v->trial_potential(u);
  return m.energy(u);
}

// ------------------------------------------------------------------ kernel.finite_difference
Measurements finite_difference(const CheckContext& ctx) {
  ConfigReader p = parameters(ctx);
  const Mesh mesh = mesh_from_parameters(ctx, p.child("mesh"));
  const StVenantKirchhoff mat = material_from(p);
  const double amp = p.positive("displacement");
  const auto models = p.require<std::vector<std::string>>("models");
  const auto eps_list = p.require<std::vector<double>>("eps");  // relative to |u|_inf
  const int directions = p.get<int>("directions", 3);
  p.finish();

  Measurements m;
  const VecX u = smooth_random_displacement(mesh, amp, 11);
  const double scale = u.lpNorm<Eigen::Infinity>();
  double worst_force = 0.0, worst_tangent = 0.0, worst_assembled = 0.0;
  for (const auto& name : models) {
    const auto model = make_model(name, mesh, mat, 0.5 * u, p);
    VecX f, fp, fm, Kv, Kv2;
    model->internal_force(u, f);
    tm::SpMat K;
    model->tangent(u, K);
    std::vector<double> force_err(eps_list.size(), 0.0), tangent_err(eps_list.size(), 0.0);
    for (int d = 0; d < directions; ++d) {
      const VecX v =
          smooth_random_displacement(mesh, 1.0, 100 + d).normalized() * std::sqrt(double(u.size()));
      model->tangent_apply(u, v, Kv);
      Kv2 = K * v;
      worst_assembled = std::max(worst_assembled, (Kv - Kv2).norm() / Kv.norm());
      for (std::size_t k = 0; k < eps_list.size(); ++k) {
        const double h = eps_list[k] * scale / v.lpNorm<Eigen::Infinity>();
        const double dW = (potential(*model, u + h * v) - potential(*model, u - h * v)) / (2 * h);
        force_err[k] = std::max(force_err[k], std::abs(dW - f.dot(v)) / std::abs(f.dot(v)));
        model->internal_force(u + h * v, fp);
        model->internal_force(u - h * v, fm);
        tangent_err[k] = std::max(tangent_err[k], ((fp - fm) / (2 * h) - Kv).norm() / Kv.norm());
      }
    }
    Series sf, st;
    sf.x_label = st.x_label = "eps (step / |u|_inf)";
    sf.y_label = st.y_label = "relative FD error";
    for (std::size_t k = 0; k < eps_list.size(); ++k) {
      sf.x.push_back(eps_list[k]);
      sf.y.push_back(force_err[k]);
      st.x.push_back(eps_list[k]);
      st.y.push_back(tangent_err[k]);
    }
    m.series["force_fd_" + name] = sf;
    m.series["tangent_fd_" + name] = st;
    worst_force = std::max(worst_force, *std::min_element(force_err.begin(), force_err.end()));
    worst_tangent = std::max(worst_tangent, *std::min_element(tangent_err.begin(), tangent_err.end()));
  }
  m.set("force_fd_best_error", worst_force);
  m.set("tangent_fd_best_error", worst_tangent);
  m.set("assembled_vs_apply", worst_assembled);
  m.set("max_displacement_gradient_scale", amp);
  m.notes.push_back(std::to_string(mesh.num_tets()) +
                    " tets; the best FD error over the step sizes, worst over models and " +
                    std::to_string(directions) + " directions");
  return m;
}

// ------------------------------------------------------------------ kernel.tensor_mass_vs_tl
Measurements tensor_mass_vs_tl(const CheckContext& ctx) {
  ConfigReader p = parameters(ctx);
  const Mesh mesh = mesh_from_parameters(ctx, p.child("mesh"));
  const StVenantKirchhoff mat = material_from(p);
  const auto amps = p.require<std::vector<double>>("displacements");
  p.finish();
  const tm::TensorMassStVK tmm(mesh, mat);
  const tm::TotalLagrangianStVK tl(mesh, mat);
  double e_energy = 0, e_force = 0, e_tangent = 0, e_assembled = 0;
  for (std::size_t k = 0; k < amps.size(); ++k) {
    const VecX u = smooth_random_displacement(mesh, amps[k], 20 + unsigned(k));
    const VecX v = smooth_random_displacement(mesh, 1.0, 40 + unsigned(k));
    VecX f1, f2, k1, k2;
    tmm.internal_force(u, f1);
    tl.internal_force(u, f2);
    tmm.tangent_apply(u, v, k1);
    tl.tangent_apply(u, v, k2);
    tm::SpMat K1, K2;
    tmm.tangent(u, K1);
    tl.tangent(u, K2);
    e_energy = std::max(e_energy, std::abs(tmm.energy(u) - tl.energy(u)) / std::abs(tl.energy(u)));
    e_force = std::max(e_force, rel_max_diff(f1, f2));
    e_tangent = std::max(e_tangent, rel_max_diff(k1, k2));
    e_assembled = std::max(e_assembled, (K1 - K2).norm() / K2.norm());
  }
  Measurements m;
  m.set("force_rel_diff", e_force);
  m.set("energy_rel_diff", e_energy);
  m.set("tangent_apply_rel_diff", e_tangent);
  m.set("tangent_matrix_rel_diff", e_assembled);
  m.notes.push_back(std::to_string(mesh.num_tets()) + " tets, " + std::to_string(amps.size()) +
                    " displacement fields (|grad u| up to about " + std::to_string(amps.back() * 4) + ")");
  return m;
}

// ------------------------------------------------------------------ kernel.rigid_invariance
Measurements rigid_invariance(const CheckContext& ctx) {
  ConfigReader p = parameters(ctx);
  const Mesh mesh = mesh_from_parameters(ctx, p.child("mesh"));
  const StVenantKirchhoff mat = material_from(p);
  const double amp = p.positive("displacement");
  const double angle = p.require<double>("angle");
  const double shift = p.require<double>("translation");  // in units of the bounding-box diagonal
  p.finish();
  const tm::TensorMassStVK model(mesh, mat);
  const Index n = mesh.num_points();
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(angle, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const VecX ud = smooth_random_displacement(mesh, amp, 7);
  Vec3 lo = mesh.points.front(), hi = lo;
  for (const Vec3& x : mesh.points) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  const Vec3 c = shift * (hi - lo).norm() * Vec3(0.3, -0.5, 0.8);
  VecX ur(3 * n), urigid(3 * n);
  for (Index i = 0; i < n; ++i) {
    const Vec3 X = mesh.points[i];
    ur.segment<3>(3 * i) = Q * (X + ud.segment<3>(3 * i)) + c - X;
    urigid.segment<3>(3 * i) = Q * X + c - X;
  }
  VecX fd, fr, f0;
  model.internal_force(ud, fd);
  model.internal_force(ur, fr);
  model.internal_force(urigid, f0);
  VecX fd_rot(3 * n);
  for (Index i = 0; i < n; ++i) fd_rot.segment<3>(3 * i) = Q * fd.segment<3>(3 * i);
  Measurements m;
  m.set("energy_rel_diff", std::abs(model.energy(ur) - model.energy(ud)) / model.energy(ud));
  m.set("force_rel_diff", rel_max_diff(fr, fd_rot));
  m.set("rigid_force_rel", f0.lpNorm<Eigen::Infinity>() / fd.lpNorm<Eigen::Infinity>());
  m.set("rigid_energy_rel", std::abs(model.energy(urigid)) / model.energy(ud));
  return m;
}

// ------------------------------------------------------------------ kernel.patch_test
Measurements patch_test(const CheckContext& ctx) {
  ConfigReader p = parameters(ctx);
  const Mesh mesh = mesh_from_parameters(ctx, p.child("mesh"));
  const StVenantKirchhoff mat = material_from(p);
  const auto g = p.require<std::vector<double>>("gradient");  // H = F - I, row-major 3x3
  if (g.size() != 9) throw p.error("gradient", "needs 9 values (F - I, row-major)");
  const int steps = p.get<int>("load_steps", 4);
  p.finish();
  Eigen::Matrix3d H;
  for (int i = 0; i < 9; ++i) H(i / 3, i % 3) = g[static_cast<std::size_t>(i)];
  if ((Eigen::Matrix3d::Identity() + H).determinant() <= 0.0)
    throw Error(ctx.vcase.spec_file().string() + ": key 'parameters.gradient': det(I + H) must be > 0");
  const Index n = mesh.num_points();
  // Boundary nodes follow u = H X (ramped with t in [0, 1]); the interior is free.
  std::vector<tm::DirichletCondition> conds;
  const auto bnodes = boundary_nodes(mesh);
  for (Index b : bnodes) {
    tm::DirichletCondition dc;
    dc.name = "affine";
    dc.nodes = {b};
    dc.value = H * mesh.points[b];
    dc.function = TimeFunction::ramp(0.0, 1.0);
    conds.push_back(dc);
  }
  tm::TensorMassStVK model(mesh, mat);
  const VecX node_mass = tm::lumped_node_mass(mesh, 1000.0);
  tm::MechanicalSystem sys(model, tm::lumped_dof_mass(node_mass), tm::DirichletSet(n, conds),
                           tm::ExternalLoads(mesh, node_mass));
  tm::NewtonOptions no;
  no.rtol = 1e-12;
  tm::StaticSolver solver(sys, no);
  VecX u = VecX::Zero(3 * n);
  int iterations = 0;
  for (int k = 0; k < steps; ++k)
    iterations += solver.advance(double(k) / steps, double(k + 1) / steps, u).newton_iterations;
  VecX ua(3 * n);
  for (Index i = 0; i < n; ++i) ua.segment<3>(3 * i) = H * mesh.points[i];
  Measurements m;
  m.set("interior_rel_error", rel_max_diff(u, ua));
  m.set("interior_nodes", double(n - Index(bnodes.size())));
  m.set("newton_iterations", iterations);
  // The residual of the exact affine field itself (before any solve): the discrete equilibrium of
  // a homogeneous state, independent of Newton's tolerance.
  VecX f;
  model.internal_force(ua, f);
  for (Index b : bnodes) f.segment<3>(3 * b).setZero();
  VecX fb;
  model.internal_force(ua, fb);
  m.set("affine_residual_rel", f.lpNorm<Eigen::Infinity>() / fb.lpNorm<Eigen::Infinity>());
  return m;
}

}  // namespace

void register_kernel_checks(CheckRegistry& registry) {
  registry.add({{"kernel.finite_difference", finite_difference},
                {"kernel.tensor_mass_vs_tl", tensor_mass_vs_tl},
                {"kernel.rigid_invariance", rigid_invariance},
                {"kernel.patch_test", patch_test}});
}

}  // namespace tmlab::verify
