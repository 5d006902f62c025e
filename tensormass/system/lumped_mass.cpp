#include "tensormass/system/lumped_mass.hpp"

#include "core/base/error.hpp"
#include "tensormass/kernels/tet_geometry.hpp"

#include <cmath>

namespace tmlab::tm {

VecX lumped_node_mass(const Mesh& mesh, double density) {
  if (!(density > 0.0) || !std::isfinite(density))
    throw Error("density must be > 0 (got " + std::to_string(density) + ")");
  const std::vector<TetRest> rest = compute_tet_rest(mesh);  // throws naming an inverted tet
  VecX m = VecX::Zero(mesh.num_points());
  for (Index t = 0; t < mesh.num_tets(); ++t)
    for (Index n : mesh.tets[t]) m[n] += density * rest[t].volume / 4.0;
  return m;
}

VecX lumped_dof_mass(const VecX& node_mass) {
  VecX m(3 * node_mass.size());
  for (Eigen::Index i = 0; i < node_mass.size(); ++i) m.segment<3>(3 * i).setConstant(node_mass[i]);
  return m;
}

}  // namespace tmlab::tm
