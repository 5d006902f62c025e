// External loads: nodal point forces, surface pressure (dead or follower) and gravity, each scaled
// by a TimeFunction. assemble() returns f_ext(u, t); follower pressure depends on u and contributes
// the (non-symmetric) load stiffness -d f_ext / du to the Newton tangent.
#pragma once

#include "core/config/time_function.hpp"
#include "core/mesh/mesh.hpp"
#include "core/mesh/quadratic_mesh.hpp"
#include "tensormass/kernels/elastic_model.hpp"

#include <Eigen/SparseCore>

#include <string>
#include <vector>

namespace tmlab::tm {

struct NodalForce {
  std::string name;
  std::vector<Index> nodes;
  Vec3 force = Vec3::Zero();  ///< newtons at f(t) = 1: the total over the set, split equally
  TimeFunction function = TimeFunction::constant(1.0);
};

struct SurfacePressure {
  std::string name;
  std::vector<Tri> faces;  ///< oriented with outward normals (right-hand rule)
  double pressure = 0.0;   ///< pascals at f(t) = 1, positive pushes into the body
  bool follower = false;   ///< true: acts on the deformed surface (load stiffness included)
  TimeFunction function = TimeFunction::constant(1.0);
};

struct SurfaceTraction {
  std::string name;
  std::vector<Tri> faces;        ///< boundary faces (reference configuration)
  Vec3 traction = Vec3::Zero();  ///< Pa per unit reference area at f(t) = 1 (dead load)
  TimeFunction function = TimeFunction::constant(1.0);
};

/// A dead pressure and traction on 6-node faces (quadratic elements): the consistent load
/// f_a = int N_a (t - p n) dA over the reference face, by the degree-4 triangle rule
/// (core/mesh/triangle_quadrature.hpp; exact on straight-sided faces). On a flat face a uniform
/// load puts nothing on the corners and a third of the total on each midside node.
struct QuadraticFaceLoad {
  std::string name;
  std::vector<Tri6> faces;       ///< outward (right-hand rule on the vertices)
  double pressure = 0.0;         ///< Pa at f(t) = 1, positive pushes into the body
  Vec3 traction = Vec3::Zero();  ///< Pa per unit reference area at f(t) = 1
  TimeFunction function = TimeFunction::constant(1.0);
};

struct Gravity {
  Vec3 acceleration = Vec3::Zero();  ///< m/s^2
  TimeFunction function = TimeFunction::constant(1.0);
};

class ExternalLoads {
 public:
  ExternalLoads() = default;
  /// `lumped_mass` holds the nodal masses (one per node), used by gravity.
  ExternalLoads(const Mesh& mesh, VecX lumped_node_mass);

  void add(NodalForce f);
  void add(SurfacePressure p);
  void add(SurfaceTraction t);
  void add(Gravity g);
  void add(QuadraticFaceLoad q);

  /// f_ext(u, t), overwrites f (size 3n).
  void assemble(const VecX& u, double t, VecX& f) const;
  bool has_follower() const;
  /// Adds -d f_ext/du (the load stiffness of follower pressure) as triplets.
  void add_load_stiffness(const VecX& u, double t, std::vector<Eigen::Triplet<double>>& triplets) const;

 private:
  void assemble_quadratic(double t, VecX& f) const;

  const Mesh* mesh_ = nullptr;
  VecX node_mass_;
  std::vector<NodalForce> nodal_;
  std::vector<SurfacePressure> pressure_;
  std::vector<SurfaceTraction> traction_;
  std::vector<Gravity> gravity_;
  std::vector<QuadraticFaceLoad> quadratic_;
};

}  // namespace tmlab::tm
