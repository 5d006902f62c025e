// The shared Prony vocabulary: names round-trip, shorthands, recursion factors against their
// closed forms, and the two weight conventions against each other.
#include "core/constitutive/prony.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tmlab {
namespace {

constexpr PronyIntegration kIntegrations[] = {PronyIntegration::Midpoint, PronyIntegration::ExactLinear,
                                              PronyIntegration::BackwardEuler};

TEST(Prony, NamesRoundTripAndUnknownNamesAreRefused) {
  for (const std::string& n : prony_convention_names())
    EXPECT_EQ(to_string(prony_convention_from_string(n).value()), n);
  for (const std::string& n : prony_history_names())
    EXPECT_EQ(to_string(prony_history_from_string(n).value()), n);
  for (const std::string& n : prony_integration_names())
    EXPECT_EQ(to_string(prony_integration_from_string(n).value()), n);
  for (const std::string& n : prony_relaxation_names())
    EXPECT_EQ(to_string(prony_relaxation_from_string(n).value()), n);
  for (const std::string& n : prony_scheme_names())
    EXPECT_EQ(to_string(prony_scheme_from_string(n).value()), n);
  EXPECT_EQ(prony_history_names(), (std::vector<std::string>{"nodal_force", "pk2"}));
  EXPECT_EQ(prony_integration_from_string("exact_linear"), PronyIntegration::ExactLinear);
  EXPECT_EQ(prony_relaxation_from_string("deviatoric"), PronyRelaxation::Deviatoric);
  EXPECT_EQ(prony_convention_from_string("instantaneous"), PronyConvention::Instantaneous);
  EXPECT_FALSE(prony_integration_from_string("trapezoid"));
  EXPECT_FALSE(prony_history_from_string("PK2"));
  EXPECT_FALSE(prony_scheme_from_string(""));
}

TEST(Prony, SchemeNamesAndFormerNames) {
  // The names written are xu2011 / xu2011_exact_linear; the former names seed / seed_exact_linear
  // are still read (older case files) but never written.
  EXPECT_EQ(prony_scheme_names(),
            (std::vector<std::string>{"xu2011", "xu2011_exact_linear", "backward_euler", "objective"}));
  EXPECT_EQ(prony_scheme_from_string("xu2011"), PronyScheme::Xu2011);
  EXPECT_EQ(prony_scheme_from_string("xu2011_exact_linear"), PronyScheme::Xu2011ExactLinear);
  EXPECT_EQ(prony_scheme_from_string("seed"), PronyScheme::Xu2011);
  EXPECT_EQ(prony_scheme_from_string("seed_exact_linear"), PronyScheme::Xu2011ExactLinear);
  EXPECT_EQ(to_string(PronyScheme::Xu2011), "xu2011");
  EXPECT_EQ(to_string(PronyScheme::Xu2011ExactLinear), "xu2011_exact_linear");
  EXPECT_EQ(to_string(prony_scheme_from_string("seed").value()), "xu2011");
  EXPECT_FALSE(prony_scheme_from_string("Seed"));
  EXPECT_FALSE(prony_scheme_from_string("xu2011_midpoint"));
}

TEST(Prony, SchemeShorthands) {
  const PronySchemeParts xu2011 = scheme_parts(PronyScheme::Xu2011);
  EXPECT_EQ(xu2011.history, PronyHistory::NodalForce);
  EXPECT_EQ(xu2011.integration, PronyIntegration::Midpoint);
  EXPECT_EQ(scheme_parts(PronyScheme::Xu2011ExactLinear).integration, PronyIntegration::ExactLinear);
  EXPECT_EQ(scheme_parts(PronyScheme::BackwardEuler).integration, PronyIntegration::BackwardEuler);
  EXPECT_EQ(scheme_parts(PronyScheme::BackwardEuler).history, PronyHistory::NodalForce);
  EXPECT_EQ(scheme_parts(PronyScheme::Objective).history, PronyHistory::Pk2);
  EXPECT_EQ(scheme_parts(PronyScheme::Objective).integration, PronyIntegration::ExactLinear);
}

TEST(Prony, RecursionFactors) {
  // dt = 0 gives a = c = 1 for every scheme; exact_linear c -> 1 smoothly.
  for (PronyIntegration s : kIntegrations) {
    const RecursionFactors f = recursion_factors(s, 0.0, 1.0);
    EXPECT_EQ(f.a, 1.0);
    EXPECT_EQ(f.c, 1.0);
  }
  EXPECT_NEAR(recursion_factors(PronyIntegration::ExactLinear, 1e-9, 1.0).c, 1.0 - 0.5e-9, 1e-17);
  EXPECT_NEAR(recursion_factors(PronyIntegration::ExactLinear, 1.0, 2.0).c, 2.0 * (1.0 - std::exp(-0.5)),
              1e-15);
  EXPECT_NEAR(recursion_factors(PronyIntegration::ExactLinear, 0.1, 0.5).a, std::exp(-0.2), 1e-15);
  EXPECT_NEAR(recursion_factors(PronyIntegration::Midpoint, 1.0, 2.0).a, std::exp(-0.5), 1e-15);
  EXPECT_NEAR(recursion_factors(PronyIntegration::Midpoint, 1.0, 2.0).c, std::exp(-0.25), 1e-15);
  EXPECT_NEAR(recursion_factors(PronyIntegration::BackwardEuler, 1.0, 2.0).a, 1.0 / 1.5, 1e-15);
  EXPECT_NEAR(recursion_factors(PronyIntegration::BackwardEuler, 1.0, 2.0).c, 1.0 / 1.5, 1e-15);
  // exact_linear is exact for a driver linear in t: a unit ramp X_e = t over [0, dt] gives
  // h(dt) = int_0^dt e^{-(dt-s)/tau} ds = tau (1 - e^{-dt/tau}) = c dt.
  const double dt = 0.3, tau = 0.7;
  EXPECT_NEAR(recursion_factors(PronyIntegration::ExactLinear, dt, tau).c * dt,
              tau * (1.0 - std::exp(-dt / tau)), 1e-15);
}

TEST(Prony, WeightConventionsConvertBothWays) {
  // alpha_j = g_j / (1 - sum g), g_j = alpha_j / (1 + sum alpha)   (errata eq. 24)
  const std::vector<double> g{0.3, 0.2};
  const std::vector<double> alpha = long_term_weights(g);
  ASSERT_EQ(alpha.size(), 2u);
  EXPECT_NEAR(alpha[0], 0.6, 1e-15);
  EXPECT_NEAR(alpha[1], 0.4, 1e-15);
  const std::vector<double> back = instantaneous_weights(alpha);
  EXPECT_NEAR(back[0], 0.3, 1e-15);
  EXPECT_NEAR(back[1], 0.2, 1e-15);
  EXPECT_EQ(long_term_weights(PronyConvention::Instantaneous, g), alpha);
  EXPECT_EQ(long_term_weights(PronyConvention::LongTerm, g), g);
}

}  // namespace
}  // namespace tmlab
