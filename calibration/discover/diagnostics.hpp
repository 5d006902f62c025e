// Residual diagnostics of `tmlab discover` (issue 15; docs/discover.md): is a fit's residual noise,
// and if not, where does it live? Pure functions of numbers, each with a statistic, a p-value where
// one exists, and the threshold that decides it (written into the report):
//   runs test (Wald-Wolfowitz) on the signs:  z = (R - E[R]) / sd[R], two-sided p, fails p < alpha
//   Ljung-Box:  Q = n (n+2) sum_{k=1..m} rho_k^2 / (n-k),  p = P(chi2_m > Q), fails p < alpha
//   Durbin-Watson:  DW = sum (e_i - e_{i-1})^2 / sum e_i^2 (2 for white noise; reported, not decisive)
//   Jarque-Bera:  JB = n/6 (S^2 + (K-3)^2/4),  p = P(chi2_2 > JB), fails p < alpha
//   noise level from the data's own high-frequency content: sigma = 1.4826 median|d2 x| / sqrt(6)
//     (d2 the second difference; for white noise on a smooth curve Var d2 = 6 sigma^2, the median
//     makes the kinks of ramp/hold corners harmless); ratio = residual RMS / sigma, fails > 1.5
//   periodicity: Fisher's g = max periodogram ordinate / sum, p = m (1-g)^(m-1) (first term),
//     Bonferroni over the tests; a peak below 5 cycles per test is a trend, not a period.
// alpha = 1e-3 for every test: the loop runs them after every step, so a loose level would find
// "structure" in pure noise every few data sets.
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace tmlab::discover {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Thresholds {
  double alpha = 1e-3;        ///< significance level of runs, Ljung-Box, Jarque-Bera, Fisher g
  double noise_ratio = 1.5;   ///< residual RMS / high-frequency noise level above this: not noise
  int min_period_cycles = 5;  ///< a spectral peak must repeat at least this often per test
  /// Residual RMS below this times the noise level: the data carry no noise to weigh a candidate
  /// against (noise-free or smoothed data: a fit to noisy data cannot go much below the noise, so
  /// the "noise level" is the curve's own curvature), and the loop selects nothing (discover.hpp).
  double below_noise = 0.5;
  /// A noise level below this fraction of the peak force is round-off (data written exactly, e.g.
  /// synthetic curves): with no measurable noise there is nothing to weigh a candidate against, and
  /// the loop selects nothing, whatever the residual (an exact linear ramp has noise level 0 and a
  /// St VK residual: a drift linear in time, which on one ramp is linear in displacement, would be
  /// "very strong" evidence of a law the loop has not tried).
  double noise_floor = 1e-6;
};

struct Diagnostic {
  std::string name;         ///< runs_test, ljung_box, durbin_watson, jarque_bera, noise_ratio, periodicity
  double statistic = kNaN;  ///< z, Q, DW, JB, ratio or g
  double p_value = kNaN;    ///< NaN when the statistic has no p-value (DW, noise ratio)
  std::string threshold;    ///< the rule, e.g. "p < 0.001"
  bool passed = true;       ///< true: consistent with noise
  bool decisive = true;     ///< counts towards "structured"
  std::string note;
};

struct RunsResult {
  std::size_t positive = 0, negative = 0, runs = 0;
  double z = 0.0, p = 1.0;
};
/// Runs of equal sign (zeros skipped). p = 1 with fewer than 2 of either sign.
RunsResult runs_test(const std::vector<double>& r);

struct LjungBoxResult {
  double q = 0.0, p = 1.0;
  int lags = 0;
};
/// Ljung-Box at `lags` lags (about min(20, n/5) when lags <= 0), residual mean removed.
LjungBoxResult ljung_box(const std::vector<double>& r, int lags = 0);

double durbin_watson(const std::vector<double>& r);

struct JarqueBeraResult {
  double skewness = 0.0, kurtosis = 3.0, statistic = 0.0, p = 1.0;
};
JarqueBeraResult jarque_bera(const std::vector<double>& r);

/// The white-noise level of `x` (a smooth curve plus noise) from its second differences.
double noise_level(const std::vector<double>& x);

struct Periodicity {
  double frequency_hz = 0.0;  ///< of the largest periodogram ordinate
  double cycles = 0.0;        ///< periods in the series' duration
  double g = 0.0, p = 1.0;
  bool uniform = false;  ///< false: time steps vary by more than 1 %, no periodogram computed
};
/// Fisher's g test on `r` sampled at times `t` (mean and linear trend removed first).
Periodicity fisher_periodicity(const std::vector<double>& t, const std::vector<double>& r);

enum class Phase { ramp, hold, unload };
std::string to_string(Phase p);

/// The phase of each sample from the displacement rate (|rate| < 2 % of the largest: hold; the
/// sign of the rate into the sample otherwise) and its cycle (a cycle starts with each loading
/// ramp that follows an unloading). `sign` = +1 for compression/indentation, -1 for tension.
struct PhaseLabels {
  std::vector<Phase> phase;
  std::vector<int> cycle;
  std::vector<double> rate;  ///< m/s, into the sample positive
};
PhaseLabels classify_phases(const std::vector<double>& t, const std::vector<double>& d, double sign);

/// Residual statistics of a group of samples (a phase, a test, a strain bin).
struct GroupStat {
  std::string group;
  std::size_t n = 0;
  double rms = 0.0, mean = 0.0, max_abs = 0.0;
  double x = kNaN;  ///< the group's abscissa where one exists (mean strain, ramp rate)
};

/// One test of a residual study: its times, displacements and residuals (model - data).
struct SeriesView {
  std::string id;
  std::vector<double> t, d, force, residual;
};

struct ResidualStudy {
  std::size_t n = 0;
  double rms = 0.0, max_abs = 0.0, mean = 0.0;
  double noise_sigma = 0.0;  ///< from the data's high-frequency content, pooled over the tests
  std::vector<Diagnostic> diagnostics;
  bool structured = false;  ///< a decisive diagnostic failed: the residual is not noise
  std::vector<GroupStat> by_phase, by_cycle, by_test, by_strain;
  Periodicity period;               ///< the most significant periodicity over the tests
  double first_cycle_ratio = kNaN;  ///< RMS of cycle 1 over the RMS of later cycles (NaN: one cycle)
  double worst_test_ratio = kNaN;   ///< largest test RMS over the median test RMS (NaN: < 3 tests)
  double rate_correlation = kNaN;   ///< Spearman of test ramp rate vs test RMS (NaN: < 3 tests)
  std::string where;                ///< one sentence: where the residual is largest
};

/// Studies a residual. `sign` as in classify_phases; `scale` turns displacement into the strain
/// measure of the data (1/height for platens, 1/radius for indentation).
ResidualStudy study_residual(const std::vector<SeriesView>& series, double sign, double scale,
                             const Thresholds& th = {});

/// What the structure that remains looks like, for the report ("" when `s` is not structured).
std::string describe_signature(const ResidualStudy& s, const Thresholds& th = {});

}  // namespace tmlab::discover
