// The option table of every tmlab command (command_specs_*.cpp): each option declared once, with
// its kind, range, default, help line and whether the manifest and the resume fingerprint record it
// (options/option_table.hpp). Parsing, `tmlab help` and the manifests are generated from these.
#pragma once

#include "apps/tmlab/options/option_help.hpp"
#include "apps/tmlab/options/option_table.hpp"

#include <string>
#include <vector>

namespace tmlab::cli {

// The models: command_specs_models.cpp.
CommandSpec demo_spec();
CommandSpec run_spec();
CommandSpec compare_spec();
CommandSpec cases_spec();
CommandSpec mesh_info_spec();
CommandSpec mesh_check_spec();
CommandSpec mesh_quadratic_spec();
CommandSpec version_spec();
CommandSpec help_spec();
// The studies and the catalogue: command_specs_studies.cpp.
CommandSpec paper_spec();
CommandSpec hereditary_spec();
CommandSpec workprecision_spec();
CommandSpec depth_limit_spec();
CommandSpec realtime_spec();
CommandSpec verify_spec();
CommandSpec bench_spec();
// Measured data, rigs and their convergence: command_specs_calibration.cpp.
CommandSpec data_convert_spec();
CommandSpec data_show_spec();
CommandSpec rig_spec();
CommandSpec converge_spec();
CommandSpec fit_spec();
CommandSpec discover_spec();

/// Every command, in the order `tmlab help` lists them.
std::vector<CommandSpec> command_specs();

/// The specs of `command` ("data": data convert and data show); empty when there is none.
std::vector<CommandSpec> specs_of(const std::string& command);

/// `tmlab help`: every command with every option.
std::string usage_text();

/// What to say of a word that is no command: a renamed command's new name ("inversion" ->
/// "depth-limit"), else the nearest command within two edits ("fti" -> "did you mean 'fit'?"), then
/// where the list of commands is. One short message: the full help would scroll it away.
std::string unknown_command_message(const std::string& word);

/// Options shared by several commands, declared once.
OptionSpec results_option();     ///< --results DIR
OptionSpec no_plots_option();    ///< --no-plots
OptionSpec resume_option();      ///< --resume (a study or suite)
OptionSpec checkpoint_option();  ///< --checkpoint-every N|Ts|Tmin|off

}  // namespace tmlab::cli
