// tmlab: the command-line driver. Thin by design: it parses arguments and dispatches to the
// libraries; every command reports bad input as "tmlab: <file/key/element>: reason" on stderr
// and exits with status 1 (2 for a usage error).
#include "command_specs.hpp"
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

/// `tmlab help WORDS` / `tmlab WORDS --help`: the help of the command (or sub-command) the words
/// name, from its option table; false when there is none.
bool print_command_help(const std::vector<std::string>& words) {
  std::vector<tmlab::cli::CommandSpec> specs;
  if (words.size() > 1) specs = tmlab::cli::specs_of(words[0] + " " + words[1]);
  if (specs.empty() && !words.empty()) specs = tmlab::cli::specs_of(words[0]);
  for (const tmlab::cli::CommandSpec& s : specs) std::cout << tmlab::cli::command_help(s);
  return !specs.empty();
}

}  // namespace

int main(int argc, char** argv) {
  tmlab::H5File::skip_library_cleanup_at_exit();  // a failed write (full disk) must not loop at exit
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) {
    std::cerr << tmlab::cli::usage_text();
    return 2;
  }
  if (args[0] == "help" || args[0] == "--help" || args[0] == "-h") {
    if (args.size() == 1) {
      std::cout << tmlab::cli::usage_text();
      return 0;
    }
    if (print_command_help({args.begin() + 1, args.end()})) return 0;
    std::cerr << "tmlab help: " << tmlab::cli::unknown_command_message(args[1]);
    return 2;
  }
  const std::string cmd = args[0];
  for (const std::string& a : args)
    if ((a == "--help" || a == "-h") && print_command_help(args)) return 0;
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
    if (cmd == "depth-limit") return tmlab::cli::cmd_depth_limit(args, command_line);
    if (cmd == "converge") return tmlab::cli::cmd_converge(args, command_line);
    if (cmd == "bench") return tmlab::cli::cmd_bench(args, command_line);
    if (cmd == "verify") return tmlab::cli::cmd_verify(args, command_line);
    if (cmd == "data") return tmlab::cli::cmd_data(args);
    if (cmd == "rig") return tmlab::cli::cmd_rig(args);
    if (cmd == "fit") return tmlab::cli::cmd_fit(args, command_line);
    if (cmd == "realtime") return tmlab::cli::cmd_realtime(args, command_line);
    if (cmd == "discover") return tmlab::cli::cmd_discover(args, command_line);
    std::cerr << "tmlab: " << tmlab::cli::unknown_command_message(cmd);
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
      std::cerr << "tmlab " << safe(cmd) << ": " << safe(e.what()) << "\n(see 'tmlab help' or 'tmlab "
                << safe(cmd) << " --help')\n";
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
