// Small helpers shared by the check functions (verification/checks/*.cpp).
#pragma once

#include "core/config/config_reader.hpp"
#include "core/mesh/mesh.hpp"
#include "verification/checks/builtin_checks.hpp"
#include "verification/numerics/error_norms.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace tmlab::verify {

/// A strict reader of the case's "parameters" (errors name verify.json and parameters.<key>).
/// Call finish() on it once every parameter is read.
ConfigReader parameters(const CheckContext& ctx);

/// A mesh file given relative to the tmlab tree (e.g. "meshes/liver.msh"), read and checked.
Mesh load_tree_mesh(const CheckContext& ctx, const std::string& relative_path);

/// ||a - b||_inf / max(||b||_inf, floor) (verification/numerics/error_norms.hpp).
using numerics::rel_max_diff;

/// A Mesh with every interior node moved by up to `fraction` of the local edge length (seeded,
/// deterministic), boundary nodes kept; used to make structured meshes irregular.
Mesh perturb_interior(const Mesh& mesh, double fraction, unsigned seed);

}  // namespace tmlab::verify

namespace tmlab::verify {

/// The mesh named by a parameter object, either {"file": "meshes/x.msh"} (relative to the tmlab
/// tree) or {"box": [nx, ny, nz], "size": [lx, ly, lz], "perturb": f, "seed": s} (make_box_mesh
/// at the origin, interior nodes moved by perturb_interior when perturb > 0).
Mesh mesh_from_parameters(const CheckContext& ctx, ConfigReader r);

/// The nodes / boundary faces on the coordinate plane x_axis = value (tolerance 1e-12, for the
/// generated box meshes whose coordinates are exact).
std::vector<Index> plane_nodes(const Mesh& mesh, int axis, double value);
std::vector<Tri> plane_faces(const Mesh& mesh, int axis, double value);

/// A smooth, seeded displacement field: amplitude * L * (random affine + random sine modes), L the
/// mesh's bounding-box diagonal; deterministic for a given seed.
Eigen::VectorXd smooth_random_displacement(const Mesh& mesh, double amplitude, unsigned seed);

}  // namespace tmlab::verify
