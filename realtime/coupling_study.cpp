#include "realtime/coupling_study.hpp"

#include "core/base/error.hpp"
#include "core/base/interrupt.hpp"

#include <algorithm>
#include <cmath>

namespace tmlab::rt {

double path_work(const std::vector<Vec3>& x, const std::vector<Vec3>& f) {
  double w = 0.0;
  for (std::size_t n = 0; n + 1 < x.size() && n + 1 < f.size(); ++n)
    w += 0.5 * (f[n] + f[n + 1]).dot(x[n + 1] - x[n]);
  return w;
}

SchemeMetrics coupling_metrics(const std::vector<Vec3>& x, const std::vector<Vec3>& rendered,
                               const std::vector<Vec3>& truth) {
  if (rendered.size() != truth.size() || x.size() != truth.size())
    throw Error("coupling metrics: the force histories and the path differ in length");
  SchemeMetrics m;
  double num = 0.0, den = 0.0;
  for (std::size_t n = 0; n < truth.size(); ++n) {
    const double e = (rendered[n] - truth[n]).norm();
    num += e * e;
    den += truth[n].squaredNorm();
    m.force_error_max_N = std::max(m.force_error_max_N, e);
  }
  m.force_error_rel = den > 0.0 ? std::sqrt(num / den) : 0.0;
  m.coupling_energy_J = path_work(x, rendered);
  return m;
}

std::vector<Vec3> ground_truth(ControlModel& model, const std::vector<Vec3>& x, int substeps) {
  if (substeps < 1) throw Error("ground truth: substeps must be >= 1");
  std::vector<Vec3> f;
  f.reserve(x.size());
  if (x.empty()) return f;
  model.reset(x.front());
  for (const Vec3& c : x) {
    // A long recording's replay is interruptible (a pending SIGINT / SIGTERM throws tmlab::Interrupted).
    if (f.size() % 1024 == 0 && pending_interrupt() != 0)
      check_interrupt("while replaying the ground truth (tick " + std::to_string(f.size()) + " of " +
                      std::to_string(x.size()) + ")");
    f.push_back(model.step(c));  // force at (u^n, x_n), then on to the next tick
    for (int j = 1; j < substeps; ++j) model.step(c);
  }
  return f;
}

CouplingStudy run_coupling_study(ControlModel& model, const ProbeTrajectory& trajectory, int substeps,
                                 int control_every, double duration) {
  if (control_every < 1 || substeps < 1)
    throw Error("coupling study: control_every and substeps must be >= 1");
  if (!(duration > 0.0)) throw Error("coupling study: duration must be > 0");
  CouplingStudy s;
  s.haptic_dt = model.dt() * substeps;
  s.control_every = control_every;
  const long ticks = static_cast<long>(std::floor(duration / s.haptic_dt + 1e-9)) + 1;
  for (long n = 0; n < ticks; ++n) {
    s.t.push_back(static_cast<double>(n) * s.haptic_dt);
    s.x.push_back(trajectory.position(s.t.back()));
  }
  s.truth = ground_truth(model, s.x, substeps);

  // Multi-rate run.
  const auto N = static_cast<long>(control_every);
  model.reset(s.x.front());
  ExtrapolationCoupling extrapolation;
  LocalModelCoupling local;
  ContactSnapshot snap;
  s.extrapolation.assign(static_cast<std::size_t>(ticks), Vec3::Zero());
  s.local_model.assign(static_cast<std::size_t>(ticks), Vec3::Zero());
  for (long k = 0; k * N < ticks; ++k) {
    if (k % 64 == 0 && pending_interrupt() != 0)
      check_interrupt("during the coupling study (control block " + std::to_string(k) + ")");
    // Haptic ticks of block k render from the snapshot published at its start (none for k = 0).
    for (long n = k * N; n < std::min((k + 1) * N, ticks); ++n) {
      if (k == 0) continue;
      const auto i = static_cast<std::size_t>(n);
      s.extrapolation[i] = extrapolation.force(s.t[i], s.x[i]);
      s.local_model[i] = local.force(s.t[i], s.x[i]);
    }
    // Control block k: probe read at its start, held for N steps, state published at its end.
    const Vec3 c = s.x[static_cast<std::size_t>(k * N)];
    for (long j = 0; j < N * substeps; ++j) model.step(c);
    model.fill_snapshot(c, snap);
    extrapolation.on_snapshot(snap);
    local.on_snapshot(snap);
  }
  s.truth_energy_J = path_work(s.x, s.truth);
  s.extrapolation_metrics = coupling_metrics(s.x, s.extrapolation, s.truth);
  s.local_model_metrics = coupling_metrics(s.x, s.local_model, s.truth);
  return s;
}

}  // namespace tmlab::rt
