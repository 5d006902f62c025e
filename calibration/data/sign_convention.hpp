// The sign convention of tmlab-measured/1 (docs/measured-data.md) as the fit and the discovery loop
// need it: displacement_m positive into the sample (indentation depth, shortening of a compressed
// sample) and negative in tension; force_N positive when the sample pushes back, so positive in
// indentation and compression and negative in tension. A force of the wrong sign does not stop a
// fit by itself: the forward models' force has the convention's sign, so the fit drives the
// modulus to zero (or a discovery explains the curve as drift). One shared check refuses it first.
#pragma once

#include "calibration/data/measured_data.hpp"

#include <string>

namespace tmlab::measured {

/// +1 when the convention makes the force of a test of kind `t` positive (indentation,
/// compression), -1 when negative (tension).
int force_sign(TestType t);

/// Checks every test of `data` against the force sign of its kind. A test is refused when the sum
/// of its forces has the wrong sign: noise of either sign near zero (before contact, at rest) hardly
/// moves the sum, a flipped curve turns it over. tmlab::Error naming `file` (the data's CSV; the
/// data set's name when empty), the test, its kind and the convention, with how many samples have
/// the wrong sign and what to do ("flip the sign of force_N").
void check_force_sign(const DataSet& data, const std::string& file);

}  // namespace tmlab::measured
