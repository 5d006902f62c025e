// The deal.II reference: a quasi-static, total-Lagrangian, finite-strain finite-element solver that
// reads the same case file as the tensor-mass runner and writes the same result files, so that
// `tmlab compare` can diff the two (docs/reference-fem.md).
//
// This header is deal.II-free on purpose: the CLI, the thin app and most tests include it without
// paying for deal.II's headers. The solver itself is tmlab/reference_fem/solid.hpp.
#pragma once

#include "core/config/case_config.hpp"
#include "core/results/run_options.hpp"
#include "reference_fem/dealii/reference_options.hpp"

#include <array>
#include <memory>
#include <optional>
#include <string>

namespace tmlab::ref {

/// What the reference adds to a case: discretisation, constitutive law and solver choices.
struct ReferenceOptions {
  int degree = 1;  ///< polynomial degree: 1 or 2 (the volumetric form follows the case's mesh.element)
  /// Unset: the case's law (material.law, docs/case-files.md). Set: an override of a case given by
  /// E and nu: stvk | neo_hookean | yeoh (tmlab_reference --law).
  std::optional<MaterialLaw> law;
  double newton_rtol = 1e-10;  ///< |R_free| <= rtol * max(|R_0|, |f_ext|) + atol (atol from the case)
  /// direct (MUMPS through Trilinos Amesos) | direct_klu (KLU) | cg_amg (CG + ML AMG)
  LinearSolver linear_solver = LinearSolver::Direct;
  /// Yeoh law W = C10 (I1b-3) + C20 (I1b-3)^2 + C30 (I1b-3)^3 + kappa/2 (ln J)^2 with C10 = mu/2 and
  /// kappa = lambda + 2 mu / 3 from the case's E, nu; C20 and C30 given as multiples of C10.
  double yeoh_c20_ratio = 1.0;
  double yeoh_c30_ratio = 0.0;
  /// Cells: "tet" (the case's mesh, FE_SimplexP) or "hex" (the bounding box of the case's mesh,
  /// GridGenerator::subdivided_hyper_rectangle with hex_subdivisions cells, FE_Q). The hex mode is
  /// for the hex/tet cross-check on box-shaped bodies; its node selectors see the hex vertices, so
  /// group selectors are not available there.
  CellType cells = CellType::Tet;
  std::array<unsigned, 3> hex_subdivisions{4, 4, 4};
  /// Time integration of viscoelastic runs: "fixed_step" (the Prony recursion of the case's
  /// 'integration' on solver.steps increments) or "ida" (the quasi-static DAE, equilibrium algebraic
  /// and internal variables differential, by SUNDIALS IDA through deal.II; error-controlled steps,
  /// output at the same solver.steps times; one MPI rank; direct linear solvers only).
  TimeIntegration time_integration = TimeIntegration::FixedStep;
  double ida_rtol = 1e-6;  ///< IDA relative tolerance
  /// IDA absolute tolerance on the displacements (m); 0: 1e-3 ida_rtol times the bounding-box
  /// diagonal L of the mesh. The internal variables (PK2 stresses) get ida_atol E / L (Pa).
  double ida_atol = 0.0;
  bool serial = false;      ///< run on MPI_COMM_SELF even when started under mpirun
  std::string name_suffix;  ///< overrides "-reference" / "-reference-p2" when not empty
};

/// Runs the case with the deal.II reference and writes <results_root>/<case name>-reference (P1)
/// or -reference-p2 (P2; -reference-p2-mean_dilatation for mesh.element p2_mean_dilatation, whose
/// F-bar form the reference then runs): manifest.json, timeseries.h5, displacement.h5, vtu/ + result.pvd and
/// summary.json last (FAILED on errors). Under mpirun every rank must call it; rank 0 writes the
/// files and every rank returns the same summary. Input errors throw tmlab::Error.
/// MPI must be initialised by the caller: create an MpiSession in main() (tmlab_reference, the
/// tmlab CLI and the reference tests do); otherwise a tmlab::Error says so.
tmlab::RunResult run_reference_case(const tmlab::CaseConfig& config, const tmlab::RunOptions& options,
                                    const ReferenceOptions& reference = {});

/// The result directory name run_reference_case() uses.
std::string reference_result_name(const tmlab::CaseConfig& config, const ReferenceOptions& reference);

/// RAII MPI (and deal.II) initialisation for programs that use the reference: one per process, in
/// main(), before any other MPI use. Runs single-threaded inside each rank.
class MpiSession {
 public:
  MpiSession(int& argc, char**& argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  static int rank();  ///< rank in MPI_COMM_WORLD
  static int size();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tmlab::ref
