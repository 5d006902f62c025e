#include "realtime/haptic_coupling.hpp"

#include "core/base/error.hpp"

#include <algorithm>

namespace tmlab::rt {

const char* to_string(CouplingScheme s) {
  return s == CouplingScheme::Extrapolation ? "extrapolation" : "local_model";
}

CouplingScheme parse_coupling(const std::string& s) {
  if (s == "extrapolation") return CouplingScheme::Extrapolation;
  if (s == "local_model") return CouplingScheme::LocalModel;
  throw Error("haptic coupling '" + s + "' is unknown (use \"extrapolation\" or \"local_model\")");
}

void ExtrapolationCoupling::on_snapshot(const ContactSnapshot& s) {
  t0_ = t1_;
  f0_ = f1_;
  t1_ = s.t;
  f1_ = s.force;
  have_ = std::min(have_ + 1, 2);
}

Vec3 ExtrapolationCoupling::force(double t, const Vec3& /*x*/) const {
  if (have_ == 0) return Vec3::Zero();
  if (have_ == 1 || !(t1_ > t0_)) return f1_;
  const double period = t1_ - t0_;
  const double h = std::clamp(t - t1_, 0.0, 4.0 * period);
  return f1_ + (f1_ - f0_) * (h / period);
}

Vec3 LocalModelCoupling::force(double /*t*/, const Vec3& x) const {
  if (!have_ || f_.squaredNorm() == 0.0) return Vec3::Zero();
  const Vec3 f = f_ + k_ * (x - c_);
  return f.dot(f_) > 0.0 ? f : Vec3::Zero();
}

}  // namespace tmlab::rt
