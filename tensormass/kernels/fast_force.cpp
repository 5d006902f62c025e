// The fast F-based force kernel; layout, ordering and the deterministic parallel scatter are
// explained in fast_force.hpp.
#include "tensormass/kernels/fast_force.hpp"

#include "core/base/error.hpp"
#include "tensormass/kernels/tet_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace tmlab::tm {

namespace {

enum Mode { kStVK = 0, kNeoHookean = 1, kStVKTrial = 2, kFusedPk2 = 3 };

/// 3 x 21 bits interleaved: the Morton (Z-order) code of a point of the unit cube.
std::uint64_t morton(double x, double y, double z) {
  auto spread = [](double v) {
    std::uint64_t q = static_cast<std::uint64_t>(std::clamp(v, 0.0, 1.0) * ((1u << 21) - 1));
    q &= 0x1fffff;
    q = (q | q << 32) & 0x1f00000000ffffULL;
    q = (q | q << 16) & 0x1f0000ff0000ffULL;
    q = (q | q << 8) & 0x100f00f00f00f00fULL;
    q = (q | q << 4) & 0x10c30c30c30c30c3ULL;
    q = (q | q << 2) & 0x1249249249249249ULL;
    return q;
  };
  return spread(x) | spread(y) << 1 | spread(z) << 2;
}

}  // namespace

FastTetForce::FastTetForce(const Mesh& mesh, FastLaw law, double lambda, double mu, int threads)
    : num_nodes_(mesh.num_points()), num_tets_(mesh.num_tets()), law_(law), lambda_(lambda), mu_(mu) {
  const std::vector<TetRest> rest = compute_tet_rest(mesh);  // throws on bad tets
  pool_ = std::make_unique<WorkerPool>(threads);
  constexpr int L = kLanes;
  const std::size_t nt = mesh.tets.size();

  // Morton order of the tet centroids.
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  std::vector<Vec3> centroid(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    Vec3 c = Vec3::Zero();
    for (Index n : mesh.tets[t]) c += mesh.points[static_cast<std::size_t>(n)];
    centroid[t] = 0.25 * c;
    lo = lo.cwiseMin(centroid[t]);
    hi = hi.cwiseMax(centroid[t]);
  }
  const Vec3 ext = (hi - lo).cwiseMax(Vec3::Constant(1e-300));
  std::vector<std::uint64_t> code(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const Vec3 s = (centroid[t] - lo).cwiseQuotient(ext);
    code[t] = morton(s.x(), s.y(), s.z());
  }
  std::vector<std::int32_t> order(nt);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::int32_t a, std::int32_t b) {
    return code[static_cast<std::size_t>(a)] < code[static_cast<std::size_t>(b)];
  });

  // Contiguous parts of (nearly) equal size, each a whole number of groups.
  std::vector<std::size_t> tet_begin(kParts + 1, 0);
  for (int k = 0; k < kParts; ++k)
    tet_begin[static_cast<std::size_t>(k) + 1] = tet_begin[static_cast<std::size_t>(k)] + nt / kParts +
                                                 (static_cast<std::size_t>(k) < nt % kParts ? 1 : 0);
  part_begin_.assign(kParts + 1, 0);
  for (int k = 0; k < kParts; ++k) {
    const std::size_t n = tet_begin[static_cast<std::size_t>(k) + 1] - tet_begin[static_cast<std::size_t>(k)];
    part_begin_[static_cast<std::size_t>(k) + 1] =
        part_begin_[static_cast<std::size_t>(k)] + static_cast<int>((n + L - 1) / L);
  }

  // Nodes touched by more than one part are shared.
  std::vector<int> first(static_cast<std::size_t>(num_nodes_), -1);
  std::vector<std::int32_t> slot(static_cast<std::size_t>(num_nodes_), -1);
  for (int k = 0; k < kParts; ++k)
    for (std::size_t i = tet_begin[static_cast<std::size_t>(k)];
         i < tet_begin[static_cast<std::size_t>(k) + 1]; ++i)
      for (Index n : mesh.tets[static_cast<std::size_t>(order[i])]) {
        int& fp = first[static_cast<std::size_t>(n)];
        if (fp < 0) {
          fp = k;
        } else if (fp != k && slot[static_cast<std::size_t>(n)] < 0) {
          slot[static_cast<std::size_t>(n)] = static_cast<std::int32_t>(shared_nodes_.size());
          shared_nodes_.push_back(n);
        }
      }
  const std::int32_t scratch = static_cast<std::int32_t>(3 * shared_nodes_.size());
  shared_stride_ = 3 * (shared_nodes_.size() + 1);
  shared_.assign(kParts * shared_stride_, 0.0);

  // The SoA arrays; padding lanes have zero volume and gradients and scatter into the scratch slot.
  const std::size_t ng = static_cast<std::size_t>(part_begin_.back());
  grad_.assign(ng * 9 * L, 0.0);
  vol_.assign(ng * L, 0.0);
  node_.assign(ng * 4 * L, 0);
  dest_.assign(ng * 4 * L, -1 - scratch);
  tet_.assign(ng * L, -1);
  for (int k = 0; k < kParts; ++k) {
    const std::size_t t0 = tet_begin[static_cast<std::size_t>(k)];
    for (std::size_t i = t0; i < tet_begin[static_cast<std::size_t>(k) + 1]; ++i) {
      const std::size_t g = static_cast<std::size_t>(part_begin_[static_cast<std::size_t>(k)]) + (i - t0) / L;
      const std::size_t l = (i - t0) % L;
      const std::size_t t = static_cast<std::size_t>(order[i]);
      const TetRest& r = rest[t];
      for (int j = 1; j < 4; ++j)
        for (int c = 0; c < 3; ++c) grad_[(g * 9 + 3 * (j - 1) + c) * L + l] = r.grad[j][c];
      vol_[g * L + l] = r.volume;
      tet_[g * L + l] = static_cast<std::int32_t>(t);
      for (int p = 0; p < 4; ++p) {
        const Index n = mesh.tets[t][static_cast<std::size_t>(p)];
        node_[(g * 4 + p) * L + l] = n;
        const std::int32_t s = slot[static_cast<std::size_t>(n)];
        dest_[(g * 4 + p) * L + l] = s < 0 ? 3 * n : -1 - 3 * s;
      }
    }
  }
}

std::size_t FastTetForce::storage_bytes() const {
  return sizeof(double) * (grad_.size() + vol_.size() + shared_.size()) +
         sizeof(std::int32_t) * (node_.size() + dest_.size() + tet_.size()) +
         sizeof(Index) * shared_nodes_.size();
}

namespace {

// The stages of run_part, one concept each; per group of kLanes tets, lane l of every array is one
// tet. The lane loops are meant to vectorise: keep them free of calls that do not inline.
constexpr int kL = FastTetForce::kLanes;
constexpr int kT = FastTetForce::PronyStep::kMaxTerms;

/// The per-group working arrays of the lanes.
struct GroupScratch {
  alignas(64) double e[9][kL];        // e_j = U_j - U_0: e[3(j-1) + i][l]
  alignas(64) double fo[12][kL];      // f_p: fo[3p + i][l]
  alignas(64) double sv[6][kL];       // S_hist (Voigt) of the trial force
  alignas(64) double lnj[kL];         // neo-Hookean ln J
  alignas(64) double hh[9][kL];       // H, kept for the second stage of the neo-Hookean kernel
  alignas(64) double hl[6 * kT][kL];  // fused pk2: the group's history h_j, a copy of its lane-order block
  alignas(64) double xl[6][kL];       // fused pk2: the group's committed driver X, likewise
};

/// The Prony recursion of one fused pk2 step padded to kT terms: the unused terms have alpha 0 and
/// leave h unchanged (a = 1, c = 0).
struct PaddedPronyStep {
  int terms = 0;
  double al[kT] = {}, aa[kT] = {}, cc[kT] = {};
};

PaddedPronyStep padded(const FastTetForce::PronyStep& step) {
  PaddedPronyStep p;
  p.terms = step.terms;
  for (int j = 0; j < kT; ++j) {
    p.al[j] = j < p.terms ? step.alpha[j] : 0.0;
    p.aa[j] = j < p.terms ? step.a[j] : 1.0;
    p.cc[j] = j < p.terms ? step.c[j] : 0.0;
  }
  return p;
}

/// e_j = U_j - U_0 of each lane, gathered from u by the lanes' node indices nd [4][l].
inline void gather_edges(const double* u, const std::int32_t* nd, GroupScratch& w) {
  for (int l = 0; l < kL; ++l) {
    const double* u0 = u + 3 * static_cast<std::ptrdiff_t>(nd[l]);
    for (int j = 1; j < 4; ++j) {
      const double* uj = u + 3 * static_cast<std::ptrdiff_t>(nd[j * kL + l]);
      for (int i = 0; i < 3; ++i) w.e[3 * (j - 1) + i][l] = uj[i] - u0[i];
    }
  }
}

/// The trial force's S_hist of a group, its lane-order block sg [k][l] (zeros in padding slots).
inline void load_trial_history(const double* __restrict sg, GroupScratch& w) {
  for (int k = 0; k < 6; ++k)
    for (int l = 0; l < kL; ++l) w.sv[k][l] = sg[k * kL + l];
}

/// Neo-Hookean stage 1: H and ln J of every lane (log is scalar: kept out of the vectorised loops).
inline void neo_hookean_stage1(const double* a, GroupScratch& w) {
  for (int l = 0; l < kL; ++l)
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k)
        w.hh[3 * i + k][l] = w.e[i][l] * a[k * kL + l] + w.e[3 + i][l] * a[(3 + k) * kL + l] +
                             w.e[6 + i][l] * a[(6 + k) * kL + l];
  for (int l = 0; l < kL; ++l) {
    const double F00 = 1 + w.hh[0][l], F01 = w.hh[1][l], F02 = w.hh[2][l];
    const double F10 = w.hh[3][l], F11 = 1 + w.hh[4][l], F12 = w.hh[5][l];
    const double F20 = w.hh[6][l], F21 = w.hh[7][l], F22 = 1 + w.hh[8][l];
    const double J =
        F00 * (F11 * F22 - F12 * F21) - F01 * (F10 * F22 - F12 * F20) + F02 * (F10 * F21 - F11 * F20);
    w.lnj[l] = J > 0.0 ? std::log(J) : std::nan("");  // outside the domain: NaN force (as HyperelasticTL)
  }
}

/// H = sum_j e_j (x) a_j of lane l (the neo-Hookean kernel reads it from stage 1).
template <int M>
inline void displacement_gradient(const GroupScratch& w, const double* a, int l, double (&H)[3][3]) {
#pragma GCC unroll 3
  for (int i = 0; i < 3; ++i)
#pragma GCC unroll 3
    for (int k = 0; k < 3; ++k) {
      if constexpr (M == kNeoHookean)
        H[i][k] = w.hh[3 * i + k][l];
      else
        H[i][k] = w.e[i][l] * a[k * kL + l] + w.e[3 + i][l] * a[(3 + k) * kL + l] +
                  w.e[6 + i][l] * a[(6 + k) * kL + l];
    }
}

/// E = (H + H^T + H^T H) / 2
inline void green_lagrange(const double (&H)[3][3], double (&E)[3][3]) {
#pragma GCC unroll 3
  for (int i = 0; i < 3; ++i)
#pragma GCC unroll 3
    for (int k = i; k < 3; ++k)
      E[i][k] = 0.5 * (H[i][k] + H[k][i] + H[0][i] * H[0][k] + H[1][i] * H[1][k] + H[2][i] * H[2][k]);
  E[1][0] = E[0][1];
  E[2][0] = E[0][2];
  E[2][1] = E[1][2];
}

/// Neo-Hookean: C = I + 2E, S = mu (I - C^-1) + lambda ln J C^-1, C^-1 = adj(C) / det C
inline void neo_hookean_pk2(const double (&E)[3][3], double lam, double mu, double lnj, double (&S)[3][3]) {
  double C[3][3];
#pragma GCC unroll 3
  for (int i = 0; i < 3; ++i)
#pragma GCC unroll 3
    for (int k = 0; k < 3; ++k) C[i][k] = 2.0 * E[i][k] + (i == k ? 1.0 : 0.0);
  const double A00 = C[1][1] * C[2][2] - C[1][2] * C[2][1];
  const double A01 = C[0][2] * C[2][1] - C[0][1] * C[2][2];
  const double A02 = C[0][1] * C[1][2] - C[0][2] * C[1][1];
  const double A11 = C[0][0] * C[2][2] - C[0][2] * C[2][0];
  const double A12 = C[0][2] * C[1][0] - C[0][0] * C[1][2];
  const double A22 = C[0][0] * C[1][1] - C[0][1] * C[1][0];
  const double inv = 1.0 / (C[0][0] * A00 + C[1][0] * A01 + C[2][0] * A02);
  const double ci[6] = {A00 * inv, A11 * inv, A22 * inv, A01 * inv, A02 * inv, A12 * inv};
  const double b = lam * lnj - mu;
  S[0][0] = mu + b * ci[0];
  S[1][1] = mu + b * ci[1];
  S[2][2] = mu + b * ci[2];
  S[0][1] = S[1][0] = b * ci[3];
  S[0][2] = S[2][0] = b * ci[4];
  S[1][2] = S[2][1] = b * ci[5];
}

/// St Venant-Kirchhoff: S = lambda tr(E) I + 2 mu E
inline void stvk_pk2(const double (&E)[3][3], double lam, double mu, double (&S)[3][3]) {
  const double ltr = lam * (E[0][0] + E[1][1] + E[2][2]);
#pragma GCC unroll 3
  for (int i = 0; i < 3; ++i)
#pragma GCC unroll 3
    for (int k = 0; k < 3; ++k) S[i][k] = 2.0 * mu * E[i][k];
#pragma GCC unroll 3
  for (int i = 0; i < 3; ++i) S[i][i] += ltr;
}

/// S += v, v symmetric in Voigt order (xx, yy, zz, xy, xz, yz).
inline void add_voigt(double (&S)[3][3], double v0, double v1, double v2, double v3, double v4, double v5) {
  S[0][0] += v0;
  S[1][1] += v1;
  S[2][2] += v2;
  S[0][1] += v3;
  S[1][0] += v3;
  S[0][2] += v4;
  S[2][0] += v4;
  S[1][2] += v5;
  S[2][1] += v5;
}

/// The fused Prony step of lane l on S = S_e: driver x = S_e or S_dev = 2 mu (E - tr(E)/3 I)
/// (Voigt), history h_j <- a_j h_j + c_j (x - X), X <- x (NJ terms, in the scratch copies w.hl,
/// w.xl), and S += sum_j alpha_j h_j.
template <int NJ, bool dev>
inline void prony_step(const double (&E)[3][3], double mu, const PaddedPronyStep& p, int l, GroupScratch& w,
                       double (&S)[3][3]) {
  const double trd = (E[0][0] + E[1][1] + E[2][2]) / 3.0;
  const double x[6] = {dev ? 2.0 * mu * (E[0][0] - trd) : S[0][0],
                       dev ? 2.0 * mu * (E[1][1] - trd) : S[1][1],
                       dev ? 2.0 * mu * (E[2][2] - trd) : S[2][2],
                       S[0][1],
                       S[0][2],
                       S[1][2]};
  double sa[6] = {0, 0, 0, 0, 0, 0};
#pragma GCC unroll 4
  for (int j = 0; j < NJ; ++j)
#pragma GCC unroll 6
    for (int k = 0; k < 6; ++k) {
      const double h = p.aa[j] * w.hl[6 * j + k][l] + p.cc[j] * (x[k] - w.xl[k][l]);
      w.hl[6 * j + k][l] = h;
      sa[k] += p.al[j] * h;
    }
#pragma GCC unroll 6
  for (int k = 0; k < 6; ++k) w.xl[k][l] = x[k];
  add_voigt(S, sa[0], sa[1], sa[2], sa[3], sa[4], sa[5]);
}

/// The nodal forces of lane l: V P = V (I + H) S, f_j = V P a_j, f_0 = -(f_1 + f_2 + f_3).
inline void nodal_forces(double V, const double (&H)[3][3], const double (&S)[3][3], const double* a, int l,
                         GroupScratch& w) {
  double P[3][3];
#pragma GCC unroll 3
  for (int i = 0; i < 3; ++i)
#pragma GCC unroll 3
    for (int k = 0; k < 3; ++k)
      P[i][k] = V * (S[i][k] + H[i][0] * S[0][k] + H[i][1] * S[1][k] + H[i][2] * S[2][k]);
#pragma GCC unroll 3
  for (int i = 0; i < 3; ++i) {
    double s0 = 0.0;
#pragma GCC unroll 3
    for (int j = 1; j < 4; ++j) {
      const double v = P[i][0] * a[(3 * (j - 1)) * kL + l] + P[i][1] * a[(3 * (j - 1) + 1) * kL + l] +
                       P[i][2] * a[(3 * (j - 1) + 2) * kL + l];
      w.fo[3 * j + i][l] = v;
      s0 += v;
    }
    w.fo[i][l] = -s0;
  }
}

/// The forces of every lane of a group: H, E, S of the law (plus the trial force's S_hist or the
/// fused Prony step of NJ terms), the nodal forces.
template <int M, int NJ, bool DEV>
inline void group_forces(const double* a, const double* V, double lam, double mu, const PaddedPronyStep& p,
                         GroupScratch& w) {
  for (int l = 0; l < kL; ++l) {
    double H[3][3];
    displacement_gradient<M>(w, a, l, H);
    double E[3][3];
    green_lagrange(H, E);
    double S[3][3];
    if constexpr (M == kNeoHookean) {
      neo_hookean_pk2(E, lam, mu, w.lnj[l], S);
    } else {
      stvk_pk2(E, lam, mu, S);
      if constexpr (M == kFusedPk2) prony_step<NJ, DEV>(E, mu, p, l, w, S);
      if constexpr (M == kStVKTrial)
        add_voigt(S, w.sv[0][l], w.sv[1][l], w.sv[2][l], w.sv[3][l], w.sv[4][l], w.sv[5][l]);
    }
    nodal_forces(V[l], H, S, a, l, w);
  }
}

/// Row-wise copies of a group's lane-order blocks (R1 and R2 rows of kL doubles) into and out of the
/// scratch: one row (one SIMD register) at a time, inlined as vector moves (a single copy of the
/// whole block compiles to a call of memmove, measured at 17 % of the fused pass).
template <int R1, int R2>
inline void copy_rows(const double* __restrict a, const double* __restrict b, double (&ra)[6 * kT][kL],
                      double (&rb)[6][kL]) {
  for (int r = 0; r < R1; ++r)
    for (int l = 0; l < kL; ++l) ra[r][l] = a[r * kL + l];
  for (int r = 0; r < R2; ++r)
    for (int l = 0; l < kL; ++l) rb[r][l] = b[r * kL + l];
}
template <int R1, int R2>
inline void copy_rows(const double (&ra)[6 * kT][kL], const double (&rb)[6][kL], double* __restrict a,
                      double* __restrict b) {
  for (int r = 0; r < R1; ++r)
    for (int l = 0; l < kL; ++l) a[r * kL + l] = ra[r][l];
  for (int r = 0; r < R2; ++r)
    for (int l = 0; l < kL; ++l) b[r * kL + l] = rb[r][l];
}

/// Adds the lanes' nodal forces into f (dest ds [4][l] >= 0) or the part's shared row sh (< 0).
inline void scatter(const std::int32_t* ds, const GroupScratch& w, double* f, double* sh) {
  for (int l = 0; l < kL; ++l)
    for (int p = 0; p < 4; ++p) {
      const std::int32_t d = ds[p * kL + l];
      double* t = d >= 0 ? f + d : sh + (-1 - d);
      t[0] += w.fo[3 * p][l];
      t[1] += w.fo[3 * p + 1][l];
      t[2] += w.fo[3 * p + 2][l];
    }
}

}  // namespace

template <int M, int NJ, bool DEV>
void FastTetForce::run_part(int part, const double* u, const Args& args, double* f) const {
  double* sh = shared_.data() + static_cast<std::size_t>(part) * shared_stride_;
  std::fill(sh, sh + shared_stride_, 0.0);
  GroupScratch w;
  PaddedPronyStep prony;
  if constexpr (M == kFusedPk2) prony = padded(*args.step);
  for (int g = part_begin_[static_cast<std::size_t>(part)];
       g < part_begin_[static_cast<std::size_t>(part) + 1]; ++g) {
    const std::size_t gs = static_cast<std::size_t>(g);
    const double* a = &grad_[gs * 9 * kL];
    gather_edges(u, &node_[gs * 4 * kL], w);
    if constexpr (M == kStVKTrial) load_trial_history(args.s_hist + gs * 6 * kL, w);
    if constexpr (M == kNeoHookean) neo_hookean_stage1(a, w);
    // fused pk2: the group's history and driver, contiguous blocks in lane order, copied in and out
    // (plain vector copies; the lane loop then works on the local scratch only)
    double* hg = M == kFusedPk2 ? args.hist + gs * (6 * NJ) * kL : nullptr;
    double* xg = M == kFusedPk2 ? args.driver + gs * 6 * kL : nullptr;
    if constexpr (M == kFusedPk2) copy_rows<6 * NJ, 6>(hg, xg, w.hl, w.xl);
    group_forces<M, NJ, DEV>(a, &vol_[gs * kL], args.lam, args.mu, prony, w);
    if constexpr (M == kFusedPk2) copy_rows<6 * NJ, 6>(w.hl, w.xl, hg, xg);
    scatter(&dest_[gs * 4 * kL], w, f, sh);
  }
}

template <int M, int NJ, bool DEV>
void FastTetForce::evaluate(const VecX& u, const Args& args, VecX& f) const {
  if (u.size() != 3 * static_cast<Eigen::Index>(num_nodes_))
    throw Error("fast force: u has " + std::to_string(u.size()) + " entries, expected " +
                std::to_string(3 * static_cast<long>(num_nodes_)));
  f.setZero(3 * static_cast<Eigen::Index>(num_nodes_));
  const double* up = u.data();
  double* fp = f.data();
  pool_->run(kParts, [&](int k) { run_part<M, NJ, DEV>(k, up, args, fp); });
  // Shared nodes: the parts' partial sums, added in part order (the same for any thread count).
  for (std::size_t s = 0; s < shared_nodes_.size(); ++s)
    for (int c = 0; c < 3; ++c) {
      double v = 0.0;
      for (int k = 0; k < kParts; ++k) v += shared_[static_cast<std::size_t>(k) * shared_stride_ + 3 * s + c];
      fp[3 * static_cast<std::ptrdiff_t>(shared_nodes_[s]) + c] = v;
    }
}

void FastTetForce::internal_force(const VecX& u, VecX& f) const {
  Args args;
  args.lam = lambda_;
  args.mu = mu_;
  if (law_ == FastLaw::StVK)
    evaluate<kStVK>(u, args, f);
  else
    evaluate<kNeoHookean>(u, args, f);
}

void FastTetForce::trial_force_pk2(const VecX& u, double lambda_eff, double mu_eff, const double* s_hist,
                                   VecX& f) const {
  if (law_ != FastLaw::StVK) throw Error("fast force: the pk2 trial force is St Venant-Kirchhoff only");
  Args args;
  args.lam = lambda_eff;
  args.mu = mu_eff;
  args.s_hist = s_hist;
  evaluate<kStVKTrial>(u, args, f);
}

void FastTetForce::force_and_commit_pk2(const VecX& u, const PronyStep& step, double* hist, double* driver,
                                        VecX& f) const {
  if (law_ != FastLaw::StVK) throw Error("fast force: the fused pk2 step is St Venant-Kirchhoff only");
  if (step.terms < 0 || step.terms > PronyStep::kMaxTerms)
    throw Error("fast force: the fused pk2 step takes at most " + std::to_string(PronyStep::kMaxTerms) +
                " Prony terms (got " + std::to_string(step.terms) + ")");
  Args args;
  args.lam = lambda_;
  args.mu = mu_;
  args.step = &step;
  args.hist = hist;
  args.driver = driver;
  if (step.deviatoric)
    fused_pk2<true>(step.terms, u, args, f);
  else
    fused_pk2<false>(step.terms, u, args, f);
}

template <bool DEV>
void FastTetForce::fused_pk2(int terms, const VecX& u, const Args& args, VecX& f) const {
  switch (terms) {  // the number of terms a compile-time constant of the lane loop
    case 0:
      evaluate<kFusedPk2, 0, DEV>(u, args, f);
      break;
    case 1:
      evaluate<kFusedPk2, 1, DEV>(u, args, f);
      break;
    case 2:
      evaluate<kFusedPk2, 2, DEV>(u, args, f);
      break;
    case 3:
      evaluate<kFusedPk2, 3, DEV>(u, args, f);
      break;
    default:
      evaluate<kFusedPk2, 4, DEV>(u, args, f);
      break;
  }
}

std::vector<std::int32_t> FastTetForce::tet_slots() const {
  std::vector<std::int32_t> slot(static_cast<std::size_t>(num_tets_), -1);
  for (std::size_t s = 0; s < tet_.size(); ++s)
    if (tet_[s] >= 0) slot[static_cast<std::size_t>(tet_[s])] = static_cast<std::int32_t>(s);
  return slot;
}

}  // namespace tmlab::tm

namespace tmlab::tm {

namespace {
Law fast_law(FastLaw law, double lambda, double mu) {
  if (law == FastLaw::StVK) return Law(StVenantKirchhoff{lambda, mu});
  return Law(NeoHookean(lambda, mu));
}
}  // namespace

FastHyperelastic::FastHyperelastic(const Mesh& mesh, FastLaw law, double lambda, double mu, int threads)
    : tl_(mesh, fast_law(law, lambda, mu)), fast_(mesh, law, lambda, mu, threads) {}

}  // namespace tmlab::tm
