// The rig options of the command line (`tmlab rig`, `tmlab converge TEST`): the test's name, the
// sample, fixture, mesh, loading and material options of apps/tmlab/command_specs_calibration.cpp
// (add_rig_options) turned into a rigs::RigSpec, with each command's defaults in one place.
#pragma once

#include "apps/tmlab/options/parsed_options.hpp"
#include "calibration/rigs/rig.hpp"

#include <string>

namespace tmlab::cli {

/// The test a name denotes: the data format's names or the short forms unconfined, confined,
/// tension (UsageError otherwise).
rigs::RigTest rig_test(const std::string& name);
/// Whether `name` denotes a test (rig_test would accept it).
bool is_rig_test(const std::string& name);

/// The mesh resolution and the load steps of a rig: the contact rule (the default) or, with --cells,
/// --layers or --grading, the explicit form starting from `cells0` and `layers0` (docs/rigs.md).
/// Whether the explicit mesh form (--cells, --layers, --grading) is asked for; refused (UsageError)
/// together with the contact rule's --contact-cells / --rim-cells.
bool explicit_mesh_given(const ParsedOptions& p);
void apply_resolution(const ParsedOptions& p, rigs::RigSpec& s, int cells0, int layers0);
/// The material section and the model.
void apply_material(const ParsedOptions& p, rigs::RigSpec& s);

/// The rig of `test` from the options: the test's defaults (platen tests: the phantom's 50 x 30 mm
/// cylinder, 8 cells and 10 layers; tension gripped), then the sample, fixture, mesh, loading and
/// material options given; `name` names the case.
rigs::RigSpec rig_from_options(const ParsedOptions& p, rigs::RigTest test, const std::string& name);

/// The first rig option given (sample, fixture, mesh, loading or material), "" when none.
std::string first_rig_option_given(const ParsedOptions& p);

}  // namespace tmlab::cli
