// The step and commit bookkeeping of the Prony-series viscoelastic models; equations in
// viscoelastic_base.hpp and docs/theory/viscoelasticity.md.
#include "tensormass/viscoelastic/viscoelastic_base.hpp"
#include "tensormass/viscoelastic/committed_state.hpp"

#include "core/base/error.hpp"
#include "core/base/format.hpp"

#include <cassert>
#include <cmath>

namespace tmlab::tm {

// ---------------------------------------------------------------- options

using Opt = ViscoelasticOptions;

Opt::History Opt::parse_history(const std::string& s) {
  if (const auto h = prony_history_from_string(s)) return *h;
  throw Error("viscoelastic history '" + s + "' is unknown (use " + choice_list(prony_history_names(), "\"") +
              ")");
}
Opt::Integration Opt::parse_integration(const std::string& s) {
  if (const auto i = prony_integration_from_string(s)) return *i;
  throw Error("viscoelastic integration '" + s + "' is unknown (use " +
              choice_list(prony_integration_names(), "\"") + ")");
}
Opt::Relaxation Opt::parse_relaxation(const std::string& s) {
  if (const auto r = prony_relaxation_from_string(s)) return *r;
  throw Error("viscoelastic relaxation '" + s + "' is unknown (use " +
              choice_list(prony_relaxation_names(), "\"") + ")");
}

// ---------------------------------------------------------------- construction

ViscoelasticBase::ViscoelasticBase(PronySeries prony, ViscoelasticOptions options)
    : prony_(std::move(prony)), options_(options), elastic_only_(prony_.is_elastic()) {}

void ViscoelasticBase::allocate_history(std::size_t num_tets, std::size_t width) {
  assert(width <= kMaxWidth);
  num_tets_ = num_tets;
  width_ = width;
  lanes_ = 1;
  slots_.clear();
  hist_.assign(num_tets * prony_.size() * width, 0.0);
  driver_.assign(num_tets * width, 0.0);
  tet_hist_.assign(prony_.size() * width, 0.0);
}

// ---------------------------------------------------------------- storage order

std::size_t ViscoelasticBase::hist_at(std::size_t t) const {
  const std::size_t s = slots_.empty() ? t : static_cast<std::size_t>(slots_[t]);
  return (s / lanes_) * (prony_.size() * width_ * lanes_) + s % lanes_;
}

std::size_t ViscoelasticBase::driver_at(std::size_t t) const {
  const std::size_t s = slots_.empty() ? t : static_cast<std::size_t>(slots_[t]);
  return (s / lanes_) * (width_ * lanes_) + s % lanes_;
}

std::vector<double> ViscoelasticBase::to_mesh_order(const std::vector<double>& stored, std::size_t per_tet,
                                                    bool hist) const {
  std::vector<double> mesh(num_tets_ * per_tet);
  for (std::size_t t = 0; t < num_tets_; ++t) {
    const std::size_t b = hist ? hist_at(t) : driver_at(t);
    for (std::size_t c = 0; c < per_tet; ++c) mesh[t * per_tet + c] = stored[b + c * lanes_];
  }
  return mesh;
}

void ViscoelasticBase::from_mesh_order(const std::vector<double>& mesh, std::size_t per_tet, bool hist,
                                       std::vector<double>& stored) const {
  for (std::size_t t = 0; t < num_tets_; ++t) {
    const std::size_t b = hist ? hist_at(t) : driver_at(t);
    for (std::size_t c = 0; c < per_tet; ++c) stored[b + c * lanes_] = mesh[t * per_tet + c];
  }
}

void ViscoelasticBase::use_lane_order(int lanes, std::vector<std::int32_t> slots, std::size_t num_slots) {
  if (lanes < 1 || slots.size() != num_tets_ || num_slots < num_tets_ ||
      num_slots % static_cast<std::size_t>(lanes) != 0)
    throw Error("viscoelastic: a lane order of " + std::to_string(slots.size()) + " slots for " +
                std::to_string(num_tets_) + " tets in " + std::to_string(num_slots) + " slots of " +
                std::to_string(lanes) + " lanes is not a storage order");
  std::vector<bool> used(num_slots, false);
  for (std::int32_t s : slots) {
    if (s < 0 || static_cast<std::size_t>(s) >= num_slots || used[static_cast<std::size_t>(s)])
      throw Error("viscoelastic: lane order slot " + std::to_string(s) + " is outside [0, " +
                  std::to_string(num_slots) + ") or used twice");
    used[static_cast<std::size_t>(s)] = true;
  }
  const std::size_t per_tet = prony_.size() * width_;
  const std::vector<double> h = committed_history(), x = committed_driver();
  lanes_ = static_cast<std::size_t>(lanes);
  slots_ = std::move(slots);
  hist_.assign(num_slots * per_tet, 0.0);
  driver_.assign(num_slots * width_, 0.0);
  from_mesh_order(h, per_tet, true, hist_);
  from_mesh_order(x, width_, false, driver_);
}

std::vector<double> ViscoelasticBase::committed_history() const {
  return slots_.empty() ? hist_ : to_mesh_order(hist_, prony_.size() * width_, true);
}

std::vector<double> ViscoelasticBase::committed_driver() const {
  return slots_.empty() ? driver_ : to_mesh_order(driver_, width_, false);
}

// ---------------------------------------------------------------- trial step

void ViscoelasticBase::begin_step(double dt) {
  if (!(dt >= 0.0) || !std::isfinite(dt))
    throw Error("viscoelastic: step size dt = " + std::to_string(dt) + " must be >= 0");
  dt_ = dt;
  factors_.resize(prony_.size());
  gain_ = 0.0;
  for (std::size_t j = 0; j < prony_.size(); ++j) {
    factors_[j] = recursion_factors(options_.integration, dt, prony_.tau(j));
    gain_ += prony_.alpha(j) * factors_[j].c;  // g = sum_j alpha_j c_j
  }
  if (elastic_only_) {
    gain_ = 0.0;
    return;
  }
  trial_changed();
}

void ViscoelasticBase::history_part(std::size_t t, double* out) const {
  // X_hist = sum_j alpha_j (a_j h_j^c - c_j X_e^c)   (the u-independent part of the trial response)
  const std::size_t nj = prony_.size(), w = width_, L = lanes_;
  const double* X = &driver_[driver_at(t)];
  for (std::size_t k = 0; k < w; ++k) out[k] = 0.0;
  for (std::size_t j = 0; j < nj; ++j) {
    const double al = prony_.alpha(j), a = factors_[j].a, c = factors_[j].c;
    const double* h = &hist_[hist_at(t) + j * w * L];
    for (std::size_t k = 0; k < w; ++k) out[k] += al * (a * h[k * L] - c * X[k * L]);
  }
}

double ViscoelasticBase::trial_branch_energy(std::size_t t, const double* x, double* h) const {
  // h_j(x) = a_j h_j^c + c_j (x - X_e^c)
  const std::size_t nj = prony_.size(), w = width_, L = lanes_;
  const double* X = &driver_[driver_at(t)];
  for (std::size_t j = 0; j < nj; ++j) {
    const double* hc = &hist_[hist_at(t) + j * w * L];
    for (std::size_t k = 0; k < w; ++k)
      h[j * w + k] = factors_[j].a * hc[k * L] + factors_[j].c * (x[k] - X[k * L]);
  }
  double rate = 0.0;
  return branch_form(t, h, &rate);
}

double ViscoelasticBase::energy(const VecX& u) const {
  const double we = long_term_energy(u);
  if (elastic_only_) return we;
  // + branch energies of the trial histories h_j(u) = a_j h_j^c + c_j (X_e(u) - X_e^c)
  std::vector<double> h(prony_.size() * width_);
  double x[kMaxWidth], psi = 0.0;
  for (std::size_t t = 0; t < num_tets_; ++t) {
    driver(t, u, x);
    psi += trial_branch_energy(t, x, h.data());
  }
  return we + psi;
}

// ---------------------------------------------------------------- commit

void ViscoelasticBase::commit_step(const VecX& u) {
  assert(u.size() == num_dofs());
  if (!begin_commit(u)) return;  // elastic: nothing to advance
  double x[kMaxWidth], psi = 0.0, rate = 0.0;
  for (std::size_t t = 0; t < num_tets_; ++t) {
    driver(t, u, x);
    commit_tet(t, x, psi, rate);
  }
  finish_commit(options_.energy_bookkeeping, psi, rate);
}

bool ViscoelasticBase::begin_commit(const VecX& u) {
  if (options_.energy_bookkeeping) {  // the long-term spring W_e(u): computed when asked for
    committed_u_ = u;
    spring_stale_ = true;
  }
  if (elastic_only_) {
    step_dissipation_ = 0.0;
    dt_ = 0.0;
    return false;
  }
  return true;
}

void ViscoelasticBase::commit_tet(std::size_t t, const double* x, double& psi, double& rate) {
  const std::size_t nj = prony_.size(), w = width_, L = lanes_;
  double* X = &driver_[driver_at(t)];
  double* th = tet_hist_.data();  // the tet's new histories, contiguous [j][k] for branch_form
  for (std::size_t j = 0; j < nj; ++j) {
    // h_j^{n+1} = a_j h_j^n + c_j (X_e^{n+1} - X_e^n)   (eq. 20 family)
    double* h = &hist_[hist_at(t) + j * w * L];
    const double a = factors_[j].a, c = factors_[j].c;
    for (std::size_t k = 0; k < w; ++k) {
      th[j * w + k] = a * h[k * L] + c * (x[k] - X[k * L]);
      h[k * L] = th[j * w + k];
    }
  }
  for (std::size_t k = 0; k < w; ++k) X[k * L] = x[k];
  if (options_.energy_bookkeeping) {
    double r = 0.0;
    psi += branch_form(t, th, &r);
    rate += r;
  }
}

void ViscoelasticBase::finish_commit(bool book, double psi, double rate) {
  if (book) {
    // Trapezoidal quadrature of the dissipation rate over the step (>= 0: both rates are >= 0).
    step_dissipation_ = 0.5 * dt_ * (committed_rate_ + rate);
    total_dissipation_ += step_dissipation_;
    committed_rate_ = rate;
    committed_branch_ = psi;
  }
  begin_step(0.0);  // the trial at dt = 0: internal_force(u) is now the committed total force
}

// ---------------------------------------------------------------- checkpoints

double ViscoelasticBase::committed_elastic_energy() const {
  if (spring_stale_) {
    committed_elastic_ = long_term_energy(committed_u_);
    spring_stale_ = false;
  }
  return committed_elastic_;
}

std::vector<double> ViscoelasticBase::committed_state() const {
  return pack_committed_state(committed_history(), committed_driver(),  // mesh order: the same bytes
                              {committed_elastic_energy(), committed_branch_, committed_rate_,
                               step_dissipation_, total_dissipation_});
}

void ViscoelasticBase::restore_committed_state(const std::vector<double>& s) {
  std::vector<double> h(num_tets_ * prony_.size() * width_), x(num_tets_ * width_);  // mesh order
  const CommittedEnergies e = unpack_committed_state(s, h, x);
  from_mesh_order(h, prony_.size() * width_, true, hist_);
  from_mesh_order(x, width_, false, driver_);
  committed_elastic_ = e.elastic;
  spring_stale_ = false;
  committed_branch_ = e.branch;
  committed_rate_ = e.rate;
  step_dissipation_ = e.step_dissipation;
  total_dissipation_ = e.total_dissipation;
  begin_step(0.0);  // the trial state a commit leaves behind
}

}  // namespace tmlab::tm
