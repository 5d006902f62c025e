// Picinbono's mesh-level tensor storage evaluated on absolute displacements (the paper's form);
// see picinbono_storage.hpp. Tensors are the corrected ones of docs/theory/seed-errata.md, eq. 3.
#include "tensormass/kernels/picinbono_storage.hpp"

#include "tensormass/kernels/tet_geometry.hpp"

#include <algorithm>
#include <cassert>

namespace tmlab::tm {

namespace {

using Key2 = std::array<Index, 2>;
using Key3 = std::array<Index, 3>;

// Term slots, in entity-local vertex positions (vertices of the entity sorted by global index).
// C term (a; b, d): (U_a . C)(U_b . U_d).  D term (a, b)(c, e): D (U_a . U_b)(U_c . U_e).
struct CSlot {
  int a, b, d;
};
struct DSlot {
  int a, b, c, e;
};

constexpr CSlot kEdgeC[4] = {{0, 0, 1}, {1, 0, 0}, {0, 1, 1}, {1, 0, 1}};
constexpr DSlot kEdgeD[4] = {{0, 0, 0, 1}, {0, 0, 1, 1}, {0, 1, 0, 1}, {0, 1, 1, 1}};
constexpr CSlot kTriC[3] = {{0, 1, 2}, {1, 0, 2}, {2, 0, 1}};
constexpr DSlot kTriD[6] = {{0, 0, 1, 2}, {1, 1, 0, 2}, {2, 2, 0, 1},
                            {0, 1, 0, 2}, {0, 1, 1, 2}, {0, 2, 1, 2}};
constexpr DSlot kTetD[3] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}};

CSlot canonical(CSlot s) { return {s.a, std::min(s.b, s.d), std::max(s.b, s.d)}; }
DSlot canonical(DSlot s) {
  int p0 = std::min(s.a, s.b), p1 = std::max(s.a, s.b);
  int q0 = std::min(s.c, s.e), q1 = std::max(s.c, s.e);
  if (q0 < p0 || (q0 == p0 && q1 < p1)) {
    std::swap(p0, q0);
    std::swap(p1, q1);
  }
  return {p0, p1, q0, q1};
}
bool same(CSlot x, CSlot y) { return x.a == y.a && x.b == y.b && x.d == y.d; }
bool same(DSlot x, DSlot y) { return x.a == y.a && x.b == y.b && x.c == y.c && x.e == y.e; }

template <class Slot, int n>
int find_slot(const Slot (&table)[n], Slot s) {
  const Slot c = canonical(s);
  for (int i = 0; i < n; ++i)
    if (same(canonical(table[i]), c)) return i;
  assert(false && "term slot not found");
  return -1;
}

int position(const Index* v, int n, Index g) {
  for (int i = 0; i < n; ++i)
    if (v[i] == g) return i;
  assert(false && "vertex not in entity");
  return -1;
}

inline double dot3(const double* x, const double* y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; }
inline void axpy3(double s, const double* x, double* y) {
  y[0] += s * x[0];
  y[1] += s * x[1];
  y[2] += s * x[2];
}

/// Energy of the C terms (U_a . C)(U_b . U_d) of one entity (absolute displacements U[i]); adds the
/// gradient to g[i] when g != nullptr.
template <int nc>
double eval_c(const CSlot (&cs)[nc], const double (*C)[3], const double* const* U, double* const* g) {
  double w = 0.0;
  for (int i = 0; i < nc; ++i) {
    const CSlot s = cs[i];
    const double uc = dot3(U[s.a], C[i]);
    const double gbd = dot3(U[s.b], U[s.d]);
    w += uc * gbd;
    if (g) {
      axpy3(gbd, C[i], g[s.a]);
      axpy3(uc, U[s.d], g[s.b]);
      axpy3(uc, U[s.b], g[s.d]);
    }
  }
  return w;
}

/// Energy of the D terms D (U_a . U_b)(U_c . U_e) of one entity; gradient as eval_c.
template <int nd>
double eval_d(const DSlot (&ds)[nd], const double* D, const double* const* U, double* const* g) {
  double w = 0.0;
  for (int i = 0; i < nd; ++i) {
    const DSlot s = ds[i];
    const double gab = dot3(U[s.a], U[s.b]);
    const double gce = dot3(U[s.c], U[s.e]);
    w += D[i] * gab * gce;
    if (g) {
      axpy3(D[i] * gce, U[s.b], g[s.a]);
      axpy3(D[i] * gce, U[s.a], g[s.b]);
      axpy3(D[i] * gab, U[s.e], g[s.c]);
      axpy3(D[i] * gab, U[s.c], g[s.e]);
    }
  }
  return w;
}

/// Sum of all terms; gradient into f when f != nullptr.
double evaluate(const std::vector<PicinbonoAbsoluteStVK::VertexTensors>& vertices,
                const std::vector<PicinbonoAbsoluteStVK::EdgeTensors>& edges,
                const std::vector<PicinbonoAbsoluteStVK::TriangleTensors>& triangles,
                const std::vector<PicinbonoAbsoluteStVK::TetTensors>& tets, const VecX& u, double* f) {
  const double* x = u.data();
  double w = 0.0;
  for (std::size_t p = 0; p < vertices.size(); ++p) {
    const auto& T = vertices[p];
    const double* U = x + 3 * p;
    // U^T B_pp U (B symmetric, packed 00 01 02 11 12 22)
    double BU[3];
    BU[0] = T.B[0] * U[0] + T.B[1] * U[1] + T.B[2] * U[2];
    BU[1] = T.B[1] * U[0] + T.B[3] * U[1] + T.B[4] * U[2];
    BU[2] = T.B[2] * U[0] + T.B[4] * U[1] + T.B[5] * U[2];
    const double uc = dot3(U, T.C), uu = dot3(U, U);
    w += dot3(U, BU) + uc * uu + T.D * uu * uu;  // U B U + (U.C)(U.U) + D (U.U)^2
    if (f) {
      double* g = f + 3 * p;
      axpy3(2.0, BU, g);
      axpy3(uu, T.C, g);
      axpy3(2.0 * uc + 4.0 * T.D * uu, U, g);
    }
  }
  for (const auto& T : edges) {
    const double* U[2] = {x + 3 * static_cast<std::ptrdiff_t>(T.v[0]),
                          x + 3 * static_cast<std::ptrdiff_t>(T.v[1])};
    double* g[2] = {nullptr, nullptr};
    if (f) {
      g[0] = f + 3 * static_cast<std::ptrdiff_t>(T.v[0]);
      g[1] = f + 3 * static_cast<std::ptrdiff_t>(T.v[1]);
    }
    double BUq[3];  // U_p^T B U_q
    for (int r = 0; r < 3; ++r) BUq[r] = dot3(&T.B[3 * r], U[1]);
    w += dot3(U[0], BUq);
    if (f) {
      axpy3(1.0, BUq, g[0]);
      for (int c = 0; c < 3; ++c) g[1][c] += T.B[c] * U[0][0] + T.B[3 + c] * U[0][1] + T.B[6 + c] * U[0][2];
    }
    w += eval_c(kEdgeC, T.C, U, f ? g : nullptr) + eval_d(kEdgeD, T.D, U, f ? g : nullptr);
  }
  for (const auto& T : triangles) {
    const double* U[3];
    double* g[3] = {nullptr, nullptr, nullptr};
    for (int i = 0; i < 3; ++i) {
      U[i] = x + 3 * static_cast<std::ptrdiff_t>(T.v[i]);
      if (f) g[i] = f + 3 * static_cast<std::ptrdiff_t>(T.v[i]);
    }
    w += eval_c(kTriC, T.C, U, f ? g : nullptr) + eval_d(kTriD, T.D, U, f ? g : nullptr);
  }
  for (const auto& T : tets) {
    const double* U[4];
    double* g[4] = {nullptr, nullptr, nullptr, nullptr};
    for (int i = 0; i < 4; ++i) {
      U[i] = x + 3 * static_cast<std::ptrdiff_t>(T.v[i]);
      if (f) g[i] = f + 3 * static_cast<std::ptrdiff_t>(T.v[i]);
    }
    w += eval_d(kTetD, T.D, U, f ? g : nullptr);
  }
  return w;
}

}  // namespace

PicinbonoAbsoluteStVK::PicinbonoAbsoluteStVK(const Mesh& mesh, const StVenantKirchhoff& material) {
  const std::vector<TetRest> rest = compute_tet_rest(mesh);
  const auto nt = mesh.tets.size();
  vertices_.assign(static_cast<std::size_t>(mesh.num_points()), VertexTensors{});

  // Mesh entities: edges and triangles (sorted vertex keys), tets with sorted vertices.
  std::vector<Key2> ekeys;
  std::vector<Key3> tkeys;
  ekeys.reserve(6 * nt);
  tkeys.reserve(4 * nt);
  for (const Tet& tet : mesh.tets) {
    Tet s = tet;
    std::sort(s.begin(), s.end());
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) ekeys.push_back({s[i], s[j]});
    for (int m = 0; m < 4; ++m) {  // triangle without s[m]
      Key3 k{};
      int c = 0;
      for (int i = 0; i < 4; ++i)
        if (i != m) k[c++] = s[i];
      tkeys.push_back(k);
    }
  }
  std::sort(ekeys.begin(), ekeys.end());
  ekeys.erase(std::unique(ekeys.begin(), ekeys.end()), ekeys.end());
  std::sort(tkeys.begin(), tkeys.end());
  tkeys.erase(std::unique(tkeys.begin(), tkeys.end()), tkeys.end());
  edges_.assign(ekeys.size(), EdgeTensors{});
  for (std::size_t i = 0; i < ekeys.size(); ++i) {
    edges_[i].v[0] = ekeys[i][0];
    edges_[i].v[1] = ekeys[i][1];
  }
  triangles_.assign(tkeys.size(), TriangleTensors{});
  for (std::size_t i = 0; i < tkeys.size(); ++i)
    for (int c = 0; c < 3; ++c) triangles_[i].v[c] = tkeys[i][static_cast<std::size_t>(c)];
  tets_.assign(nt, TetTensors{});

  const double lam = material.lambda, mu = material.mu;
  for (std::size_t t = 0; t < nt; ++t) {
    const Tet& tet = mesh.tets[t];
    const TetRest& r = rest[t];
    const double V = r.volume;
    const auto& a = r.grad;
    double d[4][4];
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k) d[j][k] = a[j].dot(a[k]);

    // Entity of a set of local vertices, by bit mask: edges (2 bits), triangles (3 bits).
    std::size_t ent[16] = {};
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        const Key2 k{std::min(tet[i], tet[j]), std::max(tet[i], tet[j])};
        ent[(1 << i) | (1 << j)] =
            static_cast<std::size_t>(std::lower_bound(ekeys.begin(), ekeys.end(), k) - ekeys.begin());
      }
    for (int m = 0; m < 4; ++m) {
      Key3 k{};
      int c = 0;
      for (int i = 0; i < 4; ++i)
        if (i != m) k[c++] = tet[i];
      std::sort(k.begin(), k.end());
      ent[15 & ~(1 << m)] =
          static_cast<std::size_t>(std::lower_bound(tkeys.begin(), tkeys.end(), k) - tkeys.begin());
    }
    TetTensors& TT = tets_[t];
    for (int i = 0; i < 4; ++i) TT.v[i] = tet[i];
    std::sort(TT.v, TT.v + 4);

    // B_jk = V [ lambda/2 a_j (x) a_k + mu/2 ( a_k (x) a_j + (a_j . a_k) I ) ]   (errata eq. 3)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k) {
        Mat3 B = V * (0.5 * lam * a[j] * a[k].transpose() +
                      0.5 * mu * (a[k] * a[j].transpose() + d[j][k] * Mat3::Identity()));
        if (j == k) {
          VertexTensors& VT = vertices_[static_cast<std::size_t>(tet[j])];
          VT.B[0] += B(0, 0);
          VT.B[1] += B(0, 1);
          VT.B[2] += B(0, 2);
          VT.B[3] += B(1, 1);
          VT.B[4] += B(1, 2);
          VT.B[5] += B(2, 2);
        } else {
          EdgeTensors& ET = edges_[ent[(1 << j) | (1 << k)]];
          if (tet[j] != ET.v[0]) B.transposeInPlace();  // U_q^T B U_p = U_p^T B^T U_q
          for (int x = 0; x < 3; ++x)
            for (int y = 0; y < 3; ++y) ET.B[3 * x + y] += B(x, y);
        }
      }
    // C_jkl = V [ lambda/2 a_j (a_k.a_l) + mu/2 ( a_l (a_j.a_k) + a_k (a_j.a_l) ) ], all ordered (j,k,l)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k)
        for (int l = 0; l < 4; ++l) {
          const Vec3 C = V * (0.5 * lam * a[j] * d[k][l] + 0.5 * mu * (a[l] * d[j][k] + a[k] * d[j][l]));
          const int mask = (1 << j) | (1 << k) | (1 << l);
          const int nbits = __builtin_popcount(static_cast<unsigned>(mask));
          double* dst = nullptr;
          if (nbits == 1) {
            dst = vertices_[static_cast<std::size_t>(tet[j])].C;
          } else if (nbits == 2) {
            EdgeTensors& ET = edges_[ent[mask]];
            const CSlot s{position(ET.v, 2, tet[j]), position(ET.v, 2, tet[k]), position(ET.v, 2, tet[l])};
            dst = ET.C[find_slot(kEdgeC, s)];
          } else {
            TriangleTensors& TR = triangles_[ent[mask]];
            const CSlot s{position(TR.v, 3, tet[j]), position(TR.v, 3, tet[k]), position(TR.v, 3, tet[l])};
            dst = TR.C[find_slot(kTriC, s)];
          }
          for (int c = 0; c < 3; ++c) dst[c] += C(c);
        }
    // D_jklm = V [ lambda/8 (a_j.a_k)(a_l.a_m) + mu/4 (a_j.a_m)(a_k.a_l) ], all ordered (j,k,l,m)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k)
        for (int l = 0; l < 4; ++l)
          for (int m = 0; m < 4; ++m) {
            const double D = V * (lam / 8.0 * d[j][k] * d[l][m] + mu / 4.0 * d[j][m] * d[k][l]);
            const int mask = (1 << j) | (1 << k) | (1 << l) | (1 << m);
            const int nbits = __builtin_popcount(static_cast<unsigned>(mask));
            if (nbits == 1) {
              vertices_[static_cast<std::size_t>(tet[j])].D += D;
            } else if (nbits == 2) {
              EdgeTensors& ET = edges_[ent[mask]];
              const DSlot s{position(ET.v, 2, tet[j]), position(ET.v, 2, tet[k]), position(ET.v, 2, tet[l]),
                            position(ET.v, 2, tet[m])};
              ET.D[find_slot(kEdgeD, s)] += D;
            } else if (nbits == 3) {
              TriangleTensors& TR = triangles_[ent[mask]];
              const DSlot s{position(TR.v, 3, tet[j]), position(TR.v, 3, tet[k]), position(TR.v, 3, tet[l]),
                            position(TR.v, 3, tet[m])};
              TR.D[find_slot(kTriD, s)] += D;
            } else {
              const DSlot s{position(TT.v, 4, tet[j]), position(TT.v, 4, tet[k]), position(TT.v, 4, tet[l]),
                            position(TT.v, 4, tet[m])};
              TT.D[find_slot(kTetD, s)] += D;
            }
          }
  }
}

std::size_t PicinbonoAbsoluteStVK::storage_bytes() const {
  return vertices_.size() * sizeof(VertexTensors) + edges_.size() * sizeof(EdgeTensors) +
         triangles_.size() * sizeof(TriangleTensors) + tets_.size() * sizeof(TetTensors);
}

double PicinbonoAbsoluteStVK::energy(const VecX& u) const {
  assert(u.size() == num_dofs());
  return evaluate(vertices_, edges_, triangles_, tets_, u, nullptr);
}

void PicinbonoAbsoluteStVK::internal_force(const VecX& u, VecX& f) const {
  assert(u.size() == num_dofs());
  f.setZero(num_dofs());
  evaluate(vertices_, edges_, triangles_, tets_, u, f.data());
}

}  // namespace tmlab::tm
