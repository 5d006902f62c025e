// A verification case as data: verification/cases/<name>/verify.json plus a README.md.
//
// The JSON says what is checked and against what (title, what, reference), which check function
// measures it (`kind`, with its `parameters`), and how the measurements are judged: tolerance
// checks on scalar metrics and convergence checks on series, each with the rationale for its
// tolerance. The C++ check functions only measure; every threshold lives here, beside its reason.
//
//   {
//     "title": "Tensor-mass force and tangent are derivatives of the energy",
//     "what": "central finite differences of W and f on a perturbed irregular mesh",
//     "reference": "f = dW/du, K = df/du",
//     "labels": ["kernel"],
//     "suite": "fast",                       // fast (default run) | full (tmlab verify --full)
//     "kind": "kernel.finite_difference",
//     "parameters": { ... },                 // read strictly by the check function
//     "checks": [
//       {"metric": "force_rel_error", "max": 1e-7, "rationale": "O(h^2) FD truncation ..."},
//       {"metric": "min_dissipation", "min": 0.0, "rationale": "..."}
//     ],
//     "convergence": [
//       {"series": "l2_error", "expected_order": 2.0, "order_tolerance": 0.15, "fit_points": 3,
//        "finest_max": 2e-4, "rationale": "P1: ||u-u_h||_L2 = O(h^2); finest bound from ..."}
//     ],
//     "report": ["observed_locking_ratio"]    // metrics shown without a tolerance (documented)
//   }
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace tmlab::verify {

/// A bound on one scalar metric: measured <= max (an error), or measured >= min (e.g. dissipation).
struct MetricCheck {
  std::string metric;
  enum class Bound { Max, Min } bound = Bound::Max;
  double limit = 0.0;
  std::string rationale;
};

/// An observed order on one series (x = h or dt, y = error), fitted by least squares of log y on
/// log x over the `fit_points` finest points (all when 0), plus an absolute bound on the finest
/// error, so that converging to a wrong answer fails.
struct ConvergenceCheck {
  std::string series;
  double expected_order = 0.0;
  double order_tolerance = 0.0;  ///< |observed - expected| <= order_tolerance
  int fit_points = 0;
  double finest_max = 0.0;  ///< finest error <= finest_max
  std::string rationale;
};

struct VerificationCase {
  std::string name;  ///< the directory name
  std::filesystem::path dir;
  std::string title;
  std::string what;       ///< what is checked, one or two sentences
  std::string reference;  ///< the equation or reference solution
  std::vector<std::string> labels;
  std::string suite = "fast";  ///< "fast" or "full"
  std::string kind;            ///< the check function (CheckRegistry)
  nlohmann::json parameters = nlohmann::json::object();
  std::vector<MetricCheck> checks;
  std::vector<ConvergenceCheck> convergence;
  std::vector<std::string> report;  ///< informational metrics (no tolerance)

  bool has_label(const std::string& label) const;
  /// The case's verify.json.
  std::filesystem::path spec_file() const { return dir / "verify.json"; }
};

/// Reads <dir>/verify.json (strictly: unknown keys, missing tolerances or rationales, a suite other
/// than fast/full are errors naming the file and key) and checks that <dir>/README.md exists.
VerificationCase load_case(const std::filesystem::path& dir);

/// Every case under `root` (one directory each, sorted by name). Throws for a directory without
/// verify.json, or for two cases of the same name.
std::vector<VerificationCase> load_catalogue(const std::filesystem::path& root);

}  // namespace tmlab::verify
