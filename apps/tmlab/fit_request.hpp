// The request of `tmlab fit` (issue 14; docs/identification.md): its options parsed and checked
// (UsageError otherwise), and what the manifest and --resume record of them.
#pragma once

#include "cli_args.hpp"

#include "calibration/fit/fitter.hpp"
#include "calibration/fit/model_spec.hpp"
#include "calibration/fit/rig_forward_model.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace tmlab::cli {

/// What the command line asks for, parsed and checked (UsageError otherwise). The choices keep the
/// words the user gave: the manifest records them.
struct FitRequest {
  fit::ModelSpec spec;
  std::vector<std::pair<std::string, double>> fixes, weights;
  std::string cost, global, forward;
  fit::FitOptions options;
  std::vector<fit::Prior> priors;
  fit::RigForwardModelOptions fe;
  double band_floor = 0.0, band_ceiling = 0.0;  ///< --relaxation-bands (0: off)
};

/// The request of `p` (--model is required; the caller checks its presence).
FitRequest parse_fit_request(const ParsedOptions& p);

/// What --resume must match: everything that changes the result (the data files' contents, the
/// options the table marks kFingerprint, the engine's own limits), not what only changes where or
/// how it is shown. The manifest's config is the table's kManifest options (fit_spec()).
nlohmann::json fit_fingerprint(const ParsedOptions& p, const FitRequest& q, const std::filesystem::path& csv);

}  // namespace tmlab::cli
