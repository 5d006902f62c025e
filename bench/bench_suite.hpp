// tmlab bench: every force kernel and whole solver step measured side by side in one run (Google
// Benchmark underneath), with the machine's limits measured in the same run; the result is a JSON
// document (schema in docs/performance.md) from which bench_report.hpp writes bench.json, bench.md
// and the plots.
//
// Records. Force kernels ("kind": "force"), one per (kernel, history, law, mesh, threads):
//   baseline     TotalLagrangianStVK / HyperelasticTL: the plain per-tet Eigen F-based kernel,
//                kept on purpose as the yardstick; history objective = ViscoelasticStVK (pk2)
//   fast         FastTetForce (SoA, AVX-512, Morton order, deterministic parallel scatter)
//   tensor_mass  TensorMassStVK, the paper's stored tensors; history xu2011 = ViscoelasticStVK
//                (nodal_force)
// history none | xu2011 | objective (2 Prony terms), law stvk | neo_hookean; ns_per_tet (wall time:
// the fast kernel's own threads are counted), flops_per_tet and bytes_per_tet (per-tet arrays
// streamed, hand counts documented in docs/performance.md), memory_per_tet (the model's storage).
// Whole steps ("kind": "step"): explicit (central differences), implicit (Newmark, Newton with the
// direct solver), static_newton (one load step of Newton), us_per_step. With a rigid sphere pressed
// into the top of a cube (the contact ladder, cubes of 2.4k to 132k tets; "contact": "sphere", "dt",
// "active_nodes"): explicit_contact (central differences with kinematic contact, the fast objective
// viscoelastic model on 1..max_threads threads) and implicit_contact (Newmark, dt = 1 ms,
// augmented-Lagrangian contact, "linear" ldlt | cholmod), from which bench_report.hpp interpolates
// the largest mesh with a 1 ms step.
#pragma once

#include <nlohmann/json.hpp>

#include <ostream>
#include <string>
#include <vector>

namespace tmlab::tm {

struct BenchOptions {
  bool quick = false;      ///< CI: the 2.4k cube and the liver, minimal times (checks the schema, not speed)
  bool large = false;      ///< add the 2.4M-tet cube (6.7 GB max RSS, ~4 minutes on 2026-11-27)
  int max_threads = 2;     ///< thread counts 1..max_threads for the fast kernel
  double min_time = 0.2;   ///< seconds per measurement (Google Benchmark's min time)
  std::string tmlab_root;  ///< for meshes/liver.msh
  /// Only these meshes (names of bench_mesh_names(); "contact": the contact ladder); empty: all.
  std::vector<std::string> meshes;
  std::ostream* log = nullptr;
};

/// The mesh names BenchOptions::meshes accepts: liver, cube_2k, cube_24k, cube_240k, cube_2m (with
/// large), contact.
std::vector<std::string> bench_mesh_names();
/// What is wrong with BenchOptions::meshes (an unknown name, cube_2m without large, a cube --quick
/// does not measure), or "" when nothing is.
std::string check_bench_meshes(const BenchOptions& options);

/// Runs the whole suite (throws tmlab::Error naming an unknown or unavailable mesh); returns {"limits":
/// {...}, "records": [...], "meshes": [...], "options": {...}}.
nlohmann::json run_bench(const BenchOptions& options);

}  // namespace tmlab::tm
