// The FE-rig forward model of a fit (issue 14, docs/identification.md "Forward models"): every test
// of the data is simulated in-process with the fast model on the rig the data's JSON names
// (calibration/rigs/data_rig.hpp), and the rig force at every sample is returned. No case file, no
// result directory: the mesh, the model, the boundary conditions and the solver are built through
// the library APIs at each predict() (so predict() is const and thread-safe: concurrent calls share
// only the read-only mesh, node sets and rigid bodies).
//
// Static, not explicit. Tissue tests run at mm/s over seconds to minutes: the inertia of a 1-100 g
// sample is many orders of magnitude below the measured forces, so the test is quasi-static. Central
// differences would need a time step of the sample's wave transit (~1e-5 s for a 2 cm, 3 kPa
// sample), 1e5-1e7 steps per test; the static solver takes one load step per data sample (or
// `substeps`), and a viscoelastic model's history advances once per accepted step with dt the
// data's sampling interval (the solvers' begin_step/commit_step protocol).
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
#include "calibration/rigs/data_rig.hpp"

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace tmlab::fit {

struct FeRigOptions {
  rigs::DataRigMesh mesh;      ///< the rigs' mesh resolution
  int substeps = 1;            ///< static load steps per data sampling interval
  double newton_rtol = 1e-11;  ///< tight: the fit differentiates the forces numerically
  /// Builds each test's mesh instead of rigs::rig_mesh(spec) (e.g. a mesh graded for one study,
  /// verification/studies/paper_fit.cpp). It must cover the rig's sample (the same extent) and name
  /// the faces as rig_mesh does ("bottom", "top"), since the rig's boundary conditions select them.
  /// Empty: rigs::rig_mesh with `mesh`.
  std::function<Mesh(const rigs::RigSpec&)> mesh_builder;
};

/// The FE-rig forward model of `data` for the law of `spec`; tmlab::Error (naming the data's JSON
/// key) when a test has no rig.
std::unique_ptr<ForwardModel> make_fe_rig_model(const measured::DataSet& data, const ModelSpec& spec,
                                                const FeRigOptions& options = {});

/// The problem with the FE-rig model for the final numbers and, when the data and law have one, the
/// closed-form surrogate (surrogates.hpp) as the global stage's model (Problem::global_model; its
/// absence and the reason are in `why_no_surrogate`).
Problem make_fe_rig_problem(const measured::DataSet& data, const ModelSpec& spec,
                            const std::vector<std::pair<std::string, double>>& fixes = {},
                            const std::vector<std::pair<std::string, double>>& weights = {},
                            const FeRigOptions& options = {}, std::string* why_no_surrogate = nullptr);

}  // namespace tmlab::fit
