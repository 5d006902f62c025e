#include "verification/harness/runner.hpp"

#include "core/base/interrupt.hpp"

#include "core/base/error.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <ostream>
#include <set>

namespace fs = std::filesystem;

namespace tmlab::verify {

std::vector<VerificationCase> select(const std::vector<VerificationCase>& catalogue, const Selection& s) {
  for (const auto& n : s.names) {
    const bool known = std::any_of(catalogue.begin(), catalogue.end(),
                                   [&](const VerificationCase& c) { return c.name == n; });
    if (!known) {
      std::string all;
      for (const auto& c : catalogue) all += "\n  " + c.name;
      throw Error("--case " + n + ": no such verification case; the catalogue has:" + all);
    }
  }
  for (const auto& l : s.labels) {
    const bool used = std::any_of(catalogue.begin(), catalogue.end(),
                                  [&](const VerificationCase& c) { return c.has_label(l); });
    if (!used) {
      std::set<std::string> all;
      for (const auto& c : catalogue) all.insert(c.labels.begin(), c.labels.end());
      std::string list;
      for (const auto& a : all) list += (list.empty() ? "" : ", ") + a;
      throw Error("--label " + l + ": no case has this label (labels: " + list + ")");
    }
  }
  std::vector<VerificationCase> out;
  for (const auto& c : catalogue) {
    if (!s.names.empty()) {
      if (std::find(s.names.begin(), s.names.end(), c.name) == s.names.end()) continue;
    } else if (c.suite == "full" && !s.full) {
      continue;
    }
    if (!s.labels.empty() &&
        std::none_of(s.labels.begin(), s.labels.end(), [&](const std::string& l) { return c.has_label(l); }))
      continue;
    out.push_back(c);
  }
  return out;
}

std::vector<CaseResult> run_cases(const std::vector<VerificationCase>& cases, const CheckRegistry& registry,
                                  const RunSettings& settings, std::ostream& log,
                                  SuiteCheckpoint* checkpoint) {
  std::vector<CaseResult> results;
  const auto n = cases.size();
  for (std::size_t i = 0; i < n; ++i) {
    const VerificationCase& c = cases[i];
    if (checkpoint) {
      if (std::optional<CaseResult> stored = checkpoint->find(c.name)) {
        log << "[" << (i + 1) << "/" << n << "] " << c.name << " ... "
            << (stored->status == Status::Pass   ? "PASS"
                : stored->status == Status::Fail ? "FAIL"
                                                 : "ERROR")
            << " (from the checkpoint of the interrupted run)" << std::endl;
        results.push_back(std::move(*stored));
        continue;
      }
    }
    check_interrupt("before verification case " + c.name + " (" + std::to_string(i + 1) + " of " +
                    std::to_string(n) + ")");
    log << "[" << (i + 1) << "/" << n << "] " << c.name << " (" << c.kind << ") ..." << std::endl;
    const auto start = std::chrono::steady_clock::now();
    CaseResult r;
    try {
      const CheckFunction& fn = registry.get(c);
      const fs::path work = settings.work_root / c.name;
      fs::remove_all(work);
      fs::create_directories(work);
      CheckContext ctx{c, settings.source_root, work, log};
      r = evaluate(c, fn(ctx));
    } catch (const Interrupted&) {
      throw;  // the suite stops here; the cases before are in the checkpoint
    } catch (const std::exception& e) {
      r = CaseResult{};
      r.name = c.name;
      r.status = Status::Error;
      r.error_message = e.what();
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    char secs[32];
    std::snprintf(secs, sizeof secs, "%.2f s", r.seconds);
    log << "[" << (i + 1) << "/" << n << "] " << c.name << " ... "
        << (r.status == Status::Pass   ? "PASS"
            : r.status == Status::Fail ? "FAIL"
                                       : "ERROR")
        << " (" << secs << ")";
    if (const CheckOutcome* p = r.primary()) log << "  " << p->describe();
    if (r.status == Status::Error) log << "  " << r.error_message;
    log << std::endl;
    if (r.status == Status::Fail)
      for (const auto& o : r.outcomes)
        if (!o.passed) log << "    failed: " << o.describe() << std::endl;
    if (checkpoint) checkpoint->store(r);
    results.push_back(std::move(r));
  }
  return results;
}

}  // namespace tmlab::verify
