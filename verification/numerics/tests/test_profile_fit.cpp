// The profile errors against cases with known answers: the exact Hertz profile (with and without a
// rigid offset) has no error; a two-sample profile with an added eps r^2 has RMS error eps / (2c)
// (samples at r = 0 and r = a, deviations +-eps a^2 / 2 about their mean, relative to c a^2) and
// curvature error eps / c.
#include "verification/numerics/profile_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace tmlab::verify::numerics {
namespace {

std::vector<double> hertz_profile(const std::vector<double>& r, double a, double c, double offset) {
  std::vector<double> uz;
  for (double x : r) uz.push_back(-c * (2 * a * a - x * x) + offset);
  return uz;
}

TEST(ProfileFit, ExactProfileHasNoError) {
  const double a = 2e-3, c = 3.0;
  std::vector<double> r;
  for (int i = 0; i <= 8; ++i) r.push_back(a * i / 8.0);
  for (double offset : {0.0, 1e-5, -4e-4}) {
    const ProfileErrors e = profile_errors(r, hertz_profile(r, a, c, offset), a, c);
    EXPECT_LT(e.rms, 1e-10) << "offset " << offset;
    EXPECT_LT(e.curvature, 1e-10) << "offset " << offset;
  }
}

TEST(ProfileFit, ExtraCurvatureOnTwoSamples) {
  const double a = 1e-2, c = 0.5, eps = 0.02;
  const std::vector<double> r{0.0, a};
  std::vector<double> uz = hertz_profile(r, a, c, 0.0);
  for (std::size_t i = 0; i < r.size(); ++i) uz[i] += eps * r[i] * r[i];
  const ProfileErrors e = profile_errors(r, uz, a, c);
  EXPECT_NEAR(e.rms, eps / (2 * c), 1e-12);
  EXPECT_NEAR(e.curvature, eps / c, 1e-10);
}

TEST(ProfileFit, RmsOfANonQuadraticError) {
  // Error d(r) = delta for r < a/2 and -delta beyond on a symmetric sample: mean 0, RMS delta.
  const double a = 1.0, c = 2.0, delta = 1e-3;
  const std::vector<double> r{0.1, 0.2, 0.7, 0.8};
  std::vector<double> uz = hertz_profile(r, a, c, 0.0);
  for (std::size_t i = 0; i < r.size(); ++i) uz[i] += r[i] < 0.5 ? delta : -delta;
  const ProfileErrors e = profile_errors(r, uz, a, c);
  EXPECT_NEAR(e.rms, delta / (c * a * a), 1e-14);
  EXPECT_GT(e.curvature, 0.0);
}

}  // namespace
}  // namespace tmlab::verify::numerics
