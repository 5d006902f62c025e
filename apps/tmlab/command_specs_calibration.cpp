// The option tables of the measured-data commands: data, rig, fit, discover (command_specs.hpp).
#include "command_specs.hpp"

#include "calibration/rigs/rig.hpp"

#include <limits>

namespace tmlab::cli {

namespace {

OptionSpec overwrite_option() { return flag("--overwrite", "replace files already in DIR"); }

/// The sample, fixture and loading options of a rig (`tmlab rig TEST`, `tmlab converge TEST`).
void add_rig_sample_loading(std::vector<OptionSpec>& o) {
  o.push_back(text("--shape", "block|cylinder", "the sample's shape"));
  o.push_back(numbers("--size", "X,Y,Z", 3, "block size, m"));
  o.push_back(decimal("--radius", "R", Interval{}, "cylinder radius, m"));
  o.push_back(decimal("--height", "H", Interval{}, "sample height, m"));
  o.push_back(text("--indenter", "sphere|flat_punch", "the indenter"));
  o.push_back(decimal("--indenter-radius", "R", Interval{}, "indenter radius, m"));
  o.push_back(numbers("--at", "CX,CY", 2, "where the indenter presses, m"));
  o.push_back(text("--bottom", "bonded|frictionless", "the support under the sample"));
  o.push_back(text("--platens", "bonded|frictionless", "the platens' interface"));
  o.push_back(
      text("--indenter-contact", "frictionless|bonded", "the indenter's surface (default frictionless)"));
  o.push_back(decimal("--depth", "D", Interval{}, "indentation or compression depth, m (default 10 % of H)"));
  o.push_back(decimal("--ramp", "T", Interval{}, "ramp time, s (default 1)"));
  o.push_back(decimal("--hold", "T", Interval{}, "hold time, s (default 0)"));
  o.push_back(whole("--cycles", "N", 1, 100000, "load-unload cycles instead of ramp and hold"));
}

/// The mesh and material options of both forms of `tmlab rig` (and of `tmlab converge TEST`).
void add_rig_mesh_material(std::vector<OptionSpec>& o) {
  o.push_back(
      whole("--cells", "N", rigs::kMinCells, rigs::kMaxCells, "cells across the sample (default: per test)"));
  o.push_back(whole("--layers", "N", 1, rigs::kMaxLayers, "cells through the height (default: per test)"));
  o.push_back(decimal("--grading", "P", Interval{}, "grading towards the indenter (1 = uniform)"));
  o.push_back(whole("--contact-cells", "N", 1, rigs::kMaxContactCells,
                    "cells across the largest contact radius (the contact rule; default " +
                        std::to_string(rigs::kDefaultContactCells) + ")"));
  o.push_back(whole("--rim-cells", "N", 1, rigs::kMaxContactCells,
                    "platen rigs: cells across min(radius, height/2) (default " +
                        std::to_string(rigs::kDefaultRimCells) + ")"));
  o.push_back(decimal("--refine", "R", Interval{}, "multiply every cell count by R (convergence levels)"));
  o.push_back(whole("--steps-per-segment", "N", 1, rigs::kMaxLoadSteps,
                    "quasi-static load steps per history segment (--data: per sample)"));
  o.push_back(text("--material", "JSON", "the case file's material section"));
  o.push_back(decimal("--E", "PA", Interval{}, "Young's modulus"));
  o.push_back(decimal("--nu", "V", Interval{}, "Poisson's ratio"));
  o.push_back(decimal("--density", "RHO", Interval{}, "density, kg/m^3"));
  o.push_back(text("--model", "M", "the case's model (tensor_mass, hyperelastic_tl, ...)"));
  o.push_back(text("--element", "E",
                   "the case's mesh.element: p1, p1_anp, p2, p2_mean_dilatation (not p1: model\n"
                   "hyperelastic_tl unless --model is given; docs/elements.md)"));
}

}  // namespace

CommandSpec data_convert_spec() {
  return {"data convert",
          {"FILE --out DIR [options]"},
          "convert measured data (the silicone phantom CSVs) to\n"
          "tmlab-measured/1: DIR/NAME.csv + DIR/NAME.json (docs/measured-data.md)",
          {text("--out", "DIR", "where NAME.csv and NAME.json go"),
           choice("--platens", {"frictionless", "bonded"}, "the platens' interface").def("frictionless"),
           overwrite_option()}};
}

CommandSpec data_show_spec() {
  return {"data show",
          {"NAME.csv [options]"},
          "read a tmlab-measured/1 data set strictly; a summary per test and\n"
          "a plot (default results/data/NAME/NAME.png)",
          {text("--out", "DIR", "where NAME.png goes"), no_plots_option(), overwrite_option()}};
}

CommandSpec rig_spec() {
  CommandSpec c{"rig",
                {"indentation|unconfined|confined|tension --out DIR [options]",
                 "--data NAME.csv [--test ID] --out DIR [mesh and material options]"},
                "a test rig as DIR/NAME.msh + DIR/NAME.json, an ordinary case file for\n"
                "tmlab run / compare (docs/rigs.md); --data: the rig of a tmlab-measured/1\n"
                "test (sample, fixture and indenter from NAME.json, driven by its measured\n"
                "displacement column)",
                {text("--out", "DIR", "where NAME.json and NAME.msh go"),
                 text("--name", "N", "the case's name (default: the test's)"), overwrite_option(),
                 text("--data", "NAME.csv", "the rig of a measured data set"),
                 text("--test", "ID", "the test of the data set (with --data)")}};
  add_rig_sample_loading(c.options);
  add_rig_mesh_material(c.options);
  return c;
}

CommandSpec converge_spec() {
  CommandSpec c{"converge",
                {"indentation|unconfined|confined|tension [rig options] [options]", "CASE [options]"},
                "a convergence study: the rig (the options of tmlab rig) or the case\n"
                "on --levels meshes refined by --ratio (a case's mesh: every tet split\n"
                "into 8) or, --refine-in time, time steps divided by --ratio; each\n"
                "quantity's observed order, Richardson extrapolation, errors and GCI;\n"
                "results/converge/NAME/ (converge.json, .md, PNG; docs/convergence.md)",
                {whole("--levels", "N", 3, 8, "number of meshes (or time steps), coarsest first")
                     .def("3")
                     .role(kResult),
                 choice("--refine-in", {"space", "time"},
                        "what the levels refine: the mesh, or the time step (the mesh fixed;\n"
                        "a rig's --steps-per-segment, a case's solver.steps or solver.dt)")
                     .def("space")
                     .role(kResult),
                 decimal("--ratio", "R", open(1.0, 10.0),
                         "refinement ratio per level: of a rig's cells and layers (a case's\n"
                         "mesh: 2), or with --refine-in time of the steps")
                     .def("2")
                     .role(kResult),
                 text("--quantity", "NAME",
                      "a series of timeseries.h5 (default: the contact force and radius, else\n"
                      "the moving condition's reaction, and each probe's displacement)")
                     .repeat()
                     .role(kResult),
                 decimal("--time", "T", Interval{},
                         "when to take the quantities, s (default: the end of the loading\n"
                         "and the last time)")
                     .repeat()
                     .role(kResult),
                 choice("--linear", {"auto", "ldlt", "cholmod"},
                        "the levels' sparse direct solver (solver.linear; default: the case's)")
                     .role(kManifest),
                 text("--out", "DIR", "the result folder (default <results>/converge/NAME)"),
                 text("--name", "N", "the rig's name (default: the test's)").role(kManifest),
                 flag("--resume",
                      "continue an interrupted or failed study: its complete levels of the\n"
                      "same plan reused, the others run again"),
                 results_option(), no_plots_option()}};
  add_rig_sample_loading(c.options);
  add_rig_mesh_material(c.options);
  return c;
}

CommandSpec fit_spec() {
  return {
      "fit",
      {"DATA.csv --model SPEC [options]"},
      "fit a law to tmlab-measured/1 data with error bars; SPEC is\n"
      "LAW[:N][+prony:M][,NAME=VALUE...], e.g. ogden:2,poisson=0.49;\n"
      "results/fit/NAME-LAW/ (fit.json, fit.h5, PNG; docs/identification.md)",
      {text("--model", "SPEC", "the law to fit (required)").role(kResult),
       text("--out", "DIR", "the result folder (default results/fit/NAME-LAW)"),
       text("--fix", "NAME=VALUE", "hold a parameter fixed").repeat().role(kResult),
       text("--weight", "TEST=W", "weight of one test").repeat().role(kResult),
       choice("--forward", {"closed_form", "fe_rig", "auto"}, "the forward model")
           .def("closed_form")
           .role(kResult),
       text("--mesh", "C,L", "FE rig: cells, layers").def("12,6").role(kResult),
       whole("--substeps", "N", 1, 10000, "FE rig: load steps per sampling interval").def("1").role(kResult),
       choice("--discretisation-check", {"on", "off"},
              "FE rig: one solve on the refined rig at the optimum and each\n"
              "parameter's discretisation shift (default on for fe_rig; not\n"
              "applicable to a closed-form forward model: refused there)")
           .role(kResult),
       decimal("--refine-ratio", "R", open(1.0, std::numeric_limits<double>::infinity()),
               "FE rig: the refined rig's mesh ratio in h (default 2: --mesh x 2)")
           .role(kResult),
       choice("--global", {"multistart", "siman"}, "the global stage").def("multistart").role(kResult),
       text("--prior", "NAME=MEAN:SD", "a Gaussian prior").repeat().role(kResult),
       decimal("--noise", "SIGMA", positive(), "the force noise, N (default: from the residual)")
           .role(kResult),
       whole("--local-runs", "N", 1, 10000, "best candidates refined").def("3").role(kResult),
       whole("--siman-evaluations", "N", 1, 10000, "trials of the siman stage").def("3000").role(kResult),
       choice("--cost", {"least_squares", "l1"}, "the misfit").def("least_squares").role(kResult),
       whole("--starts", "N", 1, 10000, "candidate starts of the global stage").def("12").role(kResult),
       whole("--threads", "N", 1, 10000, "forward solves in parallel").def("2").role(kResult),
       whole("--seed", "N", 1, 10000, "seed of the global stage").def("1").role(kResult),
       flag("--geodesic", "geodesic acceleration in Levenberg-Marquardt").role(kResult),
       flag("--no-profile", "no profile likelihood").role(kResult),
       text("--relaxation-bands", "FLOOR,CEILING",
            "tau_j in ordered bands of [FLOOR x sampling interval, CEILING x duration]")
           .role(kResult),
       no_plots_option(),
       flag("--quiet", "no progress lines"),
       checkpoint_option(),
       flag("--resume", "continue an interrupted fit from its checkpoint")}};
}

CommandSpec discover_spec() {
  return {
      "discover",
      {"DATA.csv [options]",
       "--benchmark [--quick] [--rig R1,R2] [--only TRUTH1,TRUTH2] [--write-sets] [options]"},
      "baseline St VK + 2 Prony terms, the residual studied, effects from\n"
      "a library added when BIC and held-out prediction support them;\n"
      "results/discover/NAME/ (index.html, report.json; docs/discover.md)",
      {text("--out", "DIR", "the result folder (default results/discover/NAME)"),
       decimal("--poisson", "V", open(0.0, 0.4999), "Poisson's ratio of the baseline")
           .def("0.49")
           .role(kResult),
       flag("--free-poisson", "fit Poisson's ratio too").role(kResult),
       text_list("--effects", "A,B", "only these effects (default: the library)").role(kResult),
       whole("--rounds", "N", 1, 20, "selection rounds").def("4").role(kResult),
       whole("--baseline-prony", "M", 0, 4, "Prony terms of the baseline").def("2").role(kResult),
       whole("--max-samples", "N", 50, 1000000, "the data decimated to about N samples")
           .def("1500")
           .role(kResult),
       whole("--starts", "N", 1, 1000, "multi-start candidates per fit").def("8").role(kResult),
       whole("--threads", "N", 1, 64, "fits in parallel").def("2").role(kResult),
       whole("--seed", "N", 1, 1000000, "seed of the multi-start").def("1").role(kResult),
       flag("--no-test-control", "no test-consistency control in the selection").role(kResult),
       choice("--forward", {"closed_form", "fe_rig"}, "fe_rig: refit baseline and final model on the FE rig")
           .def("closed_form")
           .role(kResult),
       text("--mesh", "C,L", "FE rig: cells, layers").def("8,4").role(kResult),
       whole("--substeps", "N", 1, 100, "FE rig: load steps per sampling interval").def("1").role(kResult),
       whole("--fe-iterations", "N", 1, 200, "FE rig: Levenberg-Marquardt iterations").def("8").role(kResult),
       whole("--fe-max-samples", "N", 20, 1000000, "FE rig: samples of the refit").def("300").role(kResult),
       flag("--benchmark", "the synthetic benchmark instead of DATA.csv").role(kResult),
       flag("--quick", "the quick benchmark").role(kResult),
       text("--rig", "R1,R2", "only the benchmark sets of these rigs").role(kResult),
       text("--only", "TRUTH1,TRUTH2", "only the benchmark sets of these truths").role(kResult),
       flag("--write-sets", "write each benchmark set as DATA.csv"),
       no_plots_option(),
       flag("--quiet", "no progress lines"),
       checkpoint_option(),
       flag("--resume", "continue an interrupted discovery or benchmark")}};
}

}  // namespace tmlab::cli
