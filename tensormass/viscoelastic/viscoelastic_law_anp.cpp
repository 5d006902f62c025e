// Prony-series viscoelasticity on the PK2 stress at the averaged deformation gradient of the
// locking-free linear tet; equations in viscoelastic_law_anp.hpp.
#include "tensormass/viscoelastic/viscoelastic_law_anp.hpp"

#include "core/base/error.hpp"

#include <cassert>
#include <limits>

namespace tmlab::tm {

namespace {

inline double voigt_dot(const double* a, const double* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + 2.0 * (a[3] * b[3] + a[4] * b[4] + a[5] * b[5]);
}
inline Mat3 green(const Mat3& F) { return 0.5 * (F.transpose() * F - Mat3::Identity()); }

}  // namespace

ViscoelasticAveragedPressureTet::ViscoelasticAveragedPressureTet(const Mesh& mesh, Law long_term,
                                                                 PronySeries prony,
                                                                 ViscoelasticOptions options)
    : ViscoelasticBase(std::move(prony), options), elastic_(mesh, std::move(long_term)) {
  using Opt = ViscoelasticOptions;
  const std::string law = elastic_.law().name();
  if (options.history != Opt::History::Pk2)
    throw Error(
        "viscoelastic history '" + Opt::to_string(options.history) + "' is not available with law '" + law +
        "' on the p1_anp element (the general-law model relaxes its PK2 stress: use history \"pk2\")");
  if (options.relaxation != Opt::Relaxation::Full)
    throw Error("viscoelastic relaxation '" + Opt::to_string(options.relaxation) +
                "' is not available with the general-law model on the p1_anp element (law '" + law +
                "'): use \"full\"");
  if (options.fast_threads != 0)
    throw Error(
        "viscoelastic fast_threads is not available on the p1_anp element (the fast kernel is plain P1): "
        "use 0");
  c0_ = elastic_.law().small_strain();
  const auto nt = static_cast<std::size_t>(num_tets());
  allocate_history(nt, 6);
  s_hist_.assign(nt * 6, 0.0);
  begin_step(0.0);
}

double ViscoelasticAveragedPressureTet::branch_form(std::size_t t, const double* h, double* rate) const {
  const double V = elastic_.rest_volume(static_cast<Index>(t)), lam = c0_.lambda, mu = c0_.mu;
  // Psi = sum_j alpha_j/2 V h_j : C_0^{-1} : h_j (the P1 model's branch form)
  return branch_sums(h, rate, [&](const double* hj) {
    const double tr = hj[0] + hj[1] + hj[2];
    return V * (voigt_dot(hj, hj) - lam / (3.0 * lam + 2.0 * mu) * tr * tr) / (2.0 * mu);
  });
}

void ViscoelasticAveragedPressureTet::trial_changed() {
  const std::size_t nt = s_hist_.size() / 6;
  for (std::size_t t = 0; t < nt; ++t) history_part(t, &s_hist_[6 * t]);  // S_hist
}

std::vector<double> ViscoelasticAveragedPressureTet::drivers(const VecX& u) const {
  const std::vector<Mat3> fbar = elastic_.averaged_deformation_gradients(u);
  std::vector<double> x(6 * fbar.size());
  for (std::size_t t = 0; t < fbar.size(); ++t)
    to_voigt(elastic_.law().pk2_stress(green(fbar[t])), &x[6 * t]);
  return x;
}

void ViscoelasticAveragedPressureTet::driver(std::size_t t, const VecX& u, double* x) const {
  to_voigt(elastic_.law().pk2_stress(green(elastic_.averaged_deformation_gradient(static_cast<Index>(t), u))),
           x);
}

void ViscoelasticAveragedPressureTet::commit_step(const VecX& u) {
  assert(u.size() == num_dofs());
  if (!begin_commit(u)) return;  // elastic: nothing to advance
  const std::vector<double> x = drivers(u);
  double psi = 0.0, rate = 0.0;
  for (std::size_t t = 0; t < x.size() / 6; ++t) commit_tet(t, &x[6 * t], psi, rate);
  finish_commit(options().energy_bookkeeping, psi, rate);
}

double ViscoelasticAveragedPressureTet::energy(const VecX& u) const {
  const double we = long_term_energy(u);
  if (elastic_only()) return we;
  const std::vector<double> x = drivers(u);
  std::vector<double> h(prony().size() * 6);
  double psi = 0.0;
  for (std::size_t t = 0; t < x.size() / 6; ++t) psi += trial_branch_energy(t, &x[6 * t], h.data());
  return we + psi;
}

double ViscoelasticAveragedPressureTet::trial_potential(const VecX& u) const {
  if (elastic_only()) return elastic_.energy(u);
  return elastic_.energy_with(u, trial());
}

void ViscoelasticAveragedPressureTet::internal_force(const VecX& u, VecX& f) const {
  if (elastic_only()) return elastic_.internal_force(u, f);
  elastic_.internal_force_with(u, f, trial());
}

void ViscoelasticAveragedPressureTet::tangent_apply(const VecX& u, const VecX& v, VecX& Kv) const {
  if (elastic_only()) return elastic_.tangent_apply(u, v, Kv);
  elastic_.tangent_apply_with(u, v, Kv, trial());
}

void ViscoelasticAveragedPressureTet::tangent(const VecX& u, SpMat& K) const {
  if (elastic_only()) return elastic_.tangent(u, K);
  elastic_.tangent_with(u, K, trial());
}

Mat3 ViscoelasticAveragedPressureTet::total_pk2_stress(Index t, const VecX& u) const {
  const Mat3 S_e = elastic_.law().pk2_stress(green(elastic_.averaged_deformation_gradient(t, u)));
  if (elastic_only()) return S_e;
  return (1.0 + trial_gain()) * S_e + from_voigt(&s_hist_[6 * static_cast<std::size_t>(t)]);
}

}  // namespace tmlab::tm
