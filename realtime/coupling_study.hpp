// The haptic couplings measured against ground truth, deterministically (docs/realtime.md).
//
// Ground truth: the control model stepped at the HAPTIC rate with the probe position of every
// haptic tick: F_true(t_n) = force on the probe at (u^n, x(t_n)). A haptic tick dt_h is `substeps`
// model steps (the explicit step's stable limit on the liver is ~1 ms at the instantaneous modulus,
// so a 1 kHz tick takes two 0.5 ms steps).
//
// Multi-rate run (the paper's set-up, control N times slower than haptic): the control thread
// starts a block at tick kN with the probe position c_k = x(t_kN) it reads then, steps through N
// ticks with the probe held at c_k (it does not know where the probe goes next), and publishes the
// state of time t_(k+1)N at that time (the block took one control period). Haptic ticks n in
// [(k+1)N, (k+2)N) render from that snapshot with each coupling; before the first snapshot both
// render 0. The difference from the ground truth is then the coupling's alone: same model, same
// dt, same probe path.
//
// Metrics per scheme:
//   force_error_rel    sqrt(sum_n |F_n - F_true,n|^2 / sum_n |F_true,n|^2)   (whole run)
//   force_error_max_N  max_n |F_n - F_true,n|
//   coupling_energy_J  W = sum_n (F_n + F_{n+1})/2 . (x_{n+1} - x_n): the work the rendered force
//                      does on the probe (the user's hand) along the path. Over a closed path a
//                      passive coupling has W <= 0; W > 0 is energy the coupling created. The
//                      trapezoidal rule measures the rendered force field itself, not the extra
//                      energy any zero-order hold at the device's rate adds (the same for all schemes).
#pragma once

#include "realtime/control_model.hpp"
#include "realtime/haptic_coupling.hpp"
#include "realtime/probe_trajectory.hpp"

#include <string>
#include <vector>

namespace tmlab::rt {

struct SchemeMetrics {
  double force_error_rel = 0.0;
  double force_error_max_N = 0.0;
  double coupling_energy_J = 0.0;
};

/// The metrics of a rendered force history against the truth along the probe path x.
SchemeMetrics coupling_metrics(const std::vector<Vec3>& x, const std::vector<Vec3>& rendered,
                               const std::vector<Vec3>& truth);
/// W = sum (F_n + F_{n+1})/2 . (x_{n+1} - x_n).
double path_work(const std::vector<Vec3>& x, const std::vector<Vec3>& f);

/// Force histories of the ground truth on a list of probe positions (one per haptic tick): resets
/// `model` with the probe at x[0] and steps it `substeps` times per tick (haptic dt = substeps x
/// model dt) with the tick's probe position; the force of tick n is the one at (u^n, x_n).
std::vector<Vec3> ground_truth(ControlModel& model, const std::vector<Vec3>& x, int substeps);

struct CouplingStudy {
  double haptic_dt = 0.0;
  int control_every = 1;  ///< N haptic ticks per control update
  std::vector<double> t;
  std::vector<Vec3> x, truth, extrapolation, local_model;
  double truth_energy_J = 0.0;  ///< path_work of the ground truth (the tissue's own dissipation)
  SchemeMetrics extrapolation_metrics, local_model_metrics;
};

/// Runs the ground truth and the multi-rate run on `trajectory` for `duration` seconds, haptic
/// ticks of `substeps` model steps each; `model` is reset before each run. Throws tmlab::Error for
/// control_every < 1 or substeps < 1.
CouplingStudy run_coupling_study(ControlModel& model, const ProbeTrajectory& trajectory, int substeps,
                                 int control_every, double duration);

}  // namespace tmlab::rt
