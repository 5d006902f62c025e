// Shared by the tensor-mass tests: every output of TensorMassStVK against the TL oracle.
#pragma once

#include "tensormass/kernels/tensor_mass.hpp"
#include "tensormass/kernels/tl_oracle.hpp"
#include "tensormass/testing/test_meshes.hpp"

#include <algorithm>
#include <cstdio>
#include <string>

namespace tmlab::tm::testing {

struct OracleErrors {
  double energy = 0, force = 0, tangent_apply = 0, tangent = 0, tet_force = 0;
  double max() const { return std::max({energy, force, tangent_apply, tangent, tet_force}); }
};

/// Norm-wise relative differences ||x_tm - x_oracle|| / ||x_oracle|| of all kernel outputs at u.
inline OracleErrors compare_with_oracle(const TensorMassStVK& tm, const TotalLagrangianStVK& tl,
                                        const VecX& u, const std::string& label, std::mt19937& rng,
                                        bool assembled = true) {
  OracleErrors r;
  r.energy = rel_err(tm.energy(u), tl.energy(u));
  VecX f1, f2;
  tm.internal_force(u, f1);
  tl.internal_force(u, f2);
  r.force = rel_err(f1, f2);
  const VecX v = random_displacement(tm.num_nodes(), 1.0, rng);
  tm.tangent_apply(u, v, f1);
  tl.tangent_apply(u, v, f2);
  r.tangent_apply = rel_err(f1, f2);
  if (assembled) {
    SpMat K1, K2;
    tm.tangent(u, K1);
    tl.tangent(u, K2);
    r.tangent = rel_err(K1, K2);
  }
  double num = 0, den = 0;
  for (Index t = 0; t < tm.num_tets(); t += std::max<Index>(1, tm.num_tets() / 200)) {
    num = std::max(num, (tm.tet_force(t, u) - tl.tet_force(t, u)).norm());
    den = std::max(den, tl.tet_force(t, u).norm());
  }
  r.tet_force = num / den;
  std::printf("%-34s rel. err: energy %.1e force %.1e K*v %.1e K %.1e tet_force %.1e\n", label.c_str(),
              r.energy, r.force, r.tangent_apply, r.tangent, r.tet_force);
  return r;
}

}  // namespace tmlab::tm::testing
