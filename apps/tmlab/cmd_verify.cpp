// tmlab verify: runs the verification catalogue (verification/cases/) and writes the report
// (results/verification/: report.md, report.html, verification.json, plots/, manifest.json).
#include "cli_args.hpp"
#include "command_specs.hpp"
#include "commands.hpp"

#include "core/base/error.hpp"
#include "core/base/interrupt.hpp"
#include "core/results/run_output.hpp"
#include "verification/checks/builtin_checks.hpp"
#include "verification/harness/report.hpp"
#include "verification/harness/runner.hpp"

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <iostream>

namespace tmlab::cli {

namespace fs = std::filesystem;

namespace {

void print_list(const std::vector<verify::VerificationCase>& cases) {
  // Column widths from the widest entry of each column (and its header), two spaces between.
  auto joined = [](const std::vector<std::string>& v) {
    std::string s;
    for (const auto& l : v) s += (s.empty() ? "" : ",") + l;
    return s;
  };
  std::size_t wn = 4, ws = 5, wl = 6;
  for (const auto& c : cases) {
    wn = std::max(wn, c.name.size());
    ws = std::max(ws, c.suite.size());
    wl = std::max(wl, joined(c.labels).size());
  }
  auto row = [&](const std::string& a, const std::string& b, const std::string& c, const std::string& d) {
    std::cout << std::left << std::setw(static_cast<int>(wn + 2)) << a << std::setw(static_cast<int>(ws + 2))
              << b << std::setw(static_cast<int>(wl + 2)) << c << d << "\n";
  };
  row("case", "suite", "labels", "title");
  for (const auto& c : cases) row(c.name, c.suite, joined(c.labels), c.title);
}

}  // namespace

int cmd_verify(const std::vector<std::string>& args, const std::string& command_line) {
  const ParsedOptions p = parse(verify_spec(), args);
  if (!p.positional.empty()) throw UsageError("unexpected argument '" + p.positional.front() + "'");
  const fs::path root = tmlab_root();
  const fs::path cases_dir =
      p.given("--cases-dir") ? fs::path(p.text("--cases-dir")) : root / "verification" / "cases";
  const auto catalogue = verify::load_catalogue(cases_dir);

  verify::Selection sel;
  sel.full = p.flag("--full");
  sel.names = p.all("--case");
  sel.labels = p.all("--label");
  const auto cases = verify::select(catalogue, sel);
  if (p.flag("--list")) {
    print_list(cases);
    return 0;
  }
  if (cases.empty()) throw UsageError("no verification case selected");

  verify::CheckRegistry registry;
  verify::register_builtin_checks(registry);

  const fs::path root_dir = results_root(p);
  RunOutput out(root_dir / "verification");
  try {
    // The suite's identity (its checkpoint's fingerprint): the options that change the result
    // (--full), the cases dir and the cases in order.
    nlohmann::json config = p.config(kFingerprint);
    config.update({{"cases_dir", fs::absolute(cases_dir).string()}, {"cases", nlohmann::json::array()}});
    std::vector<fs::path> inputs;
    for (const auto& c : cases) {
      config["cases"].push_back(c.name);
      inputs.push_back(c.spec_file());
    }
    out.write_json("manifest.json", make_manifest({split_words(command_line), config, inputs}));
    std::cerr << "tmlab verify: " << cases.size() << " case(s)" << (sel.full ? " (full suite)" : "") << "\n";

    // Checkpoint: each finished case's result, beside the result directory (which a new run
    // empties), so that an interrupted suite continues with --resume (docs/robustness.md).
    // The suite's identity is its configuration: the cases dir, --full and the cases in order.
    // Not run_with_protocol (core/results/run_protocol.hpp): the suite's checkpoint lives beside the
    // report, not inside it, so it is removed only after the report is final (a failed finish can
    // still be resumed), and a stop names the cases it holds.
    verify::SuiteCheckpoint checkpoint(root_dir / "verification.checkpoint.h5", config, p.flag("--resume"));
    if (p.flag("--resume"))
      std::cerr << "tmlab verify: resuming: " << checkpoint.stored() << " of " << cases.size()
                << " case(s) finished before the interruption\n";
    verify::RunSettings settings{root, out.staging_dir() / "work"};
    std::vector<verify::CaseResult> results;
    try {
      results = verify::run_cases(cases, registry, settings, std::cerr, &checkpoint);
    } catch (const Interrupted& e) {
      throw Interrupted(e.signal(), std::string(e.what()) + "; " + std::to_string(checkpoint.stored()) +
                                        " of " + std::to_string(cases.size()) +
                                        " case(s) are checkpointed in " + checkpoint.file().string() +
                                        ": continue with the same command and --resume");
    }
    fs::remove_all(settings.work_root);

    verify::ReportInput in{cases, results, command_line, !p.flag("--no-plots"),
                           root / "verification" / "harness" / "python" / "plot_convergence.py"};
    verify::write_report(in, out.staging_dir());
    const nlohmann::json vj = verify::verification_json(in);
    if (p.flag("--update-docs"))
      verify::update_doc_table(root / "docs" / "verification.md", verify::results_table(in));
    const int passed = vj["passed"], failed = vj["failed"], errors = vj["errors"];
    out.finalize({{"passed", passed}, {"failed", failed}, {"errors", errors}, {"cases", cases.size()}});
    checkpoint.remove();  // the report is complete: nothing to resume
    std::cout << "verification: " << passed << " passed, " << failed << " failed, " << errors << " errors of "
              << cases.size() << "; report: " << (out.dir() / "report.md").string() << "\n";
    return failed == 0 && errors == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    out.abandon(e);
    throw;
  }
}

}  // namespace tmlab::cli
