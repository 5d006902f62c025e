#include "calibration/discover/diagnostics.hpp"

#include "core/base/format.hpp"

#include <gsl/gsl_cdf.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace tmlab::discover {

namespace {

constexpr double kPi = 3.14159265358979323846;

double mean_of(const std::vector<double>& x) {
  return x.empty() ? 0.0 : std::accumulate(x.begin(), x.end(), 0.0) / double(x.size());
}

double rms_of(const std::vector<double>& x) {
  double s = 0.0;
  for (const double v : x) s += v * v;
  return x.empty() ? 0.0 : std::sqrt(s / double(x.size()));
}

double median_of(std::vector<double> x) {
  if (x.empty()) return 0.0;
  const std::size_t m = x.size() / 2;
  std::nth_element(x.begin(), x.begin() + long(m), x.end());
  double v = x[m];
  if (x.size() % 2 == 0) v = 0.5 * (v + *std::max_element(x.begin(), x.begin() + long(m)));
  return v;
}

std::vector<double> ranks(const std::vector<double>& x) {
  std::vector<std::size_t> o(x.size());
  std::iota(o.begin(), o.end(), 0);
  std::sort(o.begin(), o.end(), [&](std::size_t a, std::size_t b) { return x[a] < x[b]; });
  std::vector<double> r(x.size());
  for (std::size_t i = 0; i < o.size();) {
    std::size_t j = i;
    while (j + 1 < o.size() && x[o[j + 1]] == x[o[i]]) ++j;
    for (std::size_t k = i; k <= j; ++k) r[o[k]] = 0.5 * double(i + j) + 1.0;
    i = j + 1;
  }
  return r;
}

double pearson(const std::vector<double>& a, const std::vector<double>& b) {
  const double ma = mean_of(a), mb = mean_of(b);
  double sab = 0.0, saa = 0.0, sbb = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return saa > 0.0 && sbb > 0.0 ? sab / std::sqrt(saa * sbb) : 0.0;
}

GroupStat group_stat(const std::string& name, const std::vector<double>& r, double x = kNaN) {
  GroupStat g;
  g.group = name;
  g.n = r.size();
  g.rms = rms_of(r);
  g.mean = mean_of(r);
  for (const double v : r) g.max_abs = std::max(g.max_abs, std::abs(v));
  g.x = x;
  return g;
}

std::string pstr(double p) { return p < 1e-16 ? "< 1e-16" : significant(p, 2); }

}  // namespace

RunsResult runs_test(const std::vector<double>& r) {
  RunsResult out;
  int last = 0;
  for (const double v : r) {
    if (v == 0.0) continue;
    const int s = v > 0.0 ? 1 : -1;
    (s > 0 ? out.positive : out.negative) += 1;
    if (s != last) ++out.runs;
    last = s;
  }
  const double n1 = double(out.positive), n2 = double(out.negative), n = n1 + n2;
  if (out.positive < 2 || out.negative < 2) return out;
  const double mu = 2.0 * n1 * n2 / n + 1.0;
  const double var = 2.0 * n1 * n2 * (2.0 * n1 * n2 - n) / (n * n * (n - 1.0));
  out.z = (double(out.runs) - mu) / std::sqrt(var);
  out.p = 2.0 * gsl_cdf_ugaussian_Q(std::abs(out.z));
  return out;
}

LjungBoxResult ljung_box(const std::vector<double>& r, int lags) {
  LjungBoxResult out;
  const std::size_t n = r.size();
  if (lags <= 0) lags = int(std::min<std::size_t>(20, std::max<std::size_t>(1, n / 5)));
  out.lags = lags;
  if (n < 3 || std::size_t(lags) >= n) return out;
  const double m = mean_of(r);
  double c0 = 0.0;
  for (const double v : r) c0 += (v - m) * (v - m);
  if (!(c0 > 0.0)) return out;
  for (int k = 1; k <= lags; ++k) {
    double ck = 0.0;
    for (std::size_t i = std::size_t(k); i < n; ++i) ck += (r[i] - m) * (r[i - std::size_t(k)] - m);
    const double rho = ck / c0;
    out.q += rho * rho / double(n - std::size_t(k));
  }
  out.q *= double(n) * double(n + 2);
  out.p = gsl_cdf_chisq_Q(out.q, double(lags));
  return out;
}

double durbin_watson(const std::vector<double>& r) {
  double num = 0.0, den = 0.0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    den += r[i] * r[i];
    if (i > 0) num += (r[i] - r[i - 1]) * (r[i] - r[i - 1]);
  }
  return den > 0.0 ? num / den : kNaN;
}

JarqueBeraResult jarque_bera(const std::vector<double>& r) {
  JarqueBeraResult out;
  const double n = double(r.size());
  if (r.size() < 8) return out;
  const double m = mean_of(r);
  double m2 = 0.0, m3 = 0.0, m4 = 0.0;
  for (const double v : r) {
    const double e = v - m;
    m2 += e * e;
    m3 += e * e * e;
    m4 += e * e * e * e;
  }
  m2 /= n;
  m3 /= n;
  m4 /= n;
  if (!(m2 > 0.0)) return out;
  out.skewness = m3 / std::pow(m2, 1.5);
  out.kurtosis = m4 / (m2 * m2);
  out.statistic = n / 6.0 * (out.skewness * out.skewness + 0.25 * std::pow(out.kurtosis - 3.0, 2));
  out.p = gsl_cdf_chisq_Q(out.statistic, 2.0);
  return out;
}

double noise_level(const std::vector<double>& x) {
  if (x.size() < 3) return 0.0;
  std::vector<double> d2;
  for (std::size_t i = 1; i + 1 < x.size(); ++i) d2.push_back(std::abs(x[i + 1] - 2.0 * x[i] + x[i - 1]));
  return 1.4826 * median_of(d2) / std::sqrt(6.0);
}

Periodicity fisher_periodicity(const std::vector<double>& t, const std::vector<double>& r) {
  Periodicity out;
  const std::size_t n = r.size();
  if (n < 16 || t.size() != n) return out;
  double dmin = 1e300, dmax = 0.0;
  for (std::size_t i = 1; i < n; ++i) {
    dmin = std::min(dmin, t[i] - t[i - 1]);
    dmax = std::max(dmax, t[i] - t[i - 1]);
  }
  if (!(dmin > 0.0) || dmax > 1.01 * dmin) return out;
  out.uniform = true;
  const double dt = (t.back() - t.front()) / double(n - 1);
  // Mean and linear trend removed (least squares against the sample index).
  std::vector<double> idx(n), e(n);
  std::iota(idx.begin(), idx.end(), 0.0);
  const double mi = mean_of(idx), mr = mean_of(r);
  double sxy = 0.0, sxx = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    sxy += (idx[i] - mi) * (r[i] - mr);
    sxx += (idx[i] - mi) * (idx[i] - mi);
  }
  const double slope = sxy / sxx;
  for (std::size_t i = 0; i < n; ++i) e[i] = r[i] - mr - slope * (idx[i] - mi);
  // Periodogram at the Fourier frequencies j/n, j = 1..m (the Nyquist ordinate left out).
  const std::size_t m = (n - 1) / 2;
  double total = 0.0, best = -1.0;
  std::size_t best_j = 1;
  for (std::size_t j = 1; j <= m; ++j) {
    double c = 0.0, s = 0.0;
    const double w = 2.0 * kPi * double(j) / double(n);
    for (std::size_t i = 0; i < n; ++i) {
      c += e[i] * std::cos(w * double(i));
      s += e[i] * std::sin(w * double(i));
    }
    const double ij = c * c + s * s;
    total += ij;
    if (ij > best) {
      best = ij;
      best_j = j;
    }
  }
  if (!(total > 0.0)) return out;
  out.g = best / total;
  out.p = std::min(1.0, double(m) * std::pow(1.0 - out.g, double(m) - 1.0));
  out.cycles = double(best_j);
  out.frequency_hz = double(best_j) / (double(n) * dt);
  return out;
}

std::string to_string(Phase p) {
  switch (p) {
    case Phase::ramp:
      return "ramp";
    case Phase::hold:
      return "hold";
    case Phase::unload:
      return "unload";
  }
  return "?";
}

PhaseLabels classify_phases(const std::vector<double>& t, const std::vector<double>& d, double sign) {
  PhaseLabels out;
  const std::size_t n = t.size();
  out.rate.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t a = i > 0 ? i - 1 : i, b = i + 1 < n ? i + 1 : i;
    if (b > a && t[b] > t[a]) out.rate[i] = sign * (d[b] - d[a]) / (t[b] - t[a]);
  }
  double vmax = 0.0;
  for (const double v : out.rate) vmax = std::max(vmax, std::abs(v));
  int cycle = 1;
  bool unloaded = false;
  for (std::size_t i = 0; i < n; ++i) {
    Phase p = Phase::hold;
    if (std::abs(out.rate[i]) > 0.02 * vmax) p = out.rate[i] > 0.0 ? Phase::ramp : Phase::unload;
    if (p == Phase::unload) unloaded = true;
    if (p == Phase::ramp && unloaded) {
      ++cycle;
      unloaded = false;
    }
    out.phase.push_back(p);
    out.cycle.push_back(cycle);
  }
  return out;
}

namespace {

/// The pooled residual and the size, RMS, mean, largest value and noise level of `s`; the noise
/// variance of each test weighted by its samples.
std::vector<double> pool_residuals(const std::vector<SeriesView>& series, ResidualStudy& s) {
  std::vector<double> all;
  double wsum = 0.0, var = 0.0;
  for (const auto& v : series) {
    all.insert(all.end(), v.residual.begin(), v.residual.end());
    const double sg = noise_level(v.force);
    var += sg * sg * double(v.force.size());
    wsum += double(v.force.size());
  }
  s.n = all.size();
  s.rms = rms_of(all);
  s.mean = mean_of(all);
  for (const double v : all) s.max_abs = std::max(s.max_abs, std::abs(v));
  s.noise_sigma = wsum > 0.0 ? std::sqrt(var / wsum) : 0.0;
  return all;
}

/// Autocorrelation and signs, per test, combined: Ljung-Box Q and its lags add over independent
/// tests, the runs test's counts (runs, their mean and variance for noise) likewise, so no lag
/// crosses from one test into the next; Durbin-Watson's numerator and denominator add too.
struct SerialSums {
  double q = 0.0;
  int lags = 0;
  double runs = 0.0, mu = 0.0, varr = 0.0;
  // Durbin-Watson's numerator and denominator. Kept in memory as before the split: as two scalars
  // the compiler fuses the denominator's multiply-add (FMA) and the last digit of DW changes.
  std::vector<double> dw_num_den = std::vector<double>(2, 0.0);
};

SerialSums serial_sums(const std::vector<SeriesView>& series) {
  SerialSums m;
  for (const auto& v : series) {
    if (v.residual.size() >= 10) {
      const LjungBoxResult lb = ljung_box(v.residual);
      m.q += lb.q;
      m.lags += lb.lags;
    }
    const RunsResult rr = runs_test(v.residual);
    if (rr.positive >= 2 && rr.negative >= 2) {
      const double n1 = double(rr.positive), n2 = double(rr.negative), n = n1 + n2;
      m.runs += double(rr.runs);
      m.mu += 2.0 * n1 * n2 / n + 1.0;
      m.varr += 2.0 * n1 * n2 * (2.0 * n1 * n2 - n) / (n * n * (n - 1.0));
    }
    for (std::size_t i = 0; i < v.residual.size(); ++i) {
      m.dw_num_den[1] += v.residual[i] * v.residual[i];
      if (i > 0) m.dw_num_den[0] += std::pow(v.residual[i] - v.residual[i - 1], 2);
    }
  }
  return m;
}

// `a` in the rules below: the level th.alpha as written in the thresholds.

Diagnostic runs_diagnostic(const SerialSums& m, const Thresholds& th, const std::string& a) {
  Diagnostic d{"runs_test", kNaN, kNaN, "two-sided p < " + a + ": not noise", true, true, ""};
  if (m.varr > 0.0) {
    d.statistic = (m.runs - m.mu) / std::sqrt(m.varr);
    d.p_value = 2.0 * gsl_cdf_ugaussian_Q(std::abs(d.statistic));
    d.passed = !(d.p_value < th.alpha);
    d.note = significant(m.runs, 6) + " runs of equal sign, " + significant(m.mu, 6) + " expected for noise";
  }
  return d;
}

Diagnostic ljung_box_diagnostic(const SerialSums& m, const Thresholds& th, const std::string& a) {
  Diagnostic d{"ljung_box", kNaN, kNaN, "p = P(chi2_lags > Q) < " + a + ": autocorrelated", true, true, ""};
  if (m.lags > 0) {
    d.statistic = m.q;
    d.p_value = gsl_cdf_chisq_Q(m.q, double(m.lags));
    d.passed = !(d.p_value < th.alpha);
    d.note = std::to_string(m.lags) + " lags summed over the tests";
  }
  return d;
}

Diagnostic durbin_watson_diagnostic(const SerialSums& m) {
  Diagnostic d{
      "durbin_watson", kNaN, kNaN, "about 2 for noise; < 1 strong positive autocorrelation (reported)", true,
      false,           ""};
  if (m.dw_num_den[1] > 0.0) {
    d.statistic = m.dw_num_den[0] / m.dw_num_den[1];
    d.passed = d.statistic >= 1.0;
  }
  return d;
}

Diagnostic jarque_bera_diagnostic(const std::vector<double>& all, const Thresholds& th,
                                  const std::string& a) {
  const JarqueBeraResult jb = jarque_bera(all);
  Diagnostic d{"jarque_bera",
               jb.statistic,
               jb.p,
               "p < " + a + ": not normal (reported; heavy-tailed instrument noise fails it too)",
               true,
               false,
               "skewness " + significant(jb.skewness, 3) + ", kurtosis " + significant(jb.kurtosis, 3)};
  d.passed = !(jb.p < th.alpha);
  return d;
}

Diagnostic noise_ratio_diagnostic(const ResidualStudy& s, const Thresholds& th) {
  Diagnostic d{"noise_ratio",
               kNaN,
               kNaN,
               "residual RMS / noise level > " + significant(th.noise_ratio, 3) + ": more than noise",
               true,
               false,
               "noise level " + significant(s.noise_sigma, 3) + " N from second differences of the data"};
  if (s.noise_sigma > 0.0) {
    d.statistic = s.rms / s.noise_sigma;
    d.passed = d.statistic <= th.noise_ratio;
  }
  return d;
}

/// Periodicity: the most significant test (Bonferroni over the tests), kept in `period`. When no
/// test has its largest ordinate at >= min_period_cycles (a trend, not a period), the statistic of
/// the most significant low-frequency peak is still written, as passed, so that the report has a
/// statistic for every diagnostic; the decision is the same.
Diagnostic periodicity_diagnostic(const std::vector<SeriesView>& series, const Thresholds& th,
                                  const std::string& a, Periodicity& period) {
  double best_p = 2.0, trend_p = 2.0;
  Periodicity trend;
  for (const auto& v : series) {
    const Periodicity pe = fisher_periodicity(v.t, v.residual);
    if (!pe.uniform) continue;
    const double p = std::min(1.0, pe.p * double(series.size()));
    if (pe.cycles >= th.min_period_cycles && p < best_p) {
      best_p = p;
      period = pe;
      period.p = p;
    }
    if (pe.cycles < th.min_period_cycles && p < trend_p) {
      trend_p = p;
      trend = pe;
      trend.p = p;
    }
  }
  Diagnostic d{"periodicity",
               kNaN,
               kNaN,
               "Fisher g with p < " + a + " (Bonferroni over tests) at >= " +
                   std::to_string(th.min_period_cycles) + " cycles per test: periodic",
               true,
               true,
               ""};
  if (best_p <= 1.0) {
    d.statistic = period.g;
    d.p_value = period.p;
    d.passed = !(period.p < th.alpha);
    d.note = "largest ordinate at " + significant(period.frequency_hz, 3) + " Hz";
  } else if (trend_p <= 1.0) {
    period = trend;
    d.statistic = trend.g;
    d.p_value = trend.p;
    d.note = "every test's largest ordinate lies below " + std::to_string(th.min_period_cycles) +
             " cycles per test (here " + significant(trend.cycles, 3) + " at " +
             significant(trend.frequency_hz, 3) + " Hz): a trend, not a period";
  } else {
    d.note = "no uniformly sampled test of 16 samples or more";
  }
  return d;
}

/// The residual sorted into groups: by phase (ramp, hold, unload), by cycle, by strain bin (five
/// equal bins up to the largest strain, with the sum of the strains for their mean), and per test
/// its mean ramp rate and RMS.
struct ResidualGroups {
  std::vector<std::vector<double>> phase = std::vector<std::vector<double>>(3), cycle;
  std::vector<std::vector<double>> strain_bin = std::vector<std::vector<double>>(5);
  std::vector<double> strain_sum = std::vector<double>(5, 0.0);
  std::vector<double> test_rate, test_rms;
};

/// Sorts the residual into groups; appends each test's GroupStat (x: its mean ramp rate) to `by_test`.
ResidualGroups group_residuals(const std::vector<SeriesView>& series, double sign, double scale,
                               std::vector<GroupStat>& by_test) {
  ResidualGroups g;
  double emax = 0.0;
  for (const auto& v : series)
    for (const double d : v.d) emax = std::max(emax, std::abs(d * scale));
  for (const auto& v : series) {
    const PhaseLabels pl = classify_phases(v.t, v.d, sign);
    double rsum = 0.0;
    int rn = 0;
    for (std::size_t i = 0; i < v.residual.size(); ++i) {
      g.phase[std::size_t(pl.phase[i])].push_back(v.residual[i]);
      const std::size_t c = std::size_t(pl.cycle[i] - 1);
      if (g.cycle.size() <= c) g.cycle.resize(c + 1);
      g.cycle[c].push_back(v.residual[i]);
      const double e = std::abs(v.d[i] * scale);
      const std::size_t b = emax > 0.0 ? std::min<std::size_t>(4, std::size_t(5.0 * e / emax)) : 0;
      g.strain_bin[b].push_back(v.residual[i]);
      g.strain_sum[b] += e;
      if (pl.phase[i] == Phase::ramp) {
        rsum += std::abs(pl.rate[i]);
        ++rn;
      }
    }
    const double rate = rn ? rsum / rn : 0.0;
    by_test.push_back(group_stat(v.id, v.residual, rate));
    g.test_rate.push_back(rate);
    g.test_rms.push_back(rms_of(v.residual));
  }
  return g;
}

/// The groups' statistics and the ratios that point at an effect: first cycle vs later cycles,
/// worst test vs the median test, and the rank correlation of the tests' ramp rates and RMS.
void summarise_groups(const ResidualGroups& g, std::size_t tests, ResidualStudy& s) {
  for (int p = 0; p < 3; ++p)
    if (!g.phase[std::size_t(p)].empty())
      s.by_phase.push_back(group_stat(to_string(Phase(p)), g.phase[std::size_t(p)]));
  for (std::size_t c = 0; c < g.cycle.size(); ++c)
    if (!g.cycle[c].empty()) s.by_cycle.push_back(group_stat("cycle " + std::to_string(c + 1), g.cycle[c]));
  for (std::size_t b = 0; b < 5; ++b)
    if (!g.strain_bin[b].empty())
      s.by_strain.push_back(group_stat("strain bin " + std::to_string(b + 1), g.strain_bin[b],
                                       g.strain_sum[b] / double(g.strain_bin[b].size())));
  if (s.by_cycle.size() >= 2) {
    std::vector<double> later;
    for (std::size_t c = 1; c < g.cycle.size(); ++c)
      later.insert(later.end(), g.cycle[c].begin(), g.cycle[c].end());
    const double rl = rms_of(later);
    s.first_cycle_ratio = rl > 0.0 ? s.by_cycle[0].rms / rl : kNaN;
  }
  if (tests >= 3) {
    s.worst_test_ratio =
        *std::max_element(g.test_rms.begin(), g.test_rms.end()) / std::max(median_of(g.test_rms), 1e-300);
    bool rates_differ = false;
    for (const double r : g.test_rate)
      rates_differ |= std::abs(r - g.test_rate[0]) > 0.05 * std::abs(g.test_rate[0]);
    if (rates_differ) s.rate_correlation = pearson(ranks(g.test_rate), ranks(g.test_rms));
  }
}

/// One sentence: the phase and the strain bin with the largest RMS ("" without either).
std::string where_largest(const ResidualStudy& s) {
  const auto worst = [](const std::vector<GroupStat>& g) {
    return std::max_element(g.begin(), g.end(),
                            [](const GroupStat& u, const GroupStat& w) { return u.rms < w.rms; });
  };
  if (s.by_phase.empty() || s.by_strain.empty()) return "";
  const auto wp = worst(s.by_phase), ws = worst(s.by_strain);
  return "largest in the " + wp->group + " phase (RMS " + significant(wp->rms, 3) + " N) and at strain " +
         significant(ws->x, 3) + " (" + ws->group + ", RMS " + significant(ws->rms, 3) + " N, mean " +
         significant(ws->mean, 3) + " N)";
}

}  // namespace

ResidualStudy study_residual(const std::vector<SeriesView>& series, double sign, double scale,
                             const Thresholds& th) {
  ResidualStudy s;
  const std::vector<double> all = pool_residuals(series, s);
  const std::string a = significant(th.alpha, 2);  // the level, as written in the thresholds

  // Is it noise? Decisive: runs, Ljung-Box, periodicity; reported: Durbin-Watson, Jarque-Bera, noise ratio.
  const SerialSums m = serial_sums(series);
  s.diagnostics.push_back(runs_diagnostic(m, th, a));
  s.diagnostics.push_back(ljung_box_diagnostic(m, th, a));
  s.diagnostics.push_back(durbin_watson_diagnostic(m));
  s.diagnostics.push_back(jarque_bera_diagnostic(all, th, a));
  s.diagnostics.push_back(noise_ratio_diagnostic(s, th));
  s.diagnostics.push_back(periodicity_diagnostic(series, th, a, s.period));
  for (const auto& d : s.diagnostics)
    if (d.decisive && !d.passed) s.structured = true;

  // Where it lives.
  const ResidualGroups groups = group_residuals(series, sign, scale, s.by_test);
  summarise_groups(groups, series.size(), s);
  s.where = where_largest(s);
  return s;
}

std::string describe_signature(const ResidualStudy& s, const Thresholds& th) {
  if (!s.structured) return "";
  std::vector<std::string> parts;
  for (const auto& d : s.diagnostics)
    if (d.name == "periodicity" && !d.passed)
      parts.push_back("periodic at " + significant(s.period.frequency_hz, 3) + " Hz (Fisher g " +
                      significant(s.period.g, 3) + ", p " + pstr(s.period.p) + ")");
  if (std::isfinite(s.first_cycle_ratio) && s.first_cycle_ratio > 2.0)
    parts.push_back("confined to the first cycle (its RMS " + significant(s.first_cycle_ratio, 3) +
                    " x that of later cycles)");
  if (std::isfinite(s.worst_test_ratio) && s.worst_test_ratio > 2.0) {
    const auto w = std::max_element(s.by_test.begin(), s.by_test.end(),
                                    [](const GroupStat& a, const GroupStat& b) { return a.rms < b.rms; });
    parts.push_back("concentrated in test '" + w->group + "' (RMS " + significant(s.worst_test_ratio, 3) +
                    " x the median test)");
  }
  if (std::isfinite(s.rate_correlation) && std::abs(s.rate_correlation) > 0.8)
    parts.push_back(std::string(s.rate_correlation > 0 ? "growing" : "falling") + " with rate (Spearman " +
                    significant(s.rate_correlation, 3) + " of test RMS vs ramp rate)");
  if (parts.empty()) parts.push_back("autocorrelated without a simple signature");
  std::string out;
  for (const auto& p : parts) out += (out.empty() ? "" : "; ") + p;
  if (!s.where.empty()) out += "; " + s.where;
  (void)th;
  return out;
}

}  // namespace tmlab::discover
