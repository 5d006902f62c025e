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
#include "core/base/error.hpp"

#include <cmath>
#include <iostream>
#include <random>
#include <sstream>

int main(int argc, char** argv) {
  using namespace tmlab;
  namespace ms = tmlab::measured;
  if (argc < 9) {
    std::cerr
        << "usage: fit_synthetic_data OUTDIR NAME SPEC NOISE_FRACTION SEED STRAINS PLATENS NAME=VALUE...\n";
    return 2;
  }
  try {
    const fit::ModelSpec spec = fit::parse_model_spec(argv[3]);
    const double noise = std::stod(argv[4]);
    const unsigned long seed = std::stoul(argv[5]);
    std::vector<double> strains;
    std::stringstream ss(argv[6]);
    for (std::string item; std::getline(ss, item, ',');) strains.push_back(std::stod(item));
    const bool bonded = std::string(argv[7]) == "bonded";
    std::vector<std::pair<std::string, double>> truth;
    fit::RigForwardModelOptions fe;
    const std::string mesh = argv[8];
    fe.mesh.cells = std::stoi(mesh.substr(0, mesh.find(',')));
    fe.mesh.layers = std::stoi(mesh.substr(mesh.find(',') + 1));
    for (int i = 9; i < argc; ++i) {
      const std::string a = argv[i];
      const std::size_t eq = a.find('=');
      if (eq == std::string::npos) throw Error("expected NAME=VALUE, got '" + a + "'");
      truth.emplace_back(a.substr(0, eq), std::stod(a.substr(eq + 1)));
    }
    ms::DataSet d;
    d.meta.name = argv[2];
    d.meta.test = ms::TestType::unconfined_compression;
    d.meta.sample.shape = ms::SampleShape::block;
    d.meta.sample.size_m = {0.02, 0.02, 0.01};
    d.meta.sample.bottom = bonded ? ms::Interface::bonded : ms::Interface::frictionless;
    d.meta.sample.platens = d.meta.sample.bottom;
    d.meta.source = "synthetic: fit_synthetic_data, FE rig (mesh " + std::string(argv[8]) + "), " + argv[3];
    d.meta.license = "CC0-1.0";
    for (std::size_t k = 0; k < strains.size(); ++k) {
      ms::Test t;
      t.id = "s" + std::to_string(k + 1);
      for (double s = 0.0; s <= 10.0 + 1e-9; s += (s < 1.0 - 1e-9 ? 0.2 : 0.5)) {
        t.time_s.push_back(s);
        t.displacement_m.push_back(0.01 * strains[k] * std::min(s, 1.0));
        t.force_N.push_back(1.0);
      }
      d.tests.push_back(t);
    }
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
