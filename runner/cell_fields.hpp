// Per-tet kinematics of a displacement, for the run's checks and output: the smallest
// deformed-to-rest volume ratio (an inverted element stops the run) and the per-tet fields written
// at field frames (volume ratio, Green strain, Cauchy stress, von Mises).
#pragma once

#include "core/mesh/mesh.hpp"
#include "runner/problem.hpp"

#include <Eigen/Core>

#include <utility>
#include <vector>

namespace tmlab::tm::runner {

/// Smallest deformed-to-rest volume ratio J over all tets, and where it occurs (on quadratic
/// elements: of the tets of the vertices, u holding the vertices first).
std::pair<double, Index> min_volume_ratio(const Mesh& mesh, const VecX& u);

/// The per-tet output fields of a displacement u: volume ratio J, Green strain E, Cauchy stress
/// sigma = F S F^T / J of the case's law (S = dW/dE; for a viscoelastic material the long-term
/// stress) and its von Mises value.
struct CellFields {
  std::vector<double> jratio, von_mises;
  std::vector<Eigen::Matrix3d> strain, cauchy;
};

/// On quadratic elements the fields are those of the deformation gradient at each tet's centroid.
CellFields cell_fields(const Problem& p, const VecX& u);

/// The deformation gradient of 10-node tet t at its centroid, F = I + sum_a u_a (x) grad N_a.
Eigen::Matrix3d quadratic_centroid_gradient(const QuadraticMesh& qm, Index t, const VecX& u);

}  // namespace tmlab::tm::runner
