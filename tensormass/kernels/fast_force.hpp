// FastTetForce: the fast internal-force kernel of the F-based P1 element (St Venant-Kirchhoff or
// compressible neo-Hookean, the laws of hyperelastic_tl.hpp), written for speed; the slow, obviously
// correct per-tet Eigen kernels (TotalLagrangianStVK, HyperelasticTL) are its oracles
// (tests/test_fast_force.cpp: equal to 1e-12 relative).
//
// Per tet (relative form, a_j = grad N_j, V the rest volume):
//   H = sum_{j=1..3} (U_j - U_0) (x) a_j,  F = I + H,  E = (H + H^T + H^T H)/2,  S = S(E),
//   f_j = V F S a_j (j = 1..3),  f_0 = -(f_1 + f_2 + f_3)
// St VK: S = lambda tr(E) I + 2 mu E; neo-Hookean: C = I + 2E, S = mu (I - C^-1) + lambda ln J C^-1.
// Objective viscoelastic trial force (ViscoelasticStVK, history pk2, full relaxation): the same
// kernel with S = lambda_eff tr(E) I + 2 mu_eff E + S_hist(t) (fused: no second pass).
//
// How it is fast (docs/performance.md):
//  * Structure of arrays in groups of kLanes tets (8 with AVX-512, 4 with AVX2): the 9 shape
//    gradients, the volume, the 4 node indices and 4 scatter offsets of lane l are stored at
//    [group][k][l], so the arithmetic of a group is one vectorised loop over the lanes (one SIMD
//    register per value); only the gather of U and the scatter of f are scalar.
//  * The fused viscoelastic step's history and driver, and the trial force's S_hist, are kept by
//    the caller in the same lane order (tet_slots()): each group's block is contiguous and streams
//    with vector loads and stores; the lane loop has no control flow (the number of Prony terms and
//    the deviatoric switch are template parameters).
//  * Tets sorted by the Morton code of their centroid: neighbours in memory share nodes, so the
//    gathers and scatters hit cache.
//  * Race-free, deterministic parallel scatter: the sorted tets are cut into kParts contiguous parts
//    (a fixed number, independent of the thread count). A node touched by one part only is written
//    directly by that part; a node touched by several ("shared", the few on part interfaces) is
//    accumulated in a per-part buffer and summed afterwards in part order. Every node's sum is
//    therefore formed in the same order whatever the number of threads: 1, 2 or 4 threads give
//    bit-identical forces (tested), with no atomics.
//  * A WorkerPool started once at construction and owned by the kernel.
// Counted per tet (St VK, hand count of the lane loop, FMA = 2 flops): 237 flops; bytes streamed
// from the per-tet arrays: 116 (9 + 1 doubles, 4 + 4 + 1 int32).
#pragma once

#include "tensormass/kernels/elastic_model.hpp"
#include "tensormass/kernels/worker_pool.hpp"

#include <cstdint>
#include <memory>
#include <vector>

namespace tmlab::tm {

enum class FastLaw { StVK, NeoHookean };

class FastTetForce {
 public:
  /// Tets per group: one SIMD register of doubles per value (8 with AVX-512, else 4: with AVX2's 16
  /// registers, 8 lanes take two registers per value and the lane loop spills; measured,
  /// docs/performance.md).
#ifdef __AVX512F__
  static constexpr int kLanes = 8;
#else
  static constexpr int kLanes = 4;
#endif
  static constexpr int kParts = 8;

  /// Rest geometry (throws tmlab::Error on bad tets), the Morton order, the parts and the pool of
  /// `threads` (>= 1) threads.
  FastTetForce(const Mesh& mesh, FastLaw law, double lambda, double mu, int threads = 1);

  Index num_nodes() const { return num_nodes_; }
  Index num_tets() const { return num_tets_; }
  int threads() const { return pool_->threads(); }
  FastLaw law() const { return law_; }
  /// Bytes of the per-tet arrays and the shared-node buffers (the kernel's memory).
  std::size_t storage_bytes() const;

  /// f = dW/du (overwrites f, resized to 3 num_nodes()).
  void internal_force(const VecX& u, VecX& f) const;
  /// Objective viscoelastic trial force with S = lambda_eff tr(E) I + 2 mu_eff E + S_hist(t),
  /// s_hist: 6 Voigt values (xx, yy, zz, xy, xz, yz) per tet in this kernel's LANE ORDER (as the
  /// fused step's driver: [g][k][l], num_slots() x 6 values, zeros in padding slots). St VK only (throws
  /// tmlab::Error for neo-Hookean).
  void trial_force_pk2(const VecX& u, double lambda_eff, double mu_eff, const double* s_hist, VecX& f) const;

  /// One step of the objective (pk2) Prony history, for a step of the recursion factors (a_j, c_j).
  struct PronyStep {
    static constexpr int kMaxTerms = 4;
    int terms = 0;
    double alpha[kMaxTerms] = {}, a[kMaxTerms] = {}, c[kMaxTerms] = {};
    bool deviatoric = false;  ///< the driver is S_dev = 2 mu dev(E) instead of S_e
  };
  /// The fused explicit viscoelastic step (ViscoelasticStVK::force_and_commit, history pk2) in one
  /// pass: per tet E, the driver x (S_e = lambda tr(E) I + 2 mu E with this kernel's Lame pair, or
  /// S_dev), the history h_j <- a_j h_j + c_j (x - X), X <- x, and the force of
  /// S = S_e + sum_j alpha_j h_j (the trial force at u, equal to (1 + g) S_e + S_hist). hist and
  /// driver (Voigt) are in this kernel's LANE ORDER (tet_slots()), updated in place: hist
  /// [g][6 j + k][l] (num_slots() x 6 terms values), driver [g][k][l] (num_slots() x 6), so the pass
  /// streams them with vector loads and stores; padding slots must hold zeros (they stay zero).
  /// St VK; terms <= 4.
  void force_and_commit_pk2(const VecX& u, const PronyStep& step, double* hist, double* driver,
                            VecX& f) const;

  /// The lane order of the per-tet arrays: slot s = kLanes g + l (group g, lane l), groups in part
  /// order; num_slots() >= num_tets(), the extra (padding) slots hold no tet.
  std::size_t num_slots() const { return tet_.size(); }
  /// The slot of each mesh tet (num_tets() values, a permutation into [0, num_slots())).
  std::vector<std::int32_t> tet_slots() const;

 private:
  struct Args {
    double lam = 0.0, mu = 0.0;
    const double* s_hist = nullptr;
    const PronyStep* step = nullptr;
    double* hist = nullptr;
    double* driver = nullptr;
  };
  // Terms and Dev (deviatoric driver) of the fused pk2 step are compile-time constants so that its
  // lane loop has no control flow (and vectorises).
  template <int Mode, int Terms = 0, bool Dev = false>
  void evaluate(const VecX& u, const Args& args, VecX& f) const;
  template <int Mode, int Terms, bool Dev>
  void run_part(int part, const double* u, const Args& args, double* f) const;
  template <bool Dev>
  void fused_pk2(int terms, const VecX& u, const Args& args, VecX& f) const;

  Index num_nodes_ = 0, num_tets_ = 0;
  FastLaw law_;
  double lambda_ = 0.0, mu_ = 0.0;
  // per group g (kLanes tets): grad [g][9][l] (a_1, a_2, a_3 row by row), vol [g][l],
  // node [g][4][l], dest [g][4][l] (>= 0: 3 node into f; < 0: -1 - offset into the part's shared row),
  // tet [g][l] (mesh index of the tet, -1 in padding lanes).
  std::vector<double> grad_, vol_;
  std::vector<std::int32_t> node_, dest_, tet_;
  std::vector<int> part_begin_;  ///< kParts + 1 group offsets
  std::vector<Index> shared_nodes_;
  std::size_t shared_stride_ = 0;  ///< doubles per part row: 3 (shared nodes + 1 scratch)
  mutable std::vector<double> shared_;
  std::unique_ptr<WorkerPool> pool_;
};

}  // namespace tmlab::tm

#include "tensormass/kernels/hyperelastic_tl.hpp"

namespace tmlab::tm {

/// An ElasticModel whose internal force is FastTetForce (with `threads` threads); energy and
/// tangents are HyperelasticTL's for the same law (the solvers' hot path in explicit dynamics is the
/// force only).
class FastHyperelastic : public ElasticModel {
 public:
  FastHyperelastic(const Mesh& mesh, FastLaw law, double lambda, double mu, int threads = 1);

  Index num_nodes() const override { return fast_.num_nodes(); }
  const FastTetForce& kernel() const { return fast_; }
  double energy(const VecX& u) const override { return tl_.energy(u); }
  void internal_force(const VecX& u, VecX& f) const override { fast_.internal_force(u, f); }
  void tangent_apply(const VecX& u, const VecX& v, VecX& Kv) const override { tl_.tangent_apply(u, v, Kv); }
  void tangent(const VecX& u, SpMat& K) const override { tl_.tangent(u, K); }

 private:
  HyperelasticTL tl_;
  FastTetForce fast_;
};

}  // namespace tmlab::tm
