// Prony-series viscoelasticity on the PK2 stress at the quadrature points of 10-node tets; equations
// in viscoelastic_law_p2.hpp.
#include "tensormass/viscoelastic/viscoelastic_law_p2.hpp"

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

bool ViscoelasticHyperelasticP2::TrialPoint::operator()(Index t, int q, const Mat3& E, double* W, Mat3* S,
                                                        Mat6* D) const {
  const double* sh = s_hist + 6 * (static_cast<std::size_t>(points) * static_cast<std::size_t>(t) +
                                   static_cast<std::size_t>(q));
  double We = 0.0;
  Mat3 Se;
  law->evaluate(E, W ? &We : nullptr, S ? &Se : nullptr, D);
  if (W) {
    double e6[6];
    to_voigt(E, e6);
    *W = (1.0 + g) * We + voigt_dot(sh, e6);
  }
  if (S) *S = (1.0 + g) * Se + from_voigt(sh);
  if (D) *D *= (1.0 + g);
  return true;
}

ViscoelasticHyperelasticP2::ViscoelasticHyperelasticP2(const QuadraticMesh& mesh, Law long_term,
                                                       PronySeries prony, ViscoelasticOptions options,
                                                       P2Options p2)
    : ViscoelasticBase(std::move(prony), options), elastic_(mesh, std::move(long_term), p2) {
  using Opt = ViscoelasticOptions;
  const std::string law = elastic_.law().name();
  if (options.history != Opt::History::Pk2)
    throw Error("viscoelastic history '" + Opt::to_string(options.history) + "' is not available with law '" +
                law +
                "' on 10-node tets (the general-law model relaxes its PK2 stress: use history \"pk2\")");
  if (options.relaxation != Opt::Relaxation::Full)
    throw Error("viscoelastic relaxation '" + Opt::to_string(options.relaxation) +
                "' is not available with the general-law model on 10-node tets (law '" + law +
                "'): use \"full\"");
  if (options.fast_threads != 0)
    throw Error("viscoelastic fast_threads is not available on 10-node tets (the fast kernel is P1): use 0");
  c0_ = elastic_.law().small_strain();
  const std::size_t slots =
      static_cast<std::size_t>(num_tets()) * static_cast<std::size_t>(num_points_per_tet());
  allocate_history(slots, 6);
  s_hist_.assign(slots * 6, 0.0);
  begin_step(0.0);
}

ViscoelasticHyperelasticP2::TrialPoint ViscoelasticHyperelasticP2::trial_point() const {
  return TrialPoint{&elastic_.law(), trial_gain(), s_hist_.data(), num_points_per_tet()};
}

double ViscoelasticHyperelasticP2::branch_form(std::size_t slot, const double* h, double* rate) const {
  const auto np = static_cast<std::size_t>(num_points_per_tet());
  const double V = elastic_.point(static_cast<Index>(slot / np), static_cast<int>(slot % np)).weight;
  const double lam = c0_.lambda, mu = c0_.mu;
  // Psi = sum_j alpha_j/2 V h_j : C_0^{-1} : h_j (the P1 model's branch form, at a point of weight V).
  return branch_sums(h, rate, [&](const double* hj) {
    const double tr = hj[0] + hj[1] + hj[2];
    return V * (voigt_dot(hj, hj) - lam / (3.0 * lam + 2.0 * mu) * tr * tr) / (2.0 * mu);
  });
}

void ViscoelasticHyperelasticP2::trial_changed() {
  const std::size_t slots = s_hist_.size() / 6;
  for (std::size_t s = 0; s < slots; ++s) history_part(s, &s_hist_[6 * s]);
}

void ViscoelasticHyperelasticP2::driver(std::size_t slot, const VecX& u, double* x) const {
  const auto np = static_cast<std::size_t>(num_points_per_tet());
  const auto t = static_cast<Index>(slot / np);
  const int q = static_cast<int>(slot % np);
  if (!elastic_.mean_dilatation()) {  // F_q alone (kinematics() would compute all 14 points)
    to_voigt(elastic_.law().pk2_stress(green(elastic_.point_deformation_gradient(t, q, u))), x);
    return;
  }
  const HyperelasticP2::TetKinematics k = elastic_.kinematics(t, u);
  to_voigt(elastic_.law().pk2_stress(green(k.Fe[static_cast<std::size_t>(q)])), x);
}

double ViscoelasticHyperelasticP2::energy(const VecX& u) const {
  const double we = long_term_energy(u);
  if (elastic_only()) return we;
  const int np = num_points_per_tet();
  std::vector<double> h(prony().size() * 6);
  double x[6], psi = 0.0;
  for (Index t = 0; t < num_tets(); ++t) {
    const HyperelasticP2::TetKinematics k = elastic_.kinematics(t, u);
    for (int q = 0; q < np; ++q) {
      to_voigt(elastic_.law().pk2_stress(green(k.Fe[static_cast<std::size_t>(q)])), x);
      psi += trial_branch_energy(
          static_cast<std::size_t>(np) * static_cast<std::size_t>(t) + static_cast<std::size_t>(q), x,
          h.data());
    }
  }
  return we + psi;
}

void ViscoelasticHyperelasticP2::commit_step(const VecX& u) {
  assert(u.size() == num_dofs());
  if (!begin_commit(u)) return;
  const int np = num_points_per_tet();
  double x[6], psi = 0.0, rate = 0.0;
  for (Index t = 0; t < num_tets(); ++t) {
    const HyperelasticP2::TetKinematics k = elastic_.kinematics(t, u);
    for (int q = 0; q < np; ++q) {
      to_voigt(elastic_.law().pk2_stress(green(k.Fe[static_cast<std::size_t>(q)])), x);
      commit_tet(static_cast<std::size_t>(np) * static_cast<std::size_t>(t) + static_cast<std::size_t>(q), x,
                 psi, rate);
    }
  }
  finish_commit(options().energy_bookkeeping, psi, rate);
}

double ViscoelasticHyperelasticP2::trial_potential(const VecX& u) const {
  if (elastic_only()) return elastic_.energy(u);
  return elastic_.energy_with(u, trial_point());
}

void ViscoelasticHyperelasticP2::internal_force(const VecX& u, VecX& f) const {
  assert(u.size() == num_dofs());
  if (elastic_only()) {
    elastic_.internal_force(u, f);
    return;
  }
  elastic_.internal_force_with(u, f, trial_point());
}

void ViscoelasticHyperelasticP2::tangent_apply(const VecX& u, const VecX& v, VecX& Kv) const {
  assert(u.size() == num_dofs() && v.size() == num_dofs());
  if (elastic_only()) {
    elastic_.tangent_apply(u, v, Kv);
    return;
  }
  elastic_.tangent_apply_with(u, v, Kv, trial_point());
}

void ViscoelasticHyperelasticP2::tangent(const VecX& u, SpMat& K) const {
  if (elastic_only()) {
    elastic_.tangent(u, K);
    return;
  }
  elastic_.tangent_with(u, K, trial_point());
}

Mat3 ViscoelasticHyperelasticP2::mean_pk2_stress(Index t, const VecX& u) const {
  const HyperelasticP2::TetKinematics k = elastic_.kinematics(t, u);
  if (!k.in_domain) return Mat3::Constant(std::numeric_limits<double>::quiet_NaN());
  const TrialPoint tp = trial_point();
  Mat3 s = Mat3::Zero();
  for (int q = 0; q < num_points_per_tet(); ++q) {
    Mat3 S;
    tp(t, q, green(k.Fe[static_cast<std::size_t>(q)]), nullptr, &S, nullptr);
    s += elastic_.point(t, q).weight * S;
  }
  return s / elastic_.tet_volume(t);
}

}  // namespace tmlab::tm
