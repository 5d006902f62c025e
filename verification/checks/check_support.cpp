#include "verification/checks/check_support.hpp"

#include "core/config/case_config.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "core/mesh/mesh_quality.hpp"

#include <algorithm>
#include <cmath>
#include <random>

namespace tmlab::verify {

ConfigReader parameters(const CheckContext& ctx) {
  return ConfigReader(ctx.vcase.parameters, ctx.vcase.spec_file().string(), "parameters");
}

Mesh load_tree_mesh(const CheckContext& ctx, const std::string& relative_path) {
  MeshSpec spec;
  spec.file = (ctx.source_root / relative_path).string();
  MeshReport report;
  int repaired = 0;
  return load_case_mesh(spec, report, repaired);
}

Mesh perturb_interior(const Mesh& mesh, double fraction, unsigned seed) {
  // Shortest edge at each node bounds the move, so no tet can invert for fraction < ~0.25.
  std::vector<double> hmin(mesh.points.size(), 1e300);
  for (const Tet& t : mesh.tets)
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) {
        const double l = (mesh.points[t[a]] - mesh.points[t[b]]).norm();
        hmin[t[a]] = std::min(hmin[t[a]], l);
        hmin[t[b]] = std::min(hmin[t[b]], l);
      }
  std::vector<char> on_boundary(mesh.points.size(), 0);
  for (Index n : boundary_nodes(mesh)) on_boundary[n] = 1;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Mesh out = mesh;
  for (std::size_t i = 0; i < out.points.size(); ++i) {
    if (on_boundary[i]) continue;
    out.points[i] += fraction * hmin[i] * Vec3(u(rng), u(rng), u(rng)) / std::sqrt(3.0);
  }
  return out;
}

}  // namespace tmlab::verify

namespace tmlab::verify {

Mesh mesh_from_parameters(const CheckContext& ctx, ConfigReader r) {
  Mesh m;
  if (r.has("file")) {
    m = load_tree_mesh(ctx, r.require<std::string>("file"));
  } else {
    const auto n = r.require<std::vector<int>>("box");
    const auto size = r.require<std::vector<double>>("size");
    if (n.size() != 3 || size.size() != 3) throw r.error("box", "'box' and 'size' need three values each");
    m = make_box_mesh(Vec3::Zero(), Vec3(size[0], size[1], size[2]), n[0], n[1], n[2]);
    const double f = r.get<double>("perturb", 0.0);
    if (f < 0.0 || f > 0.3) throw r.error("perturb", "must be in [0, 0.3] (larger moves may invert tets)");
    if (f > 0.0) m = perturb_interior(m, f, r.get<unsigned>("seed", 1u));
  }
  r.finish();
  return m;
}

Eigen::VectorXd smooth_random_displacement(const Mesh& mesh, double amplitude, unsigned seed) {
  Vec3 lo = mesh.points.front(), hi = lo;
  for (const Vec3& p : mesh.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double L = (hi - lo).norm();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Matrix3d G;
  for (int i = 0; i < 9; ++i) G(i / 3, i % 3) = u(rng);
  Vec3 k1(u(rng), u(rng), u(rng)), k2(u(rng), u(rng), u(rng)), a1(u(rng), u(rng), u(rng)),
      a2(u(rng), u(rng), u(rng));
  k1 *= 2.0 * M_PI / L;
  k2 *= 4.0 * M_PI / L;
  Eigen::VectorXd out(3 * mesh.num_points());
  for (Index i = 0; i < mesh.num_points(); ++i) {
    const Vec3 X = mesh.points[i] - lo;
    const Vec3 d = G * X / L + a1 * std::sin(k1.dot(X)) + 0.5 * a2 * std::sin(k2.dot(X));
    out.segment<3>(3 * i) = amplitude * L * d;
  }
  return out;
}

std::vector<Index> plane_nodes(const Mesh& mesh, int axis, double value) {
  return select_nodes(mesh, NodeSelector::plane(axis, value, 1e-12));
}

std::vector<Tri> plane_faces(const Mesh& mesh, int axis, double value) {
  return select_faces(mesh, NodeSelector::plane(axis, value, 1e-12));
}

}  // namespace tmlab::verify
