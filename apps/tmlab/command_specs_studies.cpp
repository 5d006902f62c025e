// The option tables of the studies, the verification catalogue, the real-time loop and the
// benchmarks (command_specs.hpp).
#include "command_specs.hpp"

#include "core/constitutive/prony.hpp"

namespace tmlab::cli {

namespace {

OptionSpec study_resume() { return flag("--resume", "continue an interrupted study (finished runs reused)"); }

}  // namespace

CommandSpec paper_spec() {
  return {"paper",
          {"fig5|fig6|fig7 [--params FILE] [--results DIR] [--no-plots] [--resume]",
           "fig2|fig3|table1|table2 [--quick] [options]"},
          "fig5-7: the liver experiments of Xu et al. 2011 (creep, relaxation,\n"
          "hysteresis) from cases/paper/xu2011_liver.json; fig2, fig3, table1, table2:\n"
          "Section IV-A, tensor-mass fits to Hertz / Lee-Radok reference curves at\n"
          "2-8 mm with standard errors, from cases/paper/xu2011_indentation.json",
          {text("--params", "FILE", "the experiment's parameters (default: the file above)"),
           flag("--quick", "fewer and coarser fits (fig2, fig3, table1, table2 only)").role(kManifest),
           results_option(), no_plots_option(),
           flag("--resume", "reuse the runs (fits) an interrupted figure finished")}};
}

CommandSpec hereditary_spec() {
  std::vector<std::string> forms = prony_history_names();
  forms.push_back("both");
  return {
      "hereditary",
      {"[options]"},
      "the Prony recursions (xu2011 midpoint, exact_linear, backward_euler)\n"
      "against the exact hereditary integral: strain histories, haptic\n"
      "steps, the liver relaxation; results/hereditary/ (docs/hereditary.md)",
      {text_list("--histories", "LIST", "strain history groups").def("ramp_hold,sine,random").role(kResult),
       flag("--liver", "with the liver relaxation study (the default)"),
       flag("--no-liver", "without the liver relaxation study").role(kResult),
       choice("--liver-history", forms,
              "the liver's history forms (default: nodal_force with --quick, else both)")
           .role(kResult),
       flag("--quick", "shorter histories, fewer steps").role(kResult),
       whole("--seed", "N", 0, 9000000000000000LL, "seed of the random history")
           .def("20111101")
           .role(kResult),
       text("--params", "FILE", "the liver's parameters (default cases/paper/xu2011_liver.json)")
           .role(kResult),
       results_option(), no_plots_option(), study_resume()}};
}

CommandSpec workprecision_spec() {
  return {"workprecision",
          {"[options]"},
          "error against CPU time: fixed-step schemes and SUNDIALS;\n"
          "results/workprecision/ (workprecision.h5, .md, PNG per problem)",
          {choice("--problem", {"liver", "incompressible", "all"}, "the problems").def("all").role(kResult),
           flag("--quick", "fewer steps and tolerances").role(kResult),
           decimal("--reference-rtol", "R", open(0.0, 1e-6), "CVODE rtol of the reference")
               .def("1e-10")
               .role(kResult),
           results_option(), no_plots_option(), study_resume()}};
}

CommandSpec depth_limit_spec() {
  return {
      "depth-limit",
      {"[options]"},
      "the depth at which each law first inverts a tet (or loses\n"
      "equilibrium) under a sphere R 5 mm in a thick block, per mesh;\n"
      "results/depth-limit/ (depth_limit.json, .md, PNG; docs/contact.md)",
      {text_list("--laws", "L1,L2", "the laws (default: every law)"),
       whole_list("--cells", "N1,N2", 2, 64, "cells per axis of each mesh (default 4,6,9; 4 with --quick)"),
       decimal("--max-depth", "M", open(0.0, 0.02), "deepest indentation, m (below the 20 mm block)")
           .def("0.008"),
       decimal("--increment", "M", open(0.0, 0.02), "depth increment, m (at most --max-depth)").def("0.0005"),
       decimal("--grading", "P", closed(1.0, 20.0), "grading towards the sphere (1 = uniform)").def("2"),
       flag("--quick", "the 4-cell mesh only"), results_option(), no_plots_option(), study_resume()}};
}

CommandSpec realtime_spec() {
  return {
      "realtime",
      {"CASE [--record [--results DIR] [--no-frames]] [--duration S] [--coupling C]",
       "CASE --serve [--port P] [--duration S]"},
      "the haptic (1 kHz) / control / visual (40 Hz) threads on the liver\n"
      "with a scripted probe; --record: results/realtime/ (timing.json,\n"
      "forces.csv, frames/*.png; docs/realtime.md); --serve: the probe dragged\n"
      "(the wheel while dragging presses it in) in a live web page on\n"
      "http://127.0.0.1:P/; Ctrl-C stops",
      {flag("--record", "record the run offscreen with the coupling measurements"),
       text("--results", "DIR", "results root with --record (default: <tmlab>/results)"),
       flag("--no-frames", "no PNG frames with --record").role(kManifest),
       decimal("--duration", "S", open_closed(0.0, 3600.0), "seconds of the run (default: the case's)")
           .role(kManifest),
       text("--coupling", "extrapolation|local_model", "the rendered haptic coupling (default: the case's)")
           .role(kManifest),
       flag("--serve", "the live page instead of the scripted probe"),
       whole("--port", "P", 0, 65535, "the page's port with --serve (0: any free port)").def("8765")}};
}

CommandSpec verify_spec() {
  return {"verify",
          {"[options]"},
          "the verification catalogue (fast suite; --full: all); report\n"
          "in results/verification/ (docs/verification.md); finished cases\n"
          "are checkpointed in results/verification.checkpoint.h5 until the\n"
          "report is complete: --resume continues an interrupted suite",
          {flag("--full", "every case, the slow ones too").role(kResult),
           text("--case", "NAME", "only this case").repeat(),
           text("--label", "L", "only cases with this label").repeat(),
           flag("--list", "list the selected cases"), results_option(), no_plots_option(),
           text("--cases-dir", "DIR", "the catalogue (default verification/cases)"),
           flag("--update-docs", "write the results table into docs/verification.md"),
           flag("--resume", "continue an interrupted suite")}};
}

CommandSpec bench_spec() {
  return {"bench",
          {"[options]"},
          "every force kernel and whole step side by side with the\n"
          "machine's limits; results/bench/ (bench.json, bench.md, PNG;\n"
          "docs/performance.md)",
          {flag("--quick", "short timings on small meshes").role(kManifest),
           flag("--large", "add the 2.4M-tet cube (~6 GB, minutes)").role(kManifest),
           whole("--threads", "N", 1, 64, "most threads measured").def("2").role(kManifest),
           decimal("--min-time", "S", open_closed(0.0, 60.0),
                   "seconds per measurement (default 0.2; 0.002 --quick)")
               .role(kManifest),
           text_list("--meshes", "LIST", "only these meshes").role(kManifest), results_option(),
           no_plots_option()}};
}

}  // namespace tmlab::cli
