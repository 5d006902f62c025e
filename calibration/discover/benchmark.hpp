// The benchmark of `tmlab discover --benchmark` (issue 15; docs/discover.md): synthetic data sets
// made with the forward models of effects.hpp (one library effect present each), noise-only sets,
// and sets with effects outside the library; the loop runs on each without being told which, and
// the benchmark scores what it found (confusion matrix, false positives, median error reduction).
//
// The protocol of every set (fixed, realistic for a soft-tissue phantom): unconfined compression of
// a cylinder (radius 10 mm, height 10 mm, frictionless platens), three tests at engineering strain
// rates 0.02, 0.05 and 0.1 /s: ramp to 25 % strain, hold 20 s, unload at the same rate, rest 5 s,
// sampled at 5 Hz (sphere indentation and tension sets: benchmark.cpp); the true baseline is St VK (E_inf 30
// kPa, nu 0.49) with Prony terms e = 12, 8 kPa, tau = 0.5, 15 s; white Gaussian noise of 0.3 % of the peak
// force (seeded).
#pragma once

#include "calibration/data/measured_data.hpp"
#include "calibration/discover/discover.hpp"

#include <nlohmann/json.hpp>

#include <functional>
#include <string>
#include <vector>

namespace tmlab::discover {

enum class Truth { library, noise_only, outside_library };

/// The rig of a synthetic set: the platen protocol above, sphere indentation, uniaxial tension or
/// confined compression (benchmark.cpp gives their protocols).
enum class BenchmarkRig { unconfined, sphere, tension, confined };
std::string to_string(BenchmarkRig r);

struct SyntheticSet {
  std::string name;   ///< e.g. "bench-contact_offset-1"
  std::string truth;  ///< a library effect, "noise_only", or an outside effect
  Truth kind = Truth::library;
  BenchmarkRig rig = BenchmarkRig::unconfined;
  measured::DataSet data;
};

/// The outside-library effects the benchmark plants: "actuator_resonance" (a 0.7 Hz oscillation
/// of 2 % of the peak force, always present), "preconditioning" (the first test's force 15 % higher:
/// the virgin sample before Mullins softening, exactly a factor per test) and
/// "mullins_first_loading" (the first test's force raised by 15 % x its strain over its peak
/// strain: a virgin stiffness growing with the strain reached, not a factor per test).
std::vector<std::string> outside_effects();

/// One set with `truth` present (an effect_library() name, "noise_only" or an outside effect).
SyntheticSet make_set(const std::string& truth, unsigned seed, BenchmarkRig rig = BenchmarkRig::unconfined);

/// The sets of the full benchmark (every applicable library effect on platen data and separate bulk
/// and shear relaxation, three noise-only sets, each outside effect; on sphere indentation the
/// indentation effects and some of every kind with a noise-only set; on tension a Prony term, a law,
/// an offset and a noise-only set; on confined compression a Prony term, a contact offset and a
/// noise-only set) or of the quick one (a subset that runs in a few minutes).
std::vector<SyntheticSet> benchmark_sets(bool quick);

struct BenchmarkEntry {
  std::string name, truth, rig;
  Truth kind = Truth::library;
  std::vector<std::string> found;  ///< the final model's effects beyond the baseline (effects_in)
  bool unexplained = false;
  std::string signature;
  double rms_before = 0.0, rms_after = 0.0, peak = 0.0, seconds = 0.0;
  bool correct = false;  ///< library: exactly the truth found (same family for laws); noise: nothing;
                         ///< outside: unexplained structure reported
};

struct BenchmarkResult {
  std::vector<BenchmarkEntry> entries;
  std::vector<std::string> rows, columns;  ///< truths; effects found + "nothing"
  std::vector<std::vector<int>> confusion;
  int library_sets = 0, library_correct = 0;
  int library_exact = 0;  ///< exactly the planted effect, the law itself for a law (no family credit)
  int noise_sets = 0, noise_false_positives = 0;
  int outside_sets = 0, outside_flagged = 0, outside_forced = 0;
  double median_error_reduction = 0.0;  ///< over library sets: 1 - rms_after / rms_before
  double diagonal_fraction = 0.0;       ///< library_correct / library_sets
};

/// The resume hook of run_benchmark (tmlab discover --benchmark --resume; the CLI owns the
/// checkpoint): the entries of the sets an interrupted benchmark finished are taken from `restored`
/// (in set order; an entry of another set is a tmlab::Error), and each set that runs is handed to
/// `finished`. A set interrupted half-way runs again from its start.
struct BenchmarkLog {
  std::vector<BenchmarkEntry> restored;
  std::function<void(const BenchmarkEntry&)> finished;
};

/// Runs the loop on every set (progress through o.progress).
BenchmarkResult run_benchmark(const std::vector<SyntheticSet>& sets, const Options& o,
                              BenchmarkLog* log = nullptr);

nlohmann::json to_json(const BenchmarkResult& b);

/// The sets of `sets` on one of `rigs` (comma-separated rig names, to_string(BenchmarkRig); "" keeps
/// every rig) whose truth is one of `truths` (comma-separated; "" keeps every truth), in order.
/// Empty when none is left (the caller says which option emptied it).
std::vector<SyntheticSet> select_sets(std::vector<SyntheticSet> sets, const std::string& rigs,
                                      const std::string& truths);

/// True when `found` is the right answer for a library `truth`: exactly one effect, the truth, or
/// (for a *_hyperelastic truth) one *_hyperelastic effect: the laws approximate each other over one
/// strain range, so the family is scored, and the law within it reported in the matrix. A
/// separate_bulk_shear_relaxation truth is matched by nothing or by extra_prony_term alone: on one
/// rig's forces bulk relaxation is one more exponential of the rig's relaxation function
/// (bulk_shear.hpp), which the baseline's two free Prony terms may absorb to the noise (then
/// nothing is the honest answer) or one more term takes; the loop does not try the effect itself
/// there (not_applicable); library_exact does not count it. (run_benchmark also requires no
/// unexplained structure for it.)
bool library_match(const std::string& truth, const std::vector<std::string>& found);

}  // namespace tmlab::discover
