// tmlab: the command-line driver. Thin by design: it parses arguments and dispatches to the
// libraries; every command reports bad input as "tmlab: <file/key/element>: reason" on stderr
// and exits with status 1 (2 for a usage error).
#include "commands.hpp"

#include "core/base/error.hpp"
#include "core/base/interrupt.hpp"
#include "core/io/hdf5_file.hpp"

#ifdef TMLAB_HAVE_REFERENCE
#include "reference_fem/dealii/reference_runner.hpp"
#endif

#include <cstdio>
#include <exception>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace {

void print_usage(std::ostream& os) {
  os << "usage: tmlab <command> [options]\n"
        "\n"
        "commands:\n"
        "  demo                      the liver pressed by a probe, on embedded defaults\n"
        "  run NAME|PATH [options]   run a case (a name from 'tmlab cases' or a case file)\n"
        "      --model M             override the case's model: tensor_mass | tl_oracle | hyperelastic_tl |\n"
        "                            reference\n"
        "      --degree 1|2          reference element degree (P1 default)\n"
        "      --time-integration fixed_step|ida\n"
        "                            reference viscoelastic time integration (IDA: the DAE, serial)\n"
        "      --results DIR         results root (default: <tmlab>/results)\n"
        "      --no-plots            skip the PNG plots\n"
        "      --checkpoint-every N|Ts|Tmin|off\n"
        "                            checkpoint (.incomplete/checkpoint.h5) every N steps or T of wall\n"
        "                            time (default 60s) and always on SIGINT/SIGTERM\n"
        "      --resume              continue an interrupted run from its checkpoint (bit-identical)\n"
        "  compare NAME|PATH [--against reference|tl_oracle] [--degree 1|2]\n"
        "          [--time-integration fixed_step|ida]\n"
        "                            run the case with tensormass and the reference (or the oracle:\n"
        "                            results/<case>-compare-tl_oracle/); write\n"
        "                            results/<case>-compare/ (compare.json: max relative differences)\n"
        "  cases                     list the shipped case files\n"
        "  mesh info FILE [--scale F]            counts, volume, bounding box, quality\n"
        "  mesh check FILE [--scale F] [--repair OUT.msh [--overwrite]]\n"
        "                            exit 1 if any tet is inverted or degenerate;\n"
        "                            --repair writes a re-oriented copy (never over FILE; an\n"
        "                            existing OUT.msh only with --overwrite)\n"
        "  paper fig5|fig6|fig7 [--params FILE] [--results DIR] [--no-plots] [--resume]\n"
        "                            the liver experiments of Xu et al. 2011 (creep, relaxation,\n"
        "                            hysteresis) from cases/paper/xu2011_liver.json; --resume reuses\n"
        "                            the runs an interrupted figure finished\n"
        "  paper fig2|fig3|table1|table2 [--quick] [--params FILE] [--results DIR] [--no-plots] [--resume]\n"
        "                            Section IV-A: tensor-mass fits to Hertz / Lee-Radok reference\n"
        "                            curves at 2-8 mm with standard errors, from\n"
        "                            cases/paper/xu2011_indentation.json\n"
        "  hereditary [--histories ramp_hold,sine,random] [--no-liver] [--liver-history "
        "nodal_force|pk2|both]\n"
        "             [--quick] [--seed N] [--params FILE] [--results DIR] [--no-plots] [--resume]\n"
        "                            the Prony recursions (seed midpoint, exact_linear, backward_euler)\n"
        "                            against the exact hereditary integral: strain histories, haptic\n"
        "                            steps, the liver relaxation; results/hereditary/ (docs/hereditary.md)\n"
        "                            --resume: continue an interrupted study (finished sweeps reused)\n"
        "  workprecision [--problem liver|incompressible|all] [--quick] [--reference-rtol R]\n"
        "                [--results DIR] [--no-plots] [--resume]\n"
        "                            error against CPU time: fixed-step schemes and SUNDIALS;\n"
        "                            results/workprecision/ (workprecision.h5, .md, PNG per problem)\n"
        "                            --resume: continue an interrupted study (finished runs reused)\n"
        "  inversion [--laws L1,L2] [--cells N1,N2] [--max-depth M] [--increment M] [--grading P]\n"
        "            [--quick] [--results DIR] [--no-plots] [--resume]\n"
        "                            the depth at which each law first inverts a tet (or loses\n"
        "                            equilibrium) under a sphere R 5 mm in a thick block, per mesh;\n"
        "                            results/inversion/ (inversion.json, .md, PNG; docs/contact.md)\n"
        "                            --resume: continue an interrupted study (finished runs reused)\n"
        "  realtime CASE [--record [--results DIR] [--no-frames]] [--duration S]\n"
        "           [--coupling extrapolation|local_model]\n"
        "                            the haptic (1 kHz) / control / visual (40 Hz) threads on the liver\n"
        "                            with a scripted probe; --record: results/realtime/ (timing.json,\n"
        "                            forces.csv, frames/*.png; docs/realtime.md)\n"
        "  realtime CASE --serve [--port P] [--duration S]\n"
        "                            the same loop with the probe dragged (the wheel while dragging\n"
        "                            presses it in) in a live web page on http://127.0.0.1:P/\n"
        "                            (default 8765; 0: any free port); Ctrl-C stops\n"
        "  verify [--full] [--case NAME] [--label L] [--list] [--results DIR] [--no-plots]\n"
        "         [--cases-dir DIR] [--update-docs] [--resume]\n"
        "                            the verification catalogue (fast suite; --full: all); report\n"
        "                            in results/verification/ (docs/verification.md); finished cases\n"
        "                            are checkpointed in results/verification.checkpoint.h5 until the\n"
        "                            report is complete: --resume continues an interrupted suite\n"
        "  data convert FILE --out DIR [--platens frictionless|bonded] [--overwrite]\n"
        "                            convert measured data (the silicone phantom CSVs) to\n"
        "                            tmlab-measured/1: DIR/NAME.csv + DIR/NAME.json (docs/measured-data.md)\n"
        "  data show NAME.csv [--out DIR] [--no-plots] [--overwrite]\n"
        "                            read a tmlab-measured/1 data set strictly; a summary per test and\n"
        "                            a plot (default results/data/NAME/NAME.png)\n"
        "  rig indentation|unconfined|confined|tension --out DIR [--name N] [--overwrite]\n"
        "      [--shape block|cylinder] [--size X,Y,Z] [--radius R] [--height H]\n"
        "      [--indenter sphere|flat_punch] [--indenter-radius R] [--at CX,CY]\n"
        "      [--bottom bonded|frictionless] [--platens bonded|frictionless]\n"
        "      [--cells N] [--layers N] [--grading P] [--depth D] [--ramp T] [--hold T]\n"
        "      [--cycles N] [--material JSON] [--E PA] [--nu V] [--density RHO]\n"
        "      [--steps-per-segment N] [--model M]\n"
        "                            a test rig as DIR/NAME.msh + DIR/NAME.json, an ordinary case\n"
        "                            file for tmlab run / compare (docs/rigs.md)\n"
        "  rig --data NAME.csv [--test ID] --out DIR [--name N] [--overwrite] [--cells N] [--layers N]\n"
        "      [--grading P]\n"
        "      [--material JSON] [--E PA] [--nu V] [--density RHO] [--steps-per-segment N] [--model M]\n"
        "                            the rig of a tmlab-measured/1 test: sample, fixture and indenter\n"
        "                            from NAME.json, driven by its measured displacement column\n"
        "  fit DATA.csv --model SPEC [--out DIR] [--fix NAME=VALUE ...] [--weight TEST=W ...]\n"
        "      [--forward closed_form|fe_rig|auto] [--mesh C,L] [--substeps N] [--global multistart|siman]\n"
        "      [--prior NAME=MEAN:SD ...] [--noise SIGMA] [--local-runs N] [--siman-evaluations N]\n"
        "      [--cost least_squares|l1] [--starts N] [--threads N] [--seed N] [--geodesic]\n"
        "      [--no-profile] [--no-plots] [--quiet] [--checkpoint-every N|Ts|off] [--resume]\n"
        "      [--relaxation-bands FLOOR,CEILING]\n"
        "                            fit a law to tmlab-measured/1 data with error bars; SPEC is\n"
        "                            LAW[:N][+prony:M][,NAME=VALUE...], e.g. ogden:2,poisson=0.49;\n"
        "                            results/fit/NAME-LAW/ (fit.json, fit.h5, PNG; docs/identification.md)\n"
        "  bench [--quick] [--large] [--threads N] [--min-time S] [--results DIR] [--no-plots]\n"
        "                            every force kernel and whole step side by side with the\n"
        "                            machine's limits; results/bench/ (bench.json, bench.md, PNG;\n"
        "                            docs/performance.md). --large adds the 2.4M-tet cube (~6 GB, minutes)\n"
        "  discover DATA.csv [--out DIR] [--poisson V] [--free-poisson] [--effects A,B] [--rounds N]\n"
        "      [--baseline-prony M] [--max-samples N] [--starts N] [--threads N] [--seed N] [--no-plots]\n"
        "      [--quiet] [--checkpoint-every N|Ts|off] [--resume] [--no-test-control]\n"
        "  discover --benchmark [--quick] [--rig R1,R2] [--only TRUTH1,TRUTH2] [--write-sets] [--out DIR]\n"
        "      [--checkpoint-every N|Ts|off] [--resume]\n"
        "                            baseline St VK + 2 Prony terms, the residual studied, effects from\n"
        "                            a library added when BIC and held-out prediction support them;\n"
        "                            results/discover/NAME/ (index.html, report.json; docs/discover.md)\n"
        "  version                   git SHA and build of this binary\n"
        "  help                      this text\n"
        "\n"
        "The ./tmlab script also offers: ./tmlab test [ctest args], ./tmlab build.\n";
}

}  // namespace

int main(int argc, char** argv) {
  tmlab::H5File::skip_library_cleanup_at_exit();  // a failed write (full disk) must not loop at exit
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "help" || args[0] == "--help" || args[0] == "-h") {
    print_usage(args.empty() ? std::cerr : std::cout);
    return args.empty() ? 2 : 0;
  }
  const std::string cmd = args[0];
  args.erase(args.begin());
  std::string command_line;
  for (int i = 0; i < argc; ++i) command_line += (i ? " " : "") + std::string(argv[i]);
  try {
#ifdef TMLAB_HAVE_REFERENCE
    // The deal.II reference runs on MPI (one rank here; mpirun tmlab_reference for more): only the
    // commands that may use it start MPI, once, for the life of the process.
    std::unique_ptr<tmlab::ref::MpiSession> mpi;
    if (cmd == "run" || cmd == "compare" || cmd == "verify")
      mpi = std::make_unique<tmlab::ref::MpiSession>(argc, argv);
#endif
    // SIGINT / SIGTERM: long commands stop at their next safe point and leave INTERRUPTED.
    // Installed after MPI_Init, which sets handlers of its own.
    const tmlab::InterruptHandler interrupts;
    if (cmd == "demo") return tmlab::cli::cmd_demo(args, command_line);
    if (cmd == "run") return tmlab::cli::cmd_run(args, command_line);
    if (cmd == "cases") return tmlab::cli::cmd_cases(args);
    if (cmd == "mesh") return tmlab::cli::cmd_mesh(args);
    if (cmd == "compare") return tmlab::cli::cmd_compare(args, command_line);
    if (cmd == "paper") return tmlab::cli::cmd_paper(args, command_line);
    if (cmd == "version") return tmlab::cli::cmd_version();
    if (cmd == "hereditary") return tmlab::cli::cmd_hereditary(args, command_line);
    if (cmd == "workprecision") return tmlab::cli::cmd_workprecision(args, command_line);
    if (cmd == "inversion") return tmlab::cli::cmd_inversion(args, command_line);
    if (cmd == "bench") return tmlab::cli::cmd_bench(args, command_line);
    if (cmd == "verify") return tmlab::cli::cmd_verify(args, command_line);
    if (cmd == "data") return tmlab::cli::cmd_data(args);
    if (cmd == "rig") return tmlab::cli::cmd_rig(args);
    if (cmd == "fit") return tmlab::cli::cmd_fit(args, command_line);
    if (cmd == "realtime") return tmlab::cli::cmd_realtime(args, command_line);
    if (cmd == "discover") return tmlab::cli::cmd_discover(args, command_line);
    std::cerr << "tmlab: unknown command '" << cmd << "'\n\n";
    print_usage(std::cerr);
    return 2;
  } catch (...) {
    // The last defence for a message that quotes user text: ESC and the other C0 control characters
    // (but newline and tab) and DEL are printed as \xNN, so no message can drive the terminal.
    const auto safe = [](const std::string& text) {
      std::string out;
      for (const char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        if ((c < 0x20 && c != '\n' && c != '\t') || c == 0x7f) {
          const char* hex = "0123456789abcdef";
          out += {'\\', 'x', hex[c >> 4], hex[c & 0xf]};
        } else {
          out += ch;
        }
      }
      return out;
    };
    try {
      throw;
    } catch (const tmlab::cli::UsageError& e) {
      std::cerr << "tmlab " << safe(cmd) << ": " << safe(e.what()) << "\n(see 'tmlab help')\n";
      return 2;
    } catch (const tmlab::Interrupted& e) {
      std::cerr << "tmlab: interrupted: " << safe(e.what()) << "\n";
      return 128 + e.signal();
    } catch (const tmlab::Error& e) {
      std::cerr << "tmlab: error: " << safe(e.what()) << "\n";
      return 1;
    } catch (const std::exception& e) {
      std::cerr << "tmlab: internal error: " << safe(e.what()) << "\n";
      return 3;
    } catch (...) {
      std::cerr << "tmlab: internal error: an exception of unknown type\n";
      return 3;
    }
  }
}
