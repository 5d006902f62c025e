// Lumped masses. Linear tets: row sums, each tet gives rho V / 4 to each of its vertices.
// Quadratic (10-node) tets: the row sums of the consistent mass are negative at the vertices
// (rho V/420 (6 + 3 - 4 * 3 - 6 * 3) = -rho V/20 for a straight tet), so they are lumped by HRZ
// (Hinton, Rock and Zienkiewicz 1976): each node gets the diagonal entry of the element's consistent
// mass, M_aa = rho int N_a^2, scaled so that the element's lumped total is rho V_e. For a straight
// tet M_aa = rho V 6/420 at a vertex and rho V 32/420 at a midside node: lumped rho V/36 and 4 rho V/27.
#pragma once

#include "core/mesh/mesh.hpp"
#include "core/mesh/quadratic_mesh.hpp"
#include "tensormass/kernels/elastic_model.hpp"

namespace tmlab::tm {

/// Nodal masses (one entry per node), kilograms. Throws for density <= 0 or an inverted tet.
VecX lumped_node_mass(const Mesh& mesh, double density);
/// HRZ nodal masses of the quadratic mesh (one entry per point), kilograms, from the consistent mass
/// diagonal integrated with the P2 rule (p2_quadrature.hpp; exact for the degree-4 N_a^2 on straight
/// tets). Throws for density <= 0 or a tet with a non-positive Jacobian at a quadrature point.
VecX hrz_lumped_node_mass(const QuadraticMesh& mesh, double density);
/// The same, repeated for the three DOFs of each node (the diagonal of M).
VecX lumped_dof_mass(const VecX& node_mass);

}  // namespace tmlab::tm
