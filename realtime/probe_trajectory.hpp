// Probe trajectories: where the probe centre is at time t, so every real-time run can be repeated.
//
// Scripted motions start at `start` (the probe clear of the surface) and move along the unit
// `direction` (into the tissue) with smooth cosine ramps, so the probe velocity is continuous:
//   poke:    depth d(t) = D s((t - t0)/T_r) during the press, held for T_h, released the same way;
//            the path is closed (it ends where it started).
//   ellipse: press to D/2 (ramp T_r), then `cycles` periods T of an ellipse in the plane of
//            `direction` and the unit `lateral`: depth D/2 (1 + sin wt), lateral offset A (1 - cos wt);
//            then release from D/2. Each period is a closed path while in contact.
// with s(x) = (1 - cos(pi x))/2 the smooth ramp.
//
// A trajectory file (docs/realtime.md) is a CSV with the header `t,x,y,z` (seconds, metres, the
// probe centre in the mesh frame), then one sample per line with strictly increasing t, first t = 0;
// blank lines and lines starting with '#' are skipped. Between samples the position is linear in t;
// before the first / after the last sample it is held. Numbers follow tmlab's one decimal grammar
// (core/base/number.hpp). Errors name the file, line and column and quote at most 40 characters of
// the file (control characters escaped), never a whole line. Given the
// box the probe may move in, a sample outside it is an error too: a file in millimetres or in
// another frame would otherwise run without ever touching the tissue.
#pragma once

#include "core/mesh/mesh.hpp"

#include <string>
#include <vector>

namespace tmlab::rt {

using tmlab::Vec3;

/// Where a probe centre may be (m), and what that box is (for the error message).
struct ProbeBounds {
  Vec3 min = Vec3::Zero(), max = Vec3::Zero();
  std::string what;
};

class ProbeTrajectory {
 public:
  enum class Kind { Poke, Ellipse, Samples };

  /// Poke: press `depth` along `direction` over `ramp` s, hold `hold` s, release over `ramp` s.
  static ProbeTrajectory poke(const Vec3& start, const Vec3& direction, double depth, double ramp,
                              double hold);
  /// Ellipse (see above); `lateral` is made orthogonal to `direction`.
  static ProbeTrajectory ellipse(const Vec3& start, const Vec3& direction, const Vec3& lateral, double depth,
                                 double amplitude, double period, int cycles, double ramp);
  /// Piecewise-linear samples (t strictly increasing, t[0] = 0).
  static ProbeTrajectory samples(std::vector<double> t, std::vector<Vec3> x, std::string origin = "samples");
  /// Reads a trajectory CSV (strict: errors name the file and line); with `bounds`, every sample
  /// must lie in them.
  static ProbeTrajectory read_csv(const std::string& path, const ProbeBounds* bounds = nullptr);
  /// Writes the CSV form of `samples` (t, x) (for recorded runs and tests).
  static void write_csv(const std::string& path, const std::vector<double>& t, const std::vector<Vec3>& x);

  /// Probe centre at time t (allocation-free: used on the haptic hot path).
  Vec3 position(double t) const;
  /// Duration of the motion, s (after it the probe rests at its last position).
  double duration() const { return duration_; }
  Kind kind() const { return kind_; }
  /// "poke", "ellipse" or the CSV's path.
  std::string describe() const;
  const Vec3& start() const { return start_; }
  /// The samples of a Kind::Samples trajectory (empty for the scripted kinds).
  const std::vector<double>& sample_times() const { return t_; }
  const std::vector<Vec3>& sample_points() const { return x_; }

 private:
  Kind kind_ = Kind::Poke;
  Vec3 start_ = Vec3::Zero(), dir_ = -Vec3::UnitZ(), lateral_ = Vec3::UnitX();
  double depth_ = 0.0, ramp_ = 1.0, hold_ = 0.0, amplitude_ = 0.0, period_ = 1.0;
  int cycles_ = 0;
  double duration_ = 0.0;
  std::vector<double> t_;
  std::vector<Vec3> x_;
  std::string origin_;
};

}  // namespace tmlab::rt
