#include "verification/harness/report.hpp"

#include "core/base/format.hpp"

#include "verification/harness/convergence.hpp"

#include "core/base/error.hpp"
#include "core/base/process.hpp"
#include "core/io/atomic_file.hpp"
#include "core/io/xml_text.hpp"
#include "core/results/json_number.hpp"

#include <tmlab/build_info.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>

namespace fs = std::filesystem;

namespace tmlab::verify {

namespace {

std::string num(double v) { return std::isnan(v) ? "n/a" : significant(v, 3); }

/// Orders with two decimals (2.00, 1.97): a significant-digit format would print 2.0 as "2".
std::string order_text(double v) { return std::isnan(v) ? "n/a" : fixed_point(v, 2); }

std::string seconds_text(double s) { return fixed_point(s, s < 10 ? 2 : 0) + " s"; }

/// The first order outcome of a result (nullptr when the case has no convergence check).
const CheckOutcome* first_order(const CaseResult& r) {
  for (const auto& o : r.outcomes)
    if (o.kind == "order") return &o;
  return nullptr;
}

std::string status_word(Status s) {
  return s == Status::Pass ? "PASS" : s == Status::Fail ? "FAIL" : "ERROR";
}

std::string bound_text(const CheckOutcome& o) {
  if (o.kind == "max" || o.kind == "finest") return "<= " + num(o.limit);
  if (o.kind == "min") return ">= " + num(o.limit);
  return order_text(o.limit) + " +- " + num(o.tolerance);
}

std::string check_label(const CheckOutcome& o) {
  if (o.kind == "order") return o.name + " (observed order)";
  if (o.kind == "finest") return o.name + " (finest error)";
  return o.name;
}

/// Markdown table cells must not contain '|' or newlines.
std::string cell(const std::string& s) {
  std::string out;
  for (char ch : s) {
    if (ch == '|')
      out += "\\|";
    else
      out += ch == '\n' ? ' ' : ch;
  }
  return out;
}

std::string read_bytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

/// The plot spec of one case for plot_convergence.py (series with fitted and expected orders).
nlohmann::json plot_spec(const VerificationCase& c, const CaseResult& r) {
  nlohmann::json j;
  j["title"] = c.name + ": " + c.title;
  for (const auto& [name, s] : r.measurements.series) {
    nlohmann::json js{{"x", s.x}, {"y", s.y}, {"x_label", s.x_label}, {"y_label", s.y_label}};
    js["observed_order"] = nullptr;
    js["expected_order"] = nullptr;
    js["fit_points"] = 0;
    for (const auto& cv : c.convergence)
      if (cv.series == name) {
        js["expected_order"] = cv.expected_order;
        js["fit_points"] = cv.fit_points;
        try {
          js["observed_order"] = fitted_order(s.x, s.y, cv.fit_points);
        } catch (const Error&) {
        }
      }
    j["series"][name] = js;
  }
  return j;
}

}  // namespace

nlohmann::json verification_json(const ReportInput& in) {
  nlohmann::json cases = nlohmann::json::array();
  int passed = 0, failed = 0, errors = 0;
  for (std::size_t i = 0; i < in.results.size(); ++i) {
    const CaseResult& r = in.results[i];
    const VerificationCase& c = in.cases[i];
    nlohmann::json e;
    e["name"] = r.name;
    e["title"] = c.title;
    e["status"] = to_string(r.status);
    e["suite"] = c.suite;
    e["labels"] = c.labels;
    e["kind"] = c.kind;
    e["seconds"] = r.seconds;
    const CheckOutcome* p = r.primary();
    e["error"] = p ? finite_or_null(p->measured) : nlohmann::json();
    e["tolerance"] = p ? finite_or_null(p->tolerance) : nlohmann::json();
    if (const CheckOutcome* o = first_order(r)) {
      e["observed_order"] = finite_or_null(o->measured);
      e["expected_order"] = o->limit;
    }
    nlohmann::json checks = nlohmann::json::array();
    for (const auto& o : r.outcomes)
      checks.push_back({{"name", o.name},
                        {"kind", o.kind},
                        {"measured", finite_or_null(o.measured)},
                        {"limit", o.limit},
                        {"tolerance", o.tolerance},
                        {"passed", o.passed},
                        {"rationale", o.rationale}});
    e["checks"] = checks;
    nlohmann::json metrics = nlohmann::json::object();
    for (const auto& [k, v] : r.measurements.metrics) metrics[k] = finite_or_null(v);
    e["metrics"] = metrics;
    nlohmann::json series = nlohmann::json::object();
    for (const auto& [k, s] : r.measurements.series)
      series[k] = {{"x", s.x}, {"y", s.y}, {"x_label", s.x_label}, {"y_label", s.y_label}};
    e["series"] = series;
    e["notes"] = r.measurements.notes;
    if (!r.measurements.data.empty()) e["data"] = r.measurements.data;
    if (r.status == Status::Error) e["message"] = r.error_message;
    cases.push_back(e);
    (r.status == Status::Pass ? passed : r.status == Status::Fail ? failed : errors) += 1;
  }
  return {{"git_sha", build_info::git_sha},
          {"git_dirty", build_info::git_dirty},
          {"build_type", build_info::build_type},
          {"command_line", in.command_line},
          {"passed", passed},
          {"failed", failed},
          {"errors", errors},
          {"cases", cases}};
}

std::string results_table(const ReportInput& in) {
  std::ostringstream md;
  md << "| case | status | measured (headline check) | tolerance | observed / expected order | time |\n"
     << "|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < in.results.size(); ++i) {
    const CaseResult& r = in.results[i];
    const CheckOutcome* p = r.primary();
    md << "| " << r.name << " | " << status_word(r.status) << " | ";
    if (r.status == Status::Error)
      md << "error: " << cell(r.error_message.substr(0, 120)) << " | | ";
    else if (p)
      md << cell(check_label(*p)) << " = " << num(p->measured) << " | " << bound_text(*p) << " | ";
    else
      md << " | | ";
    if (const CheckOutcome* o = first_order(r))
      md << order_text(o->measured) << " / " << order_text(o->limit);
    md << " | " << seconds_text(r.seconds) << " |\n";
  }
  return md.str();
}

namespace {

/// The convergence plots: plots/<case>.png for each case with series (plot_convergence.py through the
/// plotting python), the report's link to each (empty: none), and what went wrong (empty: nothing).
struct Plots {
  std::vector<fs::path> files;
  std::vector<std::string> of_case;
  std::string problem;
};

Plots draw_plots(const ReportInput& in, const fs::path& dir) {
  Plots p;
  p.of_case.resize(in.results.size());
  for (std::size_t i = 0; i < in.results.size(); ++i) {
    const CaseResult& r = in.results[i];
    if (r.measurements.series.empty()) continue;
    if (!in.plots) {
      p.problem = "plots skipped (no python3 with matplotlib given)";
      continue;
    }
    fs::create_directories(dir / "plots");
    const fs::path spec = dir / "plots" / (r.name + ".json");
    const fs::path png = dir / "plots" / (r.name + ".png");
    write_file_atomically(spec, plot_spec(in.cases[i], r).dump(1));
    const fs::path log = dir / "plots" / (r.name + ".log");
    const ProcessStatus ps =
        run_python(in.plot_script, {spec.string(), png.string()}, ProcessOutput::to_file(log));
    if (ps.ok() && fs::exists(png)) {
      p.files.push_back(png);
      p.of_case[i] = "plots/" + r.name + ".png";
      fs::remove(log);
    } else {
      p.problem = "a plot failed: see " + log.string();
    }
    fs::remove(spec);
  }
  return p;
}

/// "**3 passed, 0 failed, 0 errors** of 3 cases." (markdown) or its HTML form.
std::string counts_text(const nlohmann::json& vj, std::size_t cases, bool html) {
  const std::string b = html ? "<b>" : "**", e = html ? "</b>" : "**";
  return b + std::to_string(vj["passed"].get<int>()) + " passed, " + std::to_string(vj["failed"].get<int>()) +
         " failed, " + std::to_string(vj["errors"].get<int>()) + " errors" + e + " of " +
         std::to_string(cases) + " cases.";
}

/// The value of each informational metric of a case ("n/a" when not measured).
std::vector<std::pair<std::string, std::string>> reported_metrics(const VerificationCase& c,
                                                                  const CaseResult& r) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& k : c.report) {
    const auto it = r.measurements.metrics.find(k);
    out.emplace_back(k, it == r.measurements.metrics.end() ? "n/a" : num(it->second));
  }
  return out;
}

std::string measured_text(const CheckOutcome& o) {
  return o.kind == "order" ? order_text(o.measured) : num(o.measured);
}

void markdown_case(std::ostream& md, const VerificationCase& c, const CaseResult& r,
                   const std::string& plot) {
  md << "## " << c.name << ": " << c.title << "\n\n"
     << "**" << status_word(r.status) << "** (" << c.suite << " suite; labels: ";
  for (std::size_t k = 0; k < c.labels.size(); ++k) md << (k ? ", " : "") << c.labels[k];
  md << "; kind `" << c.kind << "`; " << seconds_text(r.seconds) << ")\n\n"
     << "- What is checked: " << c.what << "\n- Reference: " << c.reference << "\n"
     << "- Case data: `verification/cases/" << c.name << "/`\n\n";
  if (r.status == Status::Error) md << "Error: `" << r.error_message << "`\n\n";
  if (!r.outcomes.empty()) {
    md << "| check | measured | tolerance | pass | why this tolerance |\n|---|---|---|---|---|\n";
    for (const auto& o : r.outcomes)
      md << "| " << cell(check_label(o)) << " | " << measured_text(o) << " | " << bound_text(o) << " | "
         << (o.passed ? "yes" : "**no**") << " | " << cell(o.rationale) << " |\n";
    md << "\n";
  }
  if (!c.report.empty()) {
    md << "Reported without a tolerance:";
    for (const auto& [k, v] : reported_metrics(c, r)) md << " " << k << " = " << v << ";";
    md << "\n\n";
  }
  for (const auto& note : r.measurements.notes) md << "- " << note << "\n";
  if (!r.measurements.notes.empty()) md << "\n";
  if (!plot.empty()) md << "![" << c.name << "](" << plot << ")\n\n";
}

std::string report_markdown(const ReportInput& in, const nlohmann::json& vj, const std::string& table,
                            const Plots& plots) {
  std::ostringstream md;
  md << "# tmlab verification report\n\n"
     << "tmlab git " << build_info::git_sha << (build_info::git_dirty ? " (modified)" : "") << ", "
     << build_info::build_type << " build. Command: `" << in.command_line << "`.\n\n"
     << counts_text(vj, in.results.size(), false);
  if (!plots.problem.empty()) md << " (" << plots.problem << ")";
  md << "\n\n## Summary\n\n" << table << "\n";
  for (std::size_t i = 0; i < in.results.size(); ++i)
    markdown_case(md, in.cases[i], in.results[i], plots.of_case[i]);
  return md.str();
}

void html_summary_table(std::ostream& h, const ReportInput& in) {
  h << "<table><tr><th>case</th><th>status</th><th>headline check</th><th>tolerance</th><th>order (obs / "
       "exp)</th>"
       "<th>time</th></tr>\n";
  for (const auto& r : in.results) {
    const CheckOutcome* p = r.primary();
    const std::string cls = to_string(r.status);
    h << "<tr><td><a href=\"#" << xml_escape(r.name) << "\">" << xml_escape(r.name) << "</a></td><td class=\""
      << cls << "\">" << status_word(r.status) << "</td><td>"
      << (p ? xml_escape(check_label(*p) + " = " + num(p->measured))
            : xml_escape(r.error_message.substr(0, 120)))
      << "</td><td>" << (p ? xml_escape(bound_text(*p)) : "") << "</td><td>";
    if (const CheckOutcome* o = first_order(r)) h << order_text(o->measured) << " / " << order_text(o->limit);
    h << "</td><td>" << seconds_text(r.seconds) << "</td></tr>\n";
  }
  h << "</table>\n";
}

void html_case(std::ostream& h, const VerificationCase& c, const CaseResult& r, const fs::path& png) {
  h << "<h2 id=\"" << xml_escape(c.name) << "\">" << xml_escape(c.name + ": " + c.title)
    << "</h2>\n<p class=\"" << to_string(r.status) << "\">" << status_word(r.status)
    << "</p>\n<ul><li>What is checked: " << xml_escape(c.what)
    << "</li><li>Reference: " << xml_escape(c.reference) << "</li><li>Case data: <code>verification/cases/"
    << xml_escape(c.name) << "/</code> (" << xml_escape(c.suite) << " suite, " << seconds_text(r.seconds)
    << ")</li></ul>\n";
  if (r.status == Status::Error) h << "<p class=\"error\">Error: " << xml_escape(r.error_message) << "</p>\n";
  if (!r.outcomes.empty()) {
    h << "<table><tr><th>check</th><th>measured</th><th>tolerance</th><th>pass</th><th>why this "
         "tolerance</th></tr>\n";
    for (const auto& o : r.outcomes)
      h << "<tr><td>" << xml_escape(check_label(o)) << "</td><td>" << measured_text(o) << "</td><td>"
        << xml_escape(bound_text(o)) << "</td><td class=\"" << (o.passed ? "pass\">yes" : "fail\">no")
        << "</td><td>" << xml_escape(o.rationale) << "</td></tr>\n";
    h << "</table>\n";
  }
  if (!c.report.empty()) {
    h << "<p>Reported without a tolerance:";
    for (const auto& [k, v] : reported_metrics(c, r)) h << " " << xml_escape(k) << " = " << v << ";";
    h << "</p>\n";
  }
  if (!r.measurements.notes.empty()) {
    h << "<ul>";
    for (const auto& note : r.measurements.notes) h << "<li>" << xml_escape(note) << "</li>";
    h << "</ul>\n";
  }
  if (!png.empty()) {
    const std::string bytes = read_bytes(png);
    h << "<img alt=\"" << xml_escape(c.name) << "\" src=\"data:image/png;base64,"
      << base64_encode(bytes.data(), bytes.size()) << "\">\n";
  }
}

/// report.html: the report's content, self-contained (PNGs inline as data URIs).
std::string report_html(const ReportInput& in, const nlohmann::json& vj, const Plots& plots,
                        const fs::path& dir) {
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>tmlab verification report</title>\n"
    << "<style>body{font-family:sans-serif;max-width:70em;margin:auto;padding:1em}"
       "table{border-collapse:collapse;margin:0.5em 0}td,th{border:1px solid #bbb;padding:3px "
       "6px;font-size:90%;"
       "vertical-align:top}.pass{color:#070;font-weight:bold}.fail,.error{color:#b00;font-weight:bold}"
       "img{max-width:100%}code{background:#f3f3f3}</style></head><body>\n"
    << "<h1>tmlab verification report</h1>\n<p>tmlab git " << xml_escape(build_info::git_sha)
    << (build_info::git_dirty ? " (modified)" : "") << ", " << xml_escape(build_info::build_type)
    << " build. Command: <code>" << xml_escape(in.command_line) << "</code></p>\n"
    << "<p>" << counts_text(vj, in.results.size(), true) << "</p>\n";
  html_summary_table(h, in);
  for (std::size_t i = 0; i < in.results.size(); ++i)
    html_case(h, in.cases[i], in.results[i], plots.of_case[i].empty() ? fs::path() : dir / plots.of_case[i]);
  h << "</body></html>\n";
  return h.str();
}

}  // namespace

std::vector<fs::path> write_report(const ReportInput& in, const fs::path& dir) {
  fs::create_directories(dir);
  const Plots plots = draw_plots(in, dir);
  const nlohmann::json vj = verification_json(in);
  write_file_atomically(dir / "verification.json", vj.dump(2));
  const std::string table = results_table(in);
  write_file_atomically(dir / "results-table.md", table);
  write_file_atomically(dir / "report.md", report_markdown(in, vj, table, plots));
  write_file_atomically(dir / "report.html", report_html(in, vj, plots, dir));
  return plots.files;
}

void update_doc_table(const fs::path& doc, const std::string& table) {
  static constexpr const char* kBegin = "<!-- verification-results:begin -->";
  static constexpr const char* kEnd = "<!-- verification-results:end -->";
  std::ifstream f(doc);
  if (!f) throw Error(doc.string() + ": cannot be read");
  std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  const auto b = text.find(kBegin);
  const auto e = text.find(kEnd);
  if (b == std::string::npos || e == std::string::npos || e < b)
    throw Error(doc.string() + ": markers '" + kBegin + "' and '" + kEnd + "' not found");
  const auto start = b + std::string(kBegin).size();
  text = text.substr(0, start) + "\n" + table + text.substr(e);
  write_file_atomically(doc, text);
}

}  // namespace tmlab::verify
