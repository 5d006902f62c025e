// ViscoelasticBase: what every Prony-series viscoelastic model keeps whatever its driver X_e is (the
// nodal forces or the PK2 stress of ViscoelasticStVK, viscoelastic_model.hpp; the PK2 stress of any
// law in ViscoelasticHyperelastic, viscoelastic_law.hpp). One copy of the step and commit
// bookkeeping both models share (docs/theory/viscoelasticity.md):
//
//   committed history  h_j^c per tet and term, driver X_e^c per tet (width values each), advanced
//                      only by a commit (an accepted step):
//                        h_j^{n+1} = a_j h_j^n + c_j (X_e^{n+1} - X_e^n),  X_e^c <- X_e^{n+1}
//   trial step         begin_step(dt) fixes (a_j, c_j) = recursion_factors(integration, dt, tau_j)
//                      (core/constitutive/prony.hpp) and the gain g = sum_j alpha_j c_j; the trial
//                      histories at a driver x are h_j(x) = a_j h_j^c + c_j (x - X_e^c), and the
//                      constant part of the trial response X_hist = sum_j alpha_j (a_j h_j^c - c_j X_e^c).
//                      A commit resets the trial step to dt = 0.
//   energies           at a commit with bookkeeping: the branch energy sum_j Psi_j and the
//                      dissipation rate D = sum_j 2 Psi_j / tau_j of the new history (each model's
//                      branch_form), the step dissipation dt/2 (D^n + D^{n+1}) (trapezoidal, >= 0)
//                      and its running total; the long-term spring W_e(u_c) is computed only when
//                      asked for, from a copy of the committed u (the same function of the same u:
//                      identical bit for bit).
//   checkpoints        committed_state() / restore_committed_state() in the layout of
//                      committed_state.hpp.
//   storage order      mesh order [t][j][k] by default; a model whose fused pass runs on
//                      FastTetForce keeps it in the kernel's lane order instead (use_lane_order:
//                      [group][j width + k][lane], so the pass streams it with vector loads). Every
//                      value is the same in either order; what leaves the model (committed_history(),
//                      committed_driver(), committed_state()) is always in mesh order.
//
// A derived model gives the long-term spring energy, the per-tet driver and branch quadratic form,
// and what its constant trial parts do when the step changes (trial_changed()); a fused pass of its
// own (ViscoelasticStVK::force_and_commit) uses begin_commit / commit_tet / finish_commit.
#pragma once

#include "core/constitutive/prony.hpp"
#include "tensormass/kernels/elastic_model.hpp"
#include "tensormass/viscoelastic/prony_series.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace tmlab::tm {

/// The names of the choices are the shared vocabulary (core/constitutive/prony.hpp).
struct ViscoelasticOptions {
  using History = PronyHistory;
  using Integration = PronyIntegration;
  using Relaxation = PronyRelaxation;

  History history = History::Pk2;
  Integration integration = Integration::Midpoint;
  Relaxation relaxation = Relaxation::Full;
  /// Keep the committed energies and the dissipation. Every commit updates the branch energies and
  /// the dissipation rate (the trapezoidal dissipation needs the rate at every commit); the
  /// long-term spring energy W_e(u_c) is computed only when it is asked for
  /// (committed_elastic_energy(), committed_state()), from a copy of the committed u, so a run that
  /// records every k-th step pays for it every k-th step. Off: none of it (long explicit runs that
  /// report no energies).
  bool energy_bookkeeping = true;
  /// 0: the trial force on the reference per-tet kernels (results bit-identical to earlier versions).
  /// N >= 1: on FastTetForce (kernels/fast_force.hpp) with N threads: equal to the reference to
  /// round-off (1e-12 relative, tested), several times faster (docs/performance.md).
  int fast_threads = 0;

  /// "nodal_force" | "pk2", "midpoint" | "exact_linear" | "backward_euler", "full" | "deviatoric"
  /// (the shared parsers of prony.hpp). Throw tmlab::Error naming the accepted values.
  static History parse_history(const std::string& s);
  static Integration parse_integration(const std::string& s);
  static Relaxation parse_relaxation(const std::string& s);
  /// tmlab::to_string of prony.hpp, kept here for the model's users.
  static std::string to_string(History h) { return tmlab::to_string(h); }
  static std::string to_string(Integration i) { return tmlab::to_string(i); }
  static std::string to_string(Relaxation r) { return tmlab::to_string(r); }
};

using tmlab::recursion_factors;
using tmlab::RecursionFactors;

class ViscoelasticBase : public ElasticModel {
 public:
  const PronySeries& prony() const { return prony_; }
  const ViscoelasticOptions& options() const { return options_; }

  /// Stored free energy of the trial state at u: the long-term spring W_e(u) plus the branch
  /// energies of the trial histories h_j(X_e(u)), joules (not the potential of the trial force).
  double energy(const VecX& u) const override;

  bool has_history() const override { return true; }
  /// Fixes the trial factors and gain for a step dt; throws tmlab::Error unless dt >= 0 is finite.
  void begin_step(double dt) override;
  /// Accepts the step ending at u: every tet's history advanced with its driver X_e(u), the
  /// energy bookkeeping, then the trial step reset to dt = 0.
  void commit_step(const VecX& u) override;
  /// hist, driver, then the committed energies, rate and dissipations (committed_state.hpp).
  std::vector<double> committed_state() const override;
  /// The inverse of committed_state(); the trial step is reset to dt = 0 (as after a commit).
  void restore_committed_state(const std::vector<double>& state) override;

  /// The current trial step size (0 after construction and after every commit).
  double trial_dt() const { return dt_; }
  /// g = sum_j alpha_j c_j of the trial step (0 for an elastic series).
  double trial_gain() const { return gain_; }

  // ---- committed state and energy bookkeeping (updated by each commit) ----
  /// W_e(u_c), the long-term spring at the last commit (computed on the first call after a commit:
  /// the same function of the same u as at the commit, so the value is identical bit for bit).
  double committed_elastic_energy() const;
  double committed_branch_energy() const { return committed_branch_; }   ///< sum of Psi_j at commit
  double step_dissipation() const { return step_dissipation_; }          ///< of the last commit, >= 0
  double total_dissipation() const { return total_dissipation_; }        ///< sum over commits
  double committed_dissipation_rate() const { return committed_rate_; }  ///< D at the last commit, W
  /// Raw committed history h_j^c per tet [t][j][k], k < history_width(), and the committed driver
  /// X_e^c per tet [t][k], in mesh order (copies, whatever the storage order).
  std::vector<double> committed_history() const;
  std::vector<double> committed_driver() const;
  /// Number of history components per tet and term (12: nodal forces, 6: a Voigt stress).
  int history_width() const { return static_cast<int>(width_); }

 protected:
  ViscoelasticBase(PronySeries prony, ViscoelasticOptions options);
  /// Zero committed history and drivers for num_tets tets of `width` components (the derived
  /// constructor calls it, then begin_step(0)).
  void allocate_history(std::size_t num_tets, std::size_t width);

  /// The long-term spring's energy W_e(u).
  virtual double long_term_energy(const VecX& u) const = 0;
  /// The driver X_e of tet t at u (history_width() <= kMaxWidth values).
  virtual void driver(std::size_t t, const VecX& u, double* x) const = 0;
  /// The branch energy sum_j Psi_j of tet t for the histories h [j][k] (returned) and the
  /// dissipation rate sum_j 2 Psi_j / tau_j (in *rate).
  virtual double branch_form(std::size_t t, const double* h, double* rate) const = 0;
  /// begin_step or a commit changed the trial factors: the model's constant trial parts (built
  /// with history_part) are out of date.
  virtual void trial_changed() = 0;

  bool elastic_only() const { return elastic_only_; }  ///< every Prony weight zero
  const RecursionFactors& factors(std::size_t j) const { return factors_[j]; }

  /// psi = sum_j alpha_j/2 q_j and *rate = sum_j alpha_j q_j / tau_j, q_j = q(h + j width) the
  /// branch quadratic form of term j (each model's compliance).
  template <class QuadraticForm>
  double branch_sums(const double* h, double* rate, const QuadraticForm& q) const {
    double psi = 0.0, d = 0.0;
    for (std::size_t j = 0; j < prony_.size(); ++j) {
      const double qj = q(h + j * width_);
      psi += 0.5 * prony_.alpha(j) * qj;
      d += prony_.alpha(j) * qj / prony_.tau(j);
    }
    *rate = d;
    return psi;
  }

  /// X_hist of tet t: out[k] = sum_j alpha_j (a_j h_j^c[k] - c_j X_e^c[k]), k < width.
  void history_part(std::size_t t, double* out) const;
  /// The branch energy of tet t in the trial state at driver x (the trial histories h_j(x), in the
  /// scratch `h` of prony().size() * width values).
  double trial_branch_energy(std::size_t t, const double* x, double* h) const;

  /// The start of a commit at u: the long-term spring of u deferred (with bookkeeping). False for an
  /// elastic series, whose commit ends here (step dissipation 0, dt = 0).
  bool begin_commit(const VecX& u);
  /// The history update of tet t with its new driver x, and (with bookkeeping) its branch energy
  /// and dissipation rate added to psi and rate.
  void commit_tet(std::size_t t, const double* x, double& psi, double& rate);
  /// The width of the widest driver (a tet's 12 nodal forces).
  static constexpr std::size_t kMaxWidth = 12;

  /// The end of a commit: the dissipation bookkeeping from psi and rate (`book`), then the trial
  /// step reset to dt = 0.
  void finish_commit(bool book, double psi, double rate);
  /// Store the committed history and drivers in a kernel's lane order from now on (values kept):
  /// tet t at slot slots[t] < num_slots, slot s = lanes g + l, the history at
  /// [g][j width + k][l] and the driver at [g][k][l]; slots without a tet hold zeros.
  void use_lane_order(int lanes, std::vector<std::int32_t> slots, std::size_t num_slots);
  /// The committed storage in its storage order, for a kernel that updates it in place
  /// (FastTetForce's fused pass, after use_lane_order with the kernel's slots).
  double* history_data() { return hist_.data(); }
  double* driver_data() { return driver_.data(); }
  /// Where component k of tet t's driver is in the driver's storage order (of driver_size()
  /// values): per-tet arrays of the driver's width in the same order use it too.
  std::size_t driver_index(std::size_t t, std::size_t k) const { return driver_at(t) + k * lanes_; }
  std::size_t driver_size() const { return driver_.size(); }

 private:
  /// Where tet t's values start in hist_ and driver_ (component c at + c lanes_).
  std::size_t hist_at(std::size_t t) const;
  std::size_t driver_at(std::size_t t) const;
  /// Mesh order [t][c] (per tet `per_tet` values) from the storage order, and back.
  std::vector<double> to_mesh_order(const std::vector<double>& stored, std::size_t per_tet, bool hist) const;
  void from_mesh_order(const std::vector<double>& mesh, std::size_t per_tet, bool hist,
                       std::vector<double>& stored) const;

  PronySeries prony_;
  ViscoelasticOptions options_;
  bool elastic_only_ = false;
  std::size_t num_tets_ = 0, width_ = 0;

  // storage order: lanes_ = 1 and no slots_: mesh order; else the lane order of use_lane_order
  std::size_t lanes_ = 1;
  std::vector<std::int32_t> slots_;  ///< slot of each tet (empty: slot t)

  // committed
  std::vector<double> hist_;                ///< [t][j][k] in storage order
  std::vector<double> driver_;              ///< [t][k] in storage order
  std::vector<double> tet_hist_;            ///< commit_tet's scratch: one tet's new h_j [j][k]
  mutable double committed_elastic_ = 0.0;  ///< valid unless spring_stale_
  double committed_branch_ = 0.0, committed_rate_ = 0.0;
  double step_dissipation_ = 0.0, total_dissipation_ = 0.0;
  VecX committed_u_;                   ///< u of the last commit while its spring energy is pending
  mutable bool spring_stale_ = false;  ///< committed_elastic_ is still to be computed from committed_u_

  // trial
  double dt_ = 0.0;
  double gain_ = 0.0;  ///< g = sum alpha_j c_j
  std::vector<RecursionFactors> factors_;
};

}  // namespace tmlab::tm
