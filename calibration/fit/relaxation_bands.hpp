// Bounds on the relaxation times of a fit's Prony terms from the data's time sampling
// (docs/identification.md, "Relaxation-time bands"). Two facts make an unbounded Prony fit
// ill-posed on a ramp-and-hold test:
//   - a term much faster than the shortest sampling interval has relaxed completely between two
//     samples: the data see it only as a little extra stiffness on the ramp, so its weight and time
//     trade against each other (tau -> 0 with e growing) and its standard error is infinite;
//   - a term much slower than the whole test has not relaxed by its end: it is long-term stiffness,
//     and trades against E_inf;
// and with two or more terms, two terms may swap or merge (both at one time scale), which makes
// J^T J singular. The bands below bound each tau from below by `floor_fraction` times the data's
// shortest sampling interval and from above by `ceiling_factor` times the longest test's duration,
// and split that range log-uniformly into one band per term, in order: tau1 in the fastest band,
// tauM in the slowest. Terms can then neither swap nor merge, and a term that ends on a band's edge
// (ParameterResult / bound_reached) says so instead of collapsing silently.
#pragma once

#include "calibration/data/measured_data.hpp"
#include "calibration/fit/model_spec.hpp"
#include "calibration/fit/parameter.hpp"

#include <string>
#include <vector>

namespace tmlab::fit {

/// The admissible range of relaxation times, s.
struct RelaxationRange {
  double tau_min = 0.0, tau_max = 0.0;
};

/// tau_min = floor_fraction x the shortest positive sampling interval of any test of `data`,
/// tau_max = ceiling_factor x the longest test's duration. tmlab::Error (naming the data set) when a
/// test has fewer than 2 samples, the factors are not positive, or tau_min >= tau_max.
RelaxationRange relaxation_range(const measured::DataSet& data, double floor_fraction, double ceiling_factor);

/// Puts tau1 .. tauM of `spec` (M = spec.prony_terms) in ordered, disjoint bands: [tau_min,
/// tau_max] split log-uniformly into M, tau_j bounded by band j; its starting value the band's
/// geometric centre and its start range the band's inner 80 % (in log). No change without Prony
/// terms. tmlab::Error when a tau is fixed (a fixed term has no band) or a parameter is missing.
void band_relaxation_times(std::vector<Parameter>& params, const ModelSpec& spec,
                           const RelaxationRange& range);

/// "lower" or "upper" when x lies within `fraction` of the (finite, two-sided) bound interval of p
/// from that bound, "" otherwise (and for a parameter without two finite bounds, or a fixed one).
std::string bound_reached(const Parameter& p, double x, double fraction = 1e-3);

}  // namespace tmlab::fit
