#include "realtime/probe_trajectory.hpp"

#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/base/number.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace tmlab::rt {

namespace {

constexpr double kPi = 3.14159265358979323846;
/// At most this many characters of the file are quoted in a message (control characters escaped).
constexpr std::size_t kExcerpt = 40;

/// s(x) = (1 - cos(pi x))/2 on [0, 1], clamped outside: the smooth ramp (zero slope at both ends).
double smooth(double x) {
  if (x <= 0.0) return 0.0;
  if (x >= 1.0) return 1.0;
  return 0.5 * (1.0 - std::cos(kPi * x));
}

Vec3 unit(const Vec3& v, const std::string& what) {
  const double n = v.norm();
  if (!(n > 0.0) || !std::isfinite(n))
    throw Error("probe trajectory: " + what + " must be a non-zero vector");
  return v / n;
}

void require_positive(double v, const std::string& what, bool allow_zero = false) {
  if (!std::isfinite(v) || v < 0.0 || (!allow_zero && v == 0.0))
    throw Error("probe trajectory: " + what + (allow_zero ? " must be >= 0" : " must be > 0"));
}

/// Shortest "%.6g" form of v, for messages.
std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

}  // namespace

ProbeTrajectory ProbeTrajectory::poke(const Vec3& start, const Vec3& direction, double depth, double ramp,
                                      double hold) {
  require_positive(depth, "poke depth");
  require_positive(ramp, "poke ramp");
  require_positive(hold, "poke hold", true);
  ProbeTrajectory p;
  p.kind_ = Kind::Poke;
  p.start_ = start;
  p.dir_ = unit(direction, "direction");
  p.depth_ = depth;
  p.ramp_ = ramp;
  p.hold_ = hold;
  p.duration_ = 2.0 * ramp + hold;
  return p;
}

ProbeTrajectory ProbeTrajectory::ellipse(const Vec3& start, const Vec3& direction, const Vec3& lateral,
                                         double depth, double amplitude, double period, int cycles,
                                         double ramp) {
  require_positive(depth, "ellipse depth");
  require_positive(amplitude, "ellipse amplitude", true);
  require_positive(period, "ellipse period");
  require_positive(ramp, "ellipse ramp");
  if (cycles < 1) throw Error("probe trajectory: ellipse cycles must be >= 1");
  ProbeTrajectory p;
  p.kind_ = Kind::Ellipse;
  p.start_ = start;
  p.dir_ = unit(direction, "direction");
  p.lateral_ = unit(lateral - lateral.dot(p.dir_) * p.dir_, "lateral (orthogonal to the direction)");
  p.depth_ = depth;
  p.amplitude_ = amplitude;
  p.period_ = period;
  p.cycles_ = cycles;
  p.ramp_ = ramp;
  p.duration_ = 2.0 * ramp + cycles * period;
  return p;
}

ProbeTrajectory ProbeTrajectory::samples(std::vector<double> t, std::vector<Vec3> x, std::string origin) {
  if (t.empty() || t.size() != x.size())
    throw Error(origin + ": a trajectory needs at least one sample and one position per time");
  if (t.front() != 0.0) throw Error(origin + ": the first sample must be at t = 0");
  for (std::size_t i = 1; i < t.size(); ++i)
    if (!(t[i] > t[i - 1])) throw Error(origin + ": sample times must be strictly increasing");
  ProbeTrajectory p;
  p.kind_ = Kind::Samples;
  p.start_ = x.front();
  p.duration_ = t.back();
  p.t_ = std::move(t);
  p.x_ = std::move(x);
  p.origin_ = std::move(origin);
  return p;
}

ProbeTrajectory ProbeTrajectory::read_csv(const std::string& path, const ProbeBounds* bounds) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open the trajectory file");
  std::vector<double> t;
  std::vector<Vec3> x;
  std::string line;
  int lineno = 0;
  bool header = false;
  while (std::getline(in, line)) {
    ++lineno;
    const std::string s = trim(line);
    const std::string at = path + ":" + std::to_string(lineno) + ": ";
    if (s.empty() || s[0] == '#') continue;
    if (!header) {
      std::string h;
      for (char c : s)
        if (c != ' ' && c != '\t') h += c;
      if (h != "t,x,y,z")
        throw Error(at + "the header must be 't,x,y,z' (got '" + printable(s, kExcerpt) + "')");
      header = true;
      continue;
    }
    if (std::count(s.begin(), s.end(), ',') != 3)
      throw Error(at + "expected 4 comma-separated columns t,x,y,z (got " +
                  std::to_string(std::count(s.begin(), s.end(), ',') + 1) + ")");
    double v[4];
    std::size_t pos = 0;
    for (int k = 0; k < 4; ++k) {
      const std::size_t comma = k < 3 ? s.find(',', pos) : s.size();
      const std::string field = trim(s.substr(pos, comma - pos));
      const char* names[] = {"t", "x", "y", "z"};
      std::string why;
      if (!parse_decimal(field, v[k], why))
        throw Error(at + "column " + std::to_string(k + 1) + " (" + names[k] + "): " + why);
      pos = comma + 1;
    }
    if (t.empty() && v[0] != 0.0)
      throw Error(at + "the first sample must be at t = 0 (got t = " + number(v[0]) + ")");
    if (!t.empty() && !(v[0] > t.back()))
      throw Error(at + "time " + number(v[0]) + " is not after the previous sample's (" + number(t.back()) +
                  ")");
    const Vec3 xi(v[1], v[2], v[3]);
    if (bounds && ((xi - bounds->min).minCoeff() < 0.0 || (bounds->max - xi).minCoeff() < 0.0))
      throw Error(at + "the probe centre (" + number(xi.x()) + ", " + number(xi.y()) + ", " + number(xi.z()) +
                  ") m lies outside " + bounds->what + ", (" + number(bounds->min.x()) + ", " +
                  number(bounds->min.y()) + ", " + number(bounds->min.z()) + ") to (" +
                  number(bounds->max.x()) + ", " + number(bounds->max.y()) + ", " + number(bounds->max.z()) +
                  ") m: positions are in metres, in the mesh frame");
    t.push_back(v[0]);
    x.push_back(xi);
  }
  if (!header) throw Error(path + ": empty trajectory file (expected the header 't,x,y,z')");
  if (t.empty()) throw Error(path + ": the trajectory has a header but no sample");
  return samples(std::move(t), std::move(x), path);
}

void ProbeTrajectory::write_csv(const std::string& path, const std::vector<double>& t,
                                const std::vector<Vec3>& x) {
  std::ofstream out(path);
  if (!out) throw Error(path + ": cannot write the trajectory file");
  out << "# tmlab probe trajectory: t (s), probe centre x, y, z (m)\nt,x,y,z\n" << std::setprecision(17);
  for (std::size_t i = 0; i < t.size(); ++i)
    out << t[i] << ',' << x[i].x() << ',' << x[i].y() << ',' << x[i].z() << '\n';
  if (!out) throw Error(path + ": write failed");
}

Vec3 ProbeTrajectory::position(double t) const {
  switch (kind_) {
    case Kind::Poke: {
      double d = 0.0;
      if (t < ramp_)
        d = smooth(t / ramp_);
      else if (t < ramp_ + hold_)
        d = 1.0;
      else
        d = 1.0 - smooth((t - ramp_ - hold_) / ramp_);
      return start_ + depth_ * d * dir_;
    }
    case Kind::Ellipse: {
      // Press to D/2, then per period: depth D/2 (1 + sin w tc), lateral A (1 - cos w tc), an ellipse
      // through the half-depth point where each period starts and ends (position continuous, the
      // velocity jumps once at the start of the cycles); then release from D/2.
      const double half = 0.5 * depth_;
      const double tc = t - ramp_, w = 2.0 * kPi / period_;
      double depth = 0.0, lat = 0.0;
      if (t < ramp_) {
        depth = half * smooth(t / ramp_);
      } else if (tc < cycles_ * period_) {
        depth = half + half * std::sin(w * tc);
        lat = amplitude_ * (1.0 - std::cos(w * tc));
      } else {
        depth = half * (1.0 - smooth((tc - cycles_ * period_) / ramp_));
      }
      return start_ + depth * dir_ + lat * lateral_;
    }
    case Kind::Samples: {
      if (t <= t_.front()) return x_.front();
      if (t >= t_.back()) return x_.back();
      const auto it = std::upper_bound(t_.begin(), t_.end(), t);
      const std::size_t i = static_cast<std::size_t>(it - t_.begin());
      const double a = (t - t_[i - 1]) / (t_[i] - t_[i - 1]);
      return (1.0 - a) * x_[i - 1] + a * x_[i];
    }
  }
  return start_;
}

std::string ProbeTrajectory::describe() const {
  switch (kind_) {
    case Kind::Poke:
      return "poke";
    case Kind::Ellipse:
      return "ellipse";
    case Kind::Samples:
      return origin_;
  }
  return "";
}

}  // namespace tmlab::rt
