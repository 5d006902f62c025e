// Row-sum lumped mass of linear tets: each tet gives rho V / 4 to each of its vertices.
#pragma once

#include "core/mesh/mesh.hpp"
#include "tensormass/kernels/elastic_model.hpp"

namespace tmlab::tm {

/// Nodal masses (one entry per node), kilograms. Throws for density <= 0 or an inverted tet.
VecX lumped_node_mass(const Mesh& mesh, double density);
/// The same, repeated for the three DOFs of each node (the diagonal of M).
VecX lumped_dof_mass(const VecX& node_mass);

}  // namespace tmlab::tm
