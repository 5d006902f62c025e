// Synthetic tmlab-measured/1 data sets made in memory: indentation by a sphere (ramp and hold to
// several depths), unconfined compression of a cylinder and of a block. Their forces are
// placeholders to fill from a forward model (set_forces); the fit tests, the identification checks
// (verification/checks/fit_checks.cpp) and the developer tool tools/fit_synthetic_data.cpp use them.
#pragma once

#include "calibration/data/measured_data.hpp"

#include <vector>

namespace tmlab::fit::synthetic {

/// Sphere (radius 5 mm) into a half-space (or a bonded layer of `thickness` m when > 0): one test per
/// depth, a 1 s ramp then a hold to t_end, samples every 0.1 s on the ramp and 0.25 s in the hold.
/// Forces are zero: fill them from a forward model.
measured::DataSet indentation_data(const std::vector<double>& depths, double t_end = 20.0,
                                   double thickness = 0.0);

/// Unconfined compression of a 50 mm x 30 mm cylinder to `strain`, n samples, frictionless platens.
measured::DataSet compression_data(double strain, int n);

/// Unconfined compression of a block (20 x 20 x 10 mm) to each strain: a 1 s ramp (samples every
/// 0.2 s) then a hold to t_end (every 0.5 s), one test per strain ("s1", "s2", ...), bonded or
/// frictionless platens. Named "synthetic_block"; forces are 1 N: fill them from a forward model.
measured::DataSet block_compression_data(const std::vector<double>& strains, double t_end, bool bonded);

/// Puts `force` (Observations order) into the tests of `d`.
void set_forces(measured::DataSet& d, const std::vector<double>& force);

}  // namespace tmlab::fit::synthetic
