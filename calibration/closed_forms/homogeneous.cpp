// Homogeneous platen tests (homogeneous.hpp has the equations).
#include "calibration/closed_forms/homogeneous.hpp"

#include "core/base/error.hpp"

#include <cmath>
#include <string>

namespace tmlab::closed_forms {

namespace {

// Green-Lagrange strain of F = diag(lt, lt, l): E = (F^T F - I) / 2.
tm::Mat3 strain(double lt, double l) {
  tm::Mat3 e = tm::Mat3::Zero();
  e(0, 0) = e(1, 1) = 0.5 * (lt * lt - 1.0);
  e(2, 2) = 0.5 * (l * l - 1.0);
  return e;
}

double lateral_pk2(const tm::Law& law, double lt, double l) { return law.pk2_stress(strain(lt, l))(0, 0); }

// The lateral stretch with S_xx = 0: bracket the root around `guess` by expanding geometrically,
// then bisect with secant steps (Illinois false position), to round-off in lt.
double lateral_root(const tm::Law& law, double l, double guess) {
  double a = guess, b = guess;
  double fa = lateral_pk2(law, a, l), fb = fa;
  for (int k = 0; k < 200 && fa * fb > 0.0; ++k) {
    a = std::max(a / 1.25, 1e-6);
    b = std::min(b * 1.25, 10.0);
    fa = lateral_pk2(law, a, l);
    fb = lateral_pk2(law, b, l);
    if (a <= 1e-6 && b >= 10.0) break;
  }
  if (!(fa * fb <= 0.0) || !std::isfinite(fa) || !std::isfinite(fb)) {
    throw Error("homogeneous platen test: no lateral stretch frees the lateral faces at axial stretch " +
                std::to_string(l) + " (the law has no homogeneous uniaxial state there)");
  }
  // Illinois false position: keep a sign change in [a, b]; when the same end survives twice in a
  // row its value is halved, so the bracket shrinks from both sides.
  for (int it = 0; it < 200 && std::abs(b - a) > 4e-16 * std::abs(b); ++it) {
    const double c = (a * fb - b * fa) / (fb - fa);
    const double fc = lateral_pk2(law, c, l);
    if (fc == 0.0) return c;
    if (fc * fb < 0.0) {
      a = b;
      fa = fb;
    } else {
      fa *= 0.5;
    }
    b = c;
    fb = fc;
  }
  return 0.5 * (a + b);
}

}  // namespace

PlatenState platen_state(const tm::Law& law, PlatenTest test, double height, double area, double d) {
  if (!(height > 0.0) || !(area > 0.0))
    throw Error("homogeneous platen test: height and area must be positive");
  if (!(d < height) || !std::isfinite(d)) {
    throw Error("homogeneous platen test: the platen displacement must be finite and below the height");
  }
  PlatenState s;
  s.stretch = 1.0 - d / height;
  s.lateral_stretch =
      test == PlatenTest::Confined ? 1.0 : lateral_root(law, s.stretch, 1.0 / std::sqrt(s.stretch));
  const double szz = law.pk2_stress(strain(s.lateral_stretch, s.stretch))(2, 2);
  s.nominal_stress = -s.stretch * szz;
  s.force = s.nominal_stress * area;
  return s;
}

std::vector<PlatenState> platen_curve(const tm::Law& law, PlatenTest test, double height, double area,
                                      const std::vector<double>& d) {
  std::vector<PlatenState> out;
  out.reserve(d.size());
  for (const double di : d) out.push_back(platen_state(law, test, height, area, di));
  return out;
}

}  // namespace tmlab::closed_forms
