// The FE-rig forward model of a fit (issue 14, docs/identification.md "Forward models"): every test
// of the data is simulated in-process with the fast model on the rig the data's JSON names
// (calibration/rigs/rig_from_data.hpp), and the rig force at every sample is returned. No case file, no
// result directory: the mesh, the model, the boundary conditions and the solver are built through
// the library APIs at each predict() (so predict() is const and thread-safe: concurrent calls share
// only the read-only mesh, node sets and rigid bodies).
//
// Static, not explicit. Tissue tests run at mm/s over seconds to minutes: the inertia of a 1-100 g
// sample is many orders of magnitude below the measured forces, so the test is quasi-static. Central
// differences would need a time step of the sample's wave transit (~1e-5 s for a 2 cm, 3 kPa
// sample), 1e5-1e7 steps per test; the static solver takes one load step per data sample (or
// `substeps`), and a viscoelastic model's history advances once per accepted step with dt the
// data's sampling interval (the solvers' begin_step/commit_step protocol). A load step that does not
// converge is approached through intermediate, uncommitted targets: cut-backs find the starting
// iterate and never refine the history's time steps, so the forces are a smooth function of the
// parameters whatever the solver needed (rig_forward_model.cpp, load_step).
//
// The model of each law (the fast model where the paper has one):
//   stvk                 TensorMassStVK (the paper's tensor-mass model);
//                        with Prony terms ViscoelasticStVK (history pk2, relaxation full)
//   other laws           HyperelasticTL (the F-based P1 element for any Law);
//                        with Prony terms ViscoelasticHyperelastic (pk2, full)
// with the Prony weights alpha_j = e_j / E_inf (E_inf the law's small-strain Young's modulus, the
// fit's "young" for stvk and neo_hookean), midpoint recursion.
//
// The rig force: platen tests, minus the z reaction of the top face (positive in compression);
// indentation, the z force the sample exerts on the rigid indenter, from the augmented-Lagrangian
// contact solver (tensormass/contact, ContactStaticSolver).
#pragma once

#include "calibration/data/measured_data.hpp"
#include "calibration/fit/forward_model.hpp"
#include "calibration/fit/model_spec.hpp"
#include "calibration/rigs/rig_from_data.hpp"

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace tmlab::fit {

struct RigForwardModelOptions {
  rigs::RigFromDataMesh mesh;  ///< the rigs' mesh resolution
  int substeps = 1;            ///< static load steps per data sampling interval
  double newton_rtol = 1e-11;  ///< tight: the fit differentiates the forces numerically
  /// Newton iterations before a load step is cut back (a cut-back only finds a starting iterate:
  /// it does not change the step's result, see rig_forward_model.cpp load_step).
  int newton_max_iterations = 40;
  /// Indentation: > 0 sets the contact stiffness eps = factor x the mean K_0 zz-diagonal over the
  /// top-face nodes within the contact radius at peak depth (sqrt(R d_max) for a sphere, R for a
  /// punch) of the indenter's axis, the stiffness scale of the nodes that touch (the approach of
  /// verification/checks/contact_checks.cpp). 0: the contact solver's default (100 x the mean over
  /// every boundary DOF), which a graded mesh's far-field cells dominate: eps then exceeds the
  /// contact nodes' stiffness by orders of magnitude and Newton stalls at the contact edge. The
  /// solution does not depend on eps beyond the contact tolerance (the same stopping test).
  double contact_stiffness_factor = 0.0;
  /// The relative step of the fitter's forward-difference Jacobian (ForwardModel::jacobian_step).
  /// The forces carry the contact solver's tolerance (the Uzawa loop stops when no multiplier
  /// moves by more than eps x gap_tol; measured on the Section IV-A rig: warm and cold solves of one
  /// point differ by ~5e-8 of the peak force), so a step of 1e-6 leaves ~5 % noise in a Jacobian
  /// column. The balance of that noise against the forward difference's truncation error is near
  /// sqrt(5e-8) ~ 2e-4 (docs/identification.md, "Jacobian step of the FE rig").
  double jacobian_step = 1e-6;
  /// Builds each test's mesh instead of rigs::rig_mesh(spec) (e.g. a mesh graded for one study,
  /// studies/paper/paper_fit.cpp). It must cover the rig's sample (the same extent) and name
  /// the faces as rig_mesh does ("bottom", "top"), since the rig's boundary conditions select them.
  /// Empty: rigs::rig_mesh with `mesh`.
  std::function<Mesh(const rigs::RigSpec&)> mesh_builder;
};

/// The FE-rig forward model of `data` for the law of `spec` (predict_warm restarts each load step from
/// the displacements and contact multipliers of a previous prediction at that sample; effort()
/// counts solves, load steps, Newton and contact iterations, cut-backs); tmlab::Error (naming the data's JSON
/// key) when a test has no rig.
std::unique_ptr<ForwardModel> make_rig_forward_model(const measured::DataSet& data, const ModelSpec& spec,
                                                     const RigForwardModelOptions& options = {});

/// The solver effort of an FE-rig model, summed over its predictions so far.
struct RigForwardModelEffort {
  long solves = 0, warm = 0;  ///< predictions, of which warm-started
  long steps = 0;             ///< load steps (accepted increments asked for)
  long newton = 0;            ///< Newton iterations (over every contact outer iteration and cut-back)
  long outer = 0;             ///< contact (Uzawa) outer iterations
  long cutbacks = 0;
};
/// The effort of `model`; tmlab::Error when it is not an FE-rig model.
RigForwardModelEffort rig_forward_model_effort(const ForwardModel& model);

/// The size of an FE-rig model's meshes, summed over its tests.
struct RigForwardModelSize {
  std::size_t tests = 0, nodes = 0, tets = 0;
  rigs::RigFromDataMesh mesh;  ///< the resolution it was built with (RigForwardModelOptions::mesh)
};
/// The size of `model`; tmlab::Error when it is not an FE-rig model.
RigForwardModelSize rig_forward_model_size(const ForwardModel& model);

/// The problem with the FE-rig model for the final numbers and, when the data and law have one, the
/// closed-form surrogate (surrogates.hpp) as the global stage's model (Problem::global_model; its
/// absence and the reason are in `why_no_surrogate`).
Problem make_rig_forward_problem(const measured::DataSet& data, const ModelSpec& spec,
                                 const std::vector<std::pair<std::string, double>>& fixes = {},
                                 const std::vector<std::pair<std::string, double>>& weights = {},
                                 const RigForwardModelOptions& options = {},
                                 std::string* why_no_surrogate = nullptr);

}  // namespace tmlab::fit
