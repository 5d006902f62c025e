#include "bench/bench_report.hpp"

#include "core/base/error.hpp"
#include "core/base/process.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

namespace tmlab::tm {

namespace {

using json = nlohmann::json;

/// The first record matching all the given fields, or nullptr.
const json* find(const json& bench, const json& fields) {
  for (const json& r : bench.at("records")) {
    bool ok = true;
    for (auto it = fields.begin(); it != fields.end() && ok; ++it)
      ok = r.contains(it.key()) && r[it.key()] == *it;
    if (ok) return &r;
  }
  return nullptr;
}

double ns_of(const json& bench, const json& fields) {
  const json* r = find(bench, fields);
  return r ? r->at("ns_per_tet").get<double>() : NAN;
}

json target(const std::string& name, double value, double limit, bool at_most, const std::string& unit,
            const std::string& how) {
  json t = {{"name", name}, {"limit", limit}, {"at_most", at_most}, {"unit", unit}, {"how", how}};
  if (std::isfinite(value)) {
    t["value"] = value;
    t["met"] = at_most ? value <= limit : value >= limit;
  } else {
    t["value"] = nullptr;
    t["met"] = nullptr;
  }
  return t;
}

std::string fmt(double v, int prec = 3) {
  std::ostringstream s;
  s << std::setprecision(prec) << v;
  return s.str();
}

/// The largest mesh with a 1 ms explicit contact step of the fast objective model on `threads`
/// threads: the contact ladder's (tets, us per step) points, the last one at or below 1000 us and
/// its larger neighbour, interpolated linearly in tets; beyond the ladder, extrapolated with the
/// per-tet cost of the end point (cost proportional to tets). NaN without records.
std::pair<double, std::string> one_ms_tets(const json& b, int threads) {
  std::vector<std::pair<double, double>> pts;
  for (const json& r : b.at("records"))
    if (r.at("kind") == "step" && r.at("step") == "explicit_contact" && r.at("kernel") == "fast" &&
        r.at("history") == "objective" && r.at("threads") == threads)
      pts.emplace_back(r.at("tets").get<double>(), r.at("us_per_step").get<double>());
  if (pts.empty()) return {NAN, "no explicit_contact records"};
  std::sort(pts.begin(), pts.end());
  std::size_t below = pts.size();
  for (std::size_t i = 0; i < pts.size(); ++i)
    if (pts[i].second <= 1000.0) below = i;
  if (below == pts.size())
    return {pts.front().first * 1000.0 / pts.front().second,
            "extrapolated below the smallest contact mesh (" + fmt(pts.front().first, 6) + " tets)"};
  if (below + 1 == pts.size())
    return {pts.back().first * 1000.0 / pts.back().second,
            "extrapolated beyond the largest contact mesh (" + fmt(pts.back().first, 6) + " tets)"};
  const auto [n0, t0] = pts[below];
  const auto [n1, t1] = pts[below + 1];
  return {n0 + (1000.0 - t0) * (n1 - n0) / (t1 - t0), "interpolated linearly in tets between " + fmt(n0, 6) +
                                                          " tets (" + fmt(t0) + " us) and " + fmt(n1, 6) +
                                                          " tets (" + fmt(t1) + " us)"};
}

/// The contact ladder's records as a table: us per step, one column per contact mesh.
std::string contact_markdown(const json& b) {
  std::vector<std::pair<long, std::string>> meshes;
  std::set<std::string> seen_mesh;
  for (const json& r : b.at("records"))
    if (r.contains("contact") && seen_mesh.insert(r.at("mesh").get<std::string>()).second)
      meshes.emplace_back(r.at("tets").get<long>(), r.at("mesh").get<std::string>());
  if (meshes.empty()) return "";
  std::sort(meshes.begin(), meshes.end());
  std::ostringstream md;
  md << "\n## Whole steps with a rigid sphere in contact, us per step (CPU time for 1 thread, wall time "
        "for more)\n\n| step | kernel | history | linear | threads |";
  for (const auto& m : meshes) md << " " << m.first << " tets |";
  md << "\n|---|---|---|---|---|";
  for (std::size_t i = 0; i < meshes.size(); ++i) md << "---|";
  md << "\n";
  std::set<std::string> seen;
  for (const json& r : b.at("records")) {
    if (!r.contains("contact")) continue;
    const std::string step =
        r.at("step").get<std::string>() + (r.at("contact") == "none" ? " (no body)" : "");
    const std::string key =
        step + "|" + r.at("linear").get<std::string>() + "|" + std::to_string(r.at("threads").get<int>());
    if (!seen.insert(key).second) continue;
    md << "| " << step << " | " << r.at("kernel").get<std::string>() << " | "
       << r.at("history").get<std::string>() << " | " << r.at("linear").get<std::string>() << " | "
       << r.at("threads").get<int>() << " |";
    for (const auto& m : meshes) {
      const json* s = find(b, {{"kind", "step"},
                               {"step", r.at("step")},
                               {"contact", r.at("contact")},
                               {"linear", r.at("linear")},
                               {"threads", r.at("threads")},
                               {"mesh", m.second}});
      md << " " << (s ? fmt(s->at("us_per_step").get<double>()) : "-") << " |";
    }
    md << "\n";
  }
  md << "\nTime steps and nodes in contact (explicit, 1 thread):";
  for (const auto& m : meshes) {
    const json* s =
        find(b, {{"kind", "step"}, {"step", "explicit_contact"}, {"threads", 1}, {"mesh", m.second}});
    if (s)
      md << " " << m.first << " tets: dt " << fmt(s->at("dt").get<double>()) << " s, "
         << s->at("active_nodes").get<int>() << " nodes;";
  }
  md << " implicit: dt 1e-3 s.\n";
  return md.str();
}

}  // namespace

json bench_targets(const json& b) {
  const double peak = b.at("limits").at("peak_gflops_1t").get<double>();
  auto F = [&](const std::string& kernel, const std::string& history, const std::string& mesh,
               int threads = 1, const std::string& law = "stvk") {
    return ns_of(b, {{"kind", "force"},
                     {"kernel", kernel},
                     {"history", history},
                     {"mesh", mesh},
                     {"threads", threads},
                     {"law", law}});
  };
  json t = json::array();
  const json* fast24 = find(b, {{"kind", "force"},
                                {"kernel", "fast"},
                                {"history", "none"},
                                {"law", "stvk"},
                                {"mesh", "cube_24k"},
                                {"threads", 1}});
  const double floor_ns = fast24 ? fast24->at("flops_per_tet").get<double>() / peak : NAN;
  t.push_back(target("fast kernel / compute floor (cube_24k, 1 thread)",
                     F("fast", "none", "cube_24k") / floor_ns, 3.0, true, "x",
                     "ns/tet over flops_per_tet / peak_gflops_1t"));
  t.push_back(target("fast / baseline (cube_24k, 1 thread)",
                     F("fast", "none", "cube_24k") / F("baseline", "none", "cube_24k"), 0.3, true, "x",
                     "ns/tet ratio"));
  t.push_back(target("tensor_mass / baseline (cube_24k)",
                     F("tensor_mass", "none", "cube_24k") / F("baseline", "none", "cube_24k"), 4.0, true, "x",
                     "ns/tet ratio"));
  t.push_back(
      target("viscoelastic overhead, tensor_mass xu2011 (cube_24k)",
             100.0 * (F("tensor_mass", "xu2011", "cube_24k") / F("tensor_mass", "none", "cube_24k") - 1.0),
             5.0, true, "%", "xu2011 trial force over elastic force"));
  t.push_back(target("viscoelastic overhead, fast objective in cache (cube_2k)",
                     100.0 * (F("fast", "objective", "cube_2k") / F("fast", "none", "cube_2k") - 1.0), 15.0,
                     true, "%", "objective trial force over elastic force"));
  t.push_back(target("viscoelastic overhead, fast objective (cube_2m)",
                     100.0 * (F("fast", "objective", "cube_2m") / F("fast", "none", "cube_2m") - 1.0), 50.0,
                     true, "%", "needs --large"));
  t.push_back(target("2 threads / 1 thread speed-up (fast, cube_240k)",
                     F("fast", "none", "cube_240k") / F("fast", "none", "cube_240k", 2), 1.7, false, "x",
                     "ns/tet 1 thread over 2 threads"));
  // Liver explicit viscoelastic step: the cheapest measured viscoelastic explicit step.
  double liver_visco = NAN, per_tet_visco = NAN;
  std::string largest_mesh;
  for (const json& r : b.at("records")) {
    if (r.at("kind") != "step" || r.at("step") != "explicit" || r.at("history") == "none") continue;
    const double us = r.at("us_per_step").get<double>();
    if (r.at("mesh") == "liver" && r.at("threads") == 1 && !(us >= liver_visco)) liver_visco = us;
  }
  // Per-tet cost of a viscoelastic explicit step on the largest mesh measured.
  long most = 0;
  for (const json& r : b.at("records"))
    if (r.at("kind") == "step" && r.at("step") == "explicit" && r.at("history") != "none" &&
        r.at("threads").get<int>() <= 2 && r.at("tets").get<long>() >= most) {
      const double pt = r.at("us_per_step").get<double>() / r.at("tets").get<double>();
      if (r.at("tets").get<long>() > most || !(pt >= per_tet_visco)) per_tet_visco = pt;
      most = r.at("tets").get<long>();
    }
  t.push_back(target("liver explicit viscoelastic step, 1 core", liver_visco, 50.0, true, "us",
                     "cheapest viscoelastic explicit step record on the liver"));
  t.push_back(
      target("largest mesh with a 1 ms viscoelastic step (2 cores, contact excluded)",
             per_tet_visco > 0 ? 1000.0 / per_tet_visco : NAN, 40000.0, false, "tets",
             "1 ms over the per-tet cost of the cheapest viscoelastic explicit step (1 or 2 threads) on the "
             "largest mesh measured: conservative, the largest mesh's per-tet cost is out of cache"));
  // Implicit steps: CHOLMOD's LL^T against Eigen's LDL^T on the largest mesh that has both.
  double chol_ratio = NAN;
  long chol_tets = 0;
  std::string chol_mesh = "none";
  for (const json& r : b.at("records")) {
    if (r.at("kind") != "step" || r.at("step") != "implicit" || r.value("linear", "") != "cholmod") continue;
    const json* d =
        find(b, {{"kind", "step"}, {"step", "implicit"}, {"linear", "ldlt"}, {"mesh", r.at("mesh")}});
    if (d && r.at("tets").get<long>() > chol_tets) {
      chol_tets = r.at("tets").get<long>();
      chol_mesh = r.at("mesh").get<std::string>();
      chol_ratio = r.at("us_per_step").get<double>() / d->at("us_per_step").get<double>();
    }
  }
  t.push_back(
      target("implicit step, CHOLMOD / Eigen LDL^T (" + chol_mesh + ")", chol_ratio, 1.0, true, "x",
             "Newmark step of the tensor-mass model, us per step with solver.linear cholmod over ldlt"));
  for (int threads : {2, 1}) {
    const auto [tets, how] = one_ms_tets(b, threads);
    t.push_back(target("largest mesh with a 1 ms viscoelastic step with contact (explicit, fast objective, " +
                           std::to_string(threads) +
                           (threads == 1 ? " thread, CPU time)" : " threads, wall time)"),
                       tets, 40000.0, false, "tets", "us per explicit_contact step against tets, " + how));
  }
  // Implicit steps with contact (dt = 1 ms): the cheapest on the smallest contact mesh (if that
  // exceeds 1 ms, no larger mesh holds a 1 ms implicit step), and CHOLMOD over LDL^T on the largest.
  double implicit_us = NAN, implicit_ratio = NAN;
  long implicit_small = 0, implicit_large = 0;
  for (const json& r : b.at("records")) {
    if (r.at("kind") != "step" || r.at("step") != "implicit_contact") continue;
    const long n = r.at("tets").get<long>();
    const double us = r.at("us_per_step").get<double>();
    if (implicit_small == 0 || n < implicit_small || (n == implicit_small && us < implicit_us)) {
      implicit_small = n;
      implicit_us = us;
    }
    const json* d =
        find(b, {{"kind", "step"}, {"step", "implicit_contact"}, {"linear", "ldlt"}, {"mesh", r.at("mesh")}});
    if (r.at("linear") == "cholmod" && d && n > implicit_large) {
      implicit_large = n;
      implicit_ratio = us / d->at("us_per_step").get<double>();
    }
  }
  t.push_back(target("implicit step with contact, dt 1 ms (" + std::to_string(implicit_small) + " tets)",
                     implicit_us, 1000.0, true, "us",
                     "cheapest implicit_contact record on the smallest contact mesh, 1 thread"));
  t.push_back(target(
      "implicit step with contact, CHOLMOD / Eigen LDL^T (" + std::to_string(implicit_large) + " tets)",
      implicit_ratio, 1.0, true, "x", "us per implicit_contact step, cholmod over ldlt"));
  t.push_back(target("cost linear in tets (fast, ns/tet cube_240k / cube_2k)",
                     F("fast", "none", "cube_240k") / F("fast", "none", "cube_2k"), 1.5, true, "x",
                     "1 = perfectly linear"));
  t.push_back(target("cost linear in tets (fast, ns/tet cube_2m / cube_2k)",
                     F("fast", "none", "cube_2m") / F("fast", "none", "cube_2k"), 1.5, true, "x",
                     "1 = perfectly linear; needs --large"));
  return t;
}

std::string bench_markdown(const json& b) {
  std::ostringstream md;
  const json& L = b.at("limits");
  md << "# tmlab bench\n\nMachine limits (same run): FMA peak " << fmt(L.at("peak_gflops_1t").get<double>())
     << " GFLOP/s (1 thread), " << fmt(L.at("peak_gflops_2t").get<double>()) << " GFLOP/s (2 threads); triad "
     << fmt(L.at("triad_gbs_1t").get<double>()) << " GB/s (1 thread), "
     << fmt(L.at("triad_gbs_2t").get<double>()) << " GB/s (2 threads).\n\n";
  std::vector<std::string> meshes;
  for (const json& m : b.at("meshes")) meshes.push_back(m.at("name").get<std::string>());
  std::map<std::string, long> tets;
  for (const json& m : b.at("meshes")) tets[m.at("name").get<std::string>()] = m.at("tets").get<long>();
  md << "## Force kernels, ns per tet (CPU time for 1 thread, wall time for more)\n\n| kernel | history | "
        "law | threads | flops/tet | "
        "bytes/tet | "
        "memory/tet |";
  for (const auto& m : meshes) md << " " << m << " (" << tets[m] << ") |";
  md << "\n|---|---|---|---|---|---|---|";
  for (std::size_t i = 0; i < meshes.size(); ++i) md << "---|";
  md << "\n";
  std::set<std::string> seen;
  for (const json& r : b.at("records")) {
    if (r.at("kind") != "force") continue;
    const std::string key = r.at("kernel").get<std::string>() + "|" + r.at("history").get<std::string>() +
                            "|" + r.at("law").get<std::string>() + "|" +
                            std::to_string(r.at("threads").get<int>());
    if (!seen.insert(key).second) continue;
    md << "| " << r.at("kernel").get<std::string>() << " | " << r.at("history").get<std::string>() << " | "
       << r.at("law").get<std::string>() << " | " << r.at("threads").get<int>() << " | "
       << fmt(r.at("flops_per_tet").get<double>()) << " | " << fmt(r.at("bytes_per_tet").get<double>())
       << " | " << fmt(r.at("memory_per_tet").get<double>()) << " |";
    for (const auto& m : meshes) {
      const double ns = ns_of(b, {{"kind", "force"},
                                  {"kernel", r.at("kernel")},
                                  {"history", r.at("history")},
                                  {"law", r.at("law")},
                                  {"threads", r.at("threads")},
                                  {"mesh", m}});
      md << " " << (std::isfinite(ns) ? fmt(ns) : "-") << " |";
    }
    md << "\n";
  }
  md << "\n## Whole steps, us per step (CPU time for 1 thread, wall time for more)\n\n| step | kernel | "
        "history | threads | energies |";
  for (const auto& m : meshes) md << " " << m << " |";
  md << "\n|---|---|---|---|---|";
  for (std::size_t i = 0; i < meshes.size(); ++i) md << "---|";
  md << "\n";
  seen.clear();
  for (const json& r : b.at("records")) {
    if (r.at("kind") != "step" || r.contains("contact")) continue;  // contact_markdown's table
    const bool book = r.value("energy_bookkeeping", false);
    const std::string linear = r.value("linear", std::string("none"));
    const std::string step = r.at("step").get<std::string>() + (linear == "none" ? "" : " (" + linear + ")");
    const std::string key = step + "|" + r.at("kernel").get<std::string>() + "|" +
                            r.at("history").get<std::string>() + "|" +
                            std::to_string(r.at("threads").get<int>()) + (book ? "|b" : "");
    if (!seen.insert(key).second) continue;
    md << "| " << step << " | " << r.at("kernel").get<std::string>() << " | "
       << r.at("history").get<std::string>() << " | " << r.at("threads").get<int>() << " | "
       << (book ? "on" : "off") << " |";
    for (const auto& m : meshes) {
      json fields = {{"kind", "step"},
                     {"step", r.at("step")},
                     {"kernel", r.at("kernel")},
                     {"history", r.at("history")},
                     {"threads", r.at("threads")},
                     {"mesh", m},
                     {"energy_bookkeeping", book}};
      if (r.contains("linear")) fields["linear"] = linear;  // records before issue 16's CHOLMOD have none
      const json* s = find(b, fields);
      md << " " << (s ? fmt(s->at("us_per_step").get<double>()) : "-") << " |";
    }
    md << "\n";
  }
  md << contact_markdown(b);
  md << "\n## Targets (issue 16; ratios from this run)\n\n| target | measured | limit | met "
        "|\n|---|---|---|---|\n";
  for (const json& t : bench_targets(b)) {
    md << "| " << t.at("name").get<std::string>() << " | "
       << (t.at("value").is_null() ? std::string("not measured")
                                   : fmt(t.at("value").get<double>()) + " " + t.at("unit").get<std::string>())
       << " | " << (t.at("at_most").get<bool>() ? "<= " : ">= ") << fmt(t.at("limit").get<double>()) << " "
       << t.at("unit").get<std::string>() << " | "
       << (t.at("met").is_null() ? "-" : (t.at("met").get<bool>() ? "yes" : "no")) << " |\n";
  }
  return md.str();
}

json write_bench_report(json bench, const std::filesystem::path& dir, bool plots,
                        const std::string& tmlab_root, std::ostream* log) {
  bench["targets"] = bench_targets(bench);
  {
    std::ofstream os(dir / "bench.json");
    os << bench.dump(1) << "\n";
    if (!os) throw Error((dir / "bench.json").string() + ": could not be written");
  }
  {
    std::ofstream os(dir / "bench.md");
    os << bench_markdown(bench);
    if (!os) throw Error((dir / "bench.md").string() + ": could not be written");
  }
  std::string plot_status = "skipped";
  if (plots) {
    const auto script = std::filesystem::path(tmlab_root) / "bench" / "python" / "tmlab_bench_plot.py";
    const ProcessStatus st = run_python(script, {dir.string()});
    plot_status = st.ok() ? "ok" : st.describe();
    if (!st.ok() && log) *log << "tmlab bench: plots failed (" << st.describe() << ")\n";
  }
  return {{"records", bench.at("records").size()}, {"plots", plot_status}};
}

}  // namespace tmlab::tm
