// fit_synthetic_data: writes a synthetic tmlab-measured/1 data set made by the FE-rig forward model
// at given parameters plus Gaussian noise, for measuring and demonstrating FE fits (issue 14,
// docs/identification.md "Measured: a 6-parameter FE fit"). Not a `tmlab` command: a developer tool.
//
//   fit_synthetic_data OUTDIR NAME SPEC NOISE_FRACTION SEED STRAINS PLATENS CELLS,LAYERS NAME=VALUE...
//     STRAINS   comma-separated platen strains of unconfined compression of a 20 x 20 x 10 mm block,
//               one test each: a 1 s ramp (samples every 0.2 s), then a hold to 10 s (every 0.5 s)
//     PLATENS   bonded | frictionless
//     CELLS,LAYERS the rig's mesh (fit with the same --mesh to fit the model that made the data)
//     NAME=VALUE every parameter of SPEC (SI units)
#include "calibration/data/measured_data.hpp"
#include "calibration/fit/model_spec.hpp"
#include "calibration/fit/rig_forward_model.hpp"
#include "calibration/fit/surrogates.hpp"
#include "calibration/fit/synthetic_data.hpp"
#include "core/base/error.hpp"
#include "core/base/number.hpp"

#include <cmath>
#include <cstdint>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>

namespace {

/// The number `text` given as `what` (the strict grammar of core/base/number.hpp).
double decimal(const std::string& text, const std::string& what) {
  double v = 0.0;
  std::string why;
  if (!tmlab::parse_decimal(text, v, why)) throw tmlab::Error(what + ": " + why);
  return v;
}

/// The whole number `text` given as `what`, within [min, max].
std::int64_t whole(const std::string& text, const std::string& what, std::int64_t min, std::int64_t max) {
  std::int64_t v = 0;
  std::string why;
  if (!tmlab::parse_whole(text, min, max, v, why)) throw tmlab::Error(what + ": " + why);
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace tmlab;
  namespace ms = tmlab::measured;
  if (argc < 9) {
    std::cerr << "usage: fit_synthetic_data OUTDIR NAME SPEC NOISE_FRACTION SEED STRAINS PLATENS "
                 "CELLS,LAYERS NAME=VALUE...\n";
    return 2;
  }
  try {
    const fit::ModelSpec spec = fit::parse_model_spec(argv[3]);
    const double noise = decimal(argv[4], "NOISE_FRACTION");
    if (!(noise >= 0.0)) throw Error("NOISE_FRACTION: must be >= 0 (got " + std::string(argv[4]) + ")");
    const auto seed =
        static_cast<unsigned long>(whole(argv[5], "SEED", 0, std::numeric_limits<std::int64_t>::max()));
    std::vector<double> strains;
    std::stringstream ss(argv[6]);
    for (std::string item; std::getline(ss, item, ',');) strains.push_back(decimal(item, "STRAINS"));
    if (strains.empty()) throw Error("STRAINS: give at least one strain");
    const std::string platens = argv[7];
    if (platens != "bonded" && platens != "frictionless")
      throw Error("PLATENS: must be bonded or frictionless (got '" + platens + "')");
    const bool bonded = platens == "bonded";
    std::vector<std::pair<std::string, double>> truth;
    fit::RigForwardModelOptions fe;
    const std::string mesh = argv[8];
    const std::size_t comma = mesh.find(',');
    if (comma == std::string::npos) throw Error("CELLS,LAYERS: expected two numbers, got '" + mesh + "'");
    fe.mesh.cells = static_cast<int>(whole(mesh.substr(0, comma), "CELLS", 1, 1000));
    fe.mesh.layers = static_cast<int>(whole(mesh.substr(comma + 1), "LAYERS", 1, 1000));
    for (int i = 9; i < argc; ++i) {
      const std::string a = argv[i];
      const std::size_t eq = a.find('=');
      if (eq == std::string::npos) throw Error("expected NAME=VALUE, got '" + a + "'");
      truth.emplace_back(a.substr(0, eq), decimal(a.substr(eq + 1), a.substr(0, eq)));
    }
    ms::DataSet d = fit::synthetic::block_compression_data(strains, 10.0, bonded);
    d.meta.name = argv[2];
    d.meta.source = "synthetic: fit_synthetic_data, FE rig (mesh " + std::string(argv[8]) + "), " + argv[3];
    d.meta.license = "CC0-1.0";
    fit::Problem p = fit::make_data_problem(d, spec, truth);
    std::vector<double> x;
    for (const auto& q : p.parameters) {
      if (!q.fixed) throw Error("give every parameter of the SPEC: '" + q.name + "' is missing");
      x.push_back(q.value);
    }
    std::vector<double> f = fit::make_rig_forward_model(d, spec, fe)->predict(x);
    double peak = 0.0;
    for (const double v : f) peak = std::max(peak, std::abs(v));
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> n(0.0, noise * peak);
    std::size_t i = 0;
    for (auto& t : d.tests)
      for (double& v : t.force_N) v = f[i++] + n(rng);
    std::cout << ms::write_data_set(d, argv[1]).string() << "\n";
  } catch (const std::exception& e) {
    std::cerr << "fit_synthetic_data: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
