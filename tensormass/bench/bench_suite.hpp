// tmlab bench: every force kernel and whole solver step measured side by side in one run (Google
// Benchmark underneath), with the machine's limits measured in the same run; the result is a JSON
// document (schema in docs/performance.md) from which bench_report.hpp writes bench.json, bench.md
// and the plots.
//
// Records. Force kernels ("kind": "force"), one per (kernel, history, law, mesh, threads):
//   baseline     TotalLagrangianStVK / HyperelasticTL: the plain per-tet Eigen F-based kernel,
//                kept on purpose as the yardstick; history objective = ViscoelasticStVK (pk2)
//   fast         FastTetForce (SoA, AVX-512, Morton order, deterministic parallel scatter)
//   tensor_mass  TensorMassStVK, the paper's stored tensors; history seed = ViscoelasticStVK
//                (nodal_force)
// history none | seed | objective (2 Prony terms), law stvk | neo_hookean; ns_per_tet (wall time:
// the fast kernel's own threads are counted), flops_per_tet and bytes_per_tet (per-tet arrays
// streamed, hand counts documented in docs/performance.md), memory_per_tet (the model's storage).
// Whole steps ("kind": "step"): explicit (central differences), implicit (Newmark, Newton with the
// direct solver), static_newton (one load step of Newton), us_per_step.
#pragma once

#include <nlohmann/json.hpp>

#include <ostream>
#include <string>

namespace tmlab::tm {

struct BenchOptions {
  bool quick = false;      ///< CI: the 2.4k cube and the liver, minimal times (checks the schema, not speed)
  bool large = false;      ///< add the 2.4M-tet cube (~4 GB of memory, several minutes)
  int max_threads = 2;     ///< thread counts 1..max_threads for the fast kernel
  double min_time = 0.2;   ///< seconds per measurement (Google Benchmark's min time)
  std::string tmlab_root;  ///< for meshes/liver.msh
  std::ostream* log = nullptr;
};

/// Runs the whole suite; returns {"limits": {...}, "records": [...], "meshes": [...], "options": {...}}.
nlohmann::json run_bench(const BenchOptions& options);

}  // namespace tmlab::tm
