#include "core/results/result_compare.hpp"
#include "core/results/series_names.hpp"

#include "core/base/error.hpp"
#include "core/io/hdf5_file.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>

namespace tmlab {

namespace fs = std::filesystem;

namespace {

H5File open_result(const fs::path& dir, const std::string& file) {
  const fs::path p = dir / file;
  if (!fs::exists(dir / "summary.json"))
    throw Error(dir.string() + ": not a complete result (no summary.json; did the run fail?)");
  if (!fs::exists(p)) throw Error(p.string() + ": missing");
  return H5File::open_read(p.string());
}

double norm(const double* v, std::size_t n) {
  double s = 0.0;
  for (std::size_t i = 0; i < n; ++i) s += v[i] * v[i];
  return std::sqrt(s);
}

/// Nodal displacements, frame by frame: |u_a - u_b| / |u_b| (absolute when |u_b| = 0).
void compare_displacements(const fs::path& a, const fs::path& b, nlohmann::json& out, ComparisonSeries& cs) {
  H5File ha = open_result(a, "displacement.h5"), hb = open_result(b, "displacement.h5");
  H5File::Dims da, db;
  const auto ua = ha.read_double("/u", &da);
  const auto ub = hb.read_double("/u", &db);
  if (da != db)
    throw Error("displacement.h5 of " + a.string() + " and " + b.string() + " differ in shape (" +
                std::to_string(da.at(0)) + "x" + std::to_string(da.at(1)) + " vs " +
                std::to_string(db.at(0)) + "x" + std::to_string(db.at(1)) +
                "): not the same mesh or output frames");
  const std::size_t rows = da.at(0), cols = da.at(1);
  const auto t = hb.read_double("/time");
  double worst = 0.0;
  for (std::size_t r = 0; r < rows; ++r) {
    std::vector<double> d(cols);
    for (std::size_t c = 0; c < cols; ++c) d[c] = ua[r * cols + c] - ub[r * cols + c];
    const double nb = norm(&ub[r * cols], cols);
    const double e = nb > 0.0 ? norm(d.data(), cols) / nb : norm(d.data(), cols);
    cs.rel_displacement.push_back(e);
    cs.time.push_back(r < t.size() ? t[r] : static_cast<double>(r));
    worst = std::max(worst, e);
  }
  out["rel_diff_displacement"] = worst;
  out["frames"] = rows;
  out["nodes"] = cols / 3;
}

/// Reactions per Dirichlet condition, step by step, against one scale (see below).
void compare_reactions(const fs::path& a, const H5File& ha, const H5File& hb, std::size_t n,
                       nlohmann::json& out, ComparisonSeries& cs) {
  std::map<std::string, int> conditions;
  for (const auto& c : series_names::reaction_conditions(hb.list("/series"))) conditions[c] = 1;
  // All reactions are measured against one scale, the largest reaction of run b over all
  // conditions and steps: a support that carries (almost) nothing must not turn round-off into
  // a large relative difference.
  std::map<std::string, std::array<std::vector<double>, 3>> ra, rb;
  double scale = 0.0;
  for (const auto& [c, unused] : conditions) {
    (void)unused;
    for (int k = 0; k < 3; ++k) {
      const std::string ds =
          "/series/" + series_names::component(series_names::reaction(c), series_names::kComponents[k]);
      if (!ha.exists(ds))
        throw Error((a / "timeseries.h5").string() + ": no " + ds + " (different boundary conditions?)");
      ra[c][k] = ha.read_double(ds);
      rb[c][k] = hb.read_double(ds);
    }
    for (std::size_t s = 0; s < n; ++s)
      scale = std::max(scale, std::sqrt(rb[c][0][s] * rb[c][0][s] + rb[c][1][s] * rb[c][1][s] +
                                        rb[c][2][s] * rb[c][2][s]));
  }
  if (scale == 0.0) scale = 1.0;
  std::vector<double> rel_reac(n, 0.0);
  double worst_reac = 0.0;
  nlohmann::json per = nlohmann::json::object();
  for (const auto& [c, unused] : conditions) {
    (void)unused;
    const auto& A = ra[c];
    const auto& B = rb[c];
    double w = 0.0;
    for (std::size_t s = 0; s < n; ++s) {
      const double dx = A[0][s] - B[0][s], dy = A[1][s] - B[1][s], dz = A[2][s] - B[2][s];
      const double e = std::sqrt(dx * dx + dy * dy + dz * dz) / scale;
      rel_reac[s] = std::max(rel_reac[s], e);
      w = std::max(w, e);
    }
    per[c] = {{"rel_diff", w},
              {"final_a_N", {A[0].back(), A[1].back(), A[2].back()}},
              {"final_b_N", {B[0].back(), B[1].back(), B[2].back()}}};
    worst_reac = std::max(worst_reac, w);
  }
  out["rel_diff_reaction"] = worst_reac;
  out["reactions"] = per;
  cs.rel_reaction = rel_reac;
}

/// Elastic energy, step by step: |W_a - W_b| / max_t |W_b|.
void compare_energy(const H5File& ha, const H5File& hb, std::size_t n, nlohmann::json& out,
                    ComparisonSeries& cs) {
  const std::string energy = std::string("/series/") + series_names::kElasticEnergy;
  const auto wa = ha.read_double(energy), wb = hb.read_double(energy);
  double wscale = 0.0;
  for (double v : wb) wscale = std::max(wscale, std::abs(v));
  double worst = 0.0;
  for (std::size_t s = 0; s < n; ++s) {
    const double e = std::abs(wa[s] - wb[s]) / (wscale > 0.0 ? wscale : 1.0);
    cs.rel_energy.push_back(e);
    worst = std::max(worst, e);
  }
  out["rel_diff_energy"] = worst;
  out["steps"] = n;
}

/// Contact force, area and active nodes per body, step by step. Forces are measured against the
/// largest contact force of run b (all bodies, all steps), areas against the largest area, as the
/// reactions: a body that barely touches must not turn round-off into a large relative difference.
void compare_contact(const fs::path& a, const fs::path& b_dir, const H5File& ha, const H5File& hb,
                     std::size_t n, nlohmann::json& out, ComparisonSeries& cs) {
  const std::vector<std::string> bodies = series_names::contact_bodies(hb.list("/series"));
  const std::vector<std::string> bodies_a = series_names::contact_bodies(ha.list("/series"));
  if (bodies.empty() && bodies_a.empty()) return;
  auto read = [&](const H5File& h, const fs::path& dir, const std::string& name) {
    const std::string ds = "/series/" + name;
    if (!h.exists(ds))
      throw Error((dir / "timeseries.h5").string() + ": no " + ds + " (different contact bodies?)");
    return h.read_double(ds);
  };
  for (const auto& b : bodies_a)
    if (std::find(bodies.begin(), bodies.end(), b) == bodies.end())
      throw Error("contact body '" + b + "' of " + a.string() +
                  " is not in the other run (different contact bodies?)");
  struct Body {
    std::array<std::vector<double>, 3> fa, fb;
    std::vector<double> area_a, area_b, nodes_a, nodes_b;
  };
  std::map<std::string, Body> data;
  double fscale = 0.0, ascale = 0.0;
  for (const auto& b : bodies) {
    Body& d = data[b];
    const std::string base = series_names::component("contact_" + b, "force");
    for (int k = 0; k < 3; ++k) {
      const std::string name = series_names::component(base, series_names::kComponents[k]);
      d.fa[k] = read(ha, a, name);
      d.fb[k] = read(hb, b_dir, name);
    }
    d.area_a = read(ha, a, "contact_" + b + "_area");
    d.area_b = read(hb, b_dir, "contact_" + b + "_area");
    d.nodes_a = read(ha, a, "contact_" + b + "_active_nodes");
    d.nodes_b = read(hb, b_dir, "contact_" + b + "_active_nodes");
    for (std::size_t s = 0; s < n; ++s) {
      fscale = std::max(
          fscale, std::sqrt(d.fb[0][s] * d.fb[0][s] + d.fb[1][s] * d.fb[1][s] + d.fb[2][s] * d.fb[2][s]));
      ascale = std::max(ascale, d.area_b[s]);
    }
  }
  if (fscale == 0.0) fscale = 1.0;
  if (ascale == 0.0) ascale = 1.0;
  cs.rel_contact_force.assign(n, 0.0);
  cs.rel_contact_area.assign(n, 0.0);
  double worst_f = 0.0, worst_a = 0.0, worst_nodes = 0.0;
  nlohmann::json per = nlohmann::json::object();
  for (const auto& [b, d] : data) {
    double wf = 0.0, wa = 0.0, wn = 0.0;
    for (std::size_t s = 0; s < n; ++s) {
      const double dx = d.fa[0][s] - d.fb[0][s], dy = d.fa[1][s] - d.fb[1][s], dz = d.fa[2][s] - d.fb[2][s];
      const double ef = std::sqrt(dx * dx + dy * dy + dz * dz) / fscale;
      const double ea = std::abs(d.area_a[s] - d.area_b[s]) / ascale;
      cs.rel_contact_force[s] = std::max(cs.rel_contact_force[s], ef);
      cs.rel_contact_area[s] = std::max(cs.rel_contact_area[s], ea);
      wf = std::max(wf, ef);
      wa = std::max(wa, ea);
      wn = std::max(wn, std::abs(d.nodes_a[s] - d.nodes_b[s]));
    }
    per[b] = {{"rel_diff_force", wf},
              {"rel_diff_area", wa},
              {"max_diff_active_nodes", wn},
              {"final_force_a_N", {d.fa[0].back(), d.fa[1].back(), d.fa[2].back()}},
              {"final_force_b_N", {d.fb[0].back(), d.fb[1].back(), d.fb[2].back()}},
              {"final_area_a_m2", d.area_a.back()},
              {"final_area_b_m2", d.area_b.back()},
              {"final_active_nodes_a", d.nodes_a.back()},
              {"final_active_nodes_b", d.nodes_b.back()}};
    worst_f = std::max(worst_f, wf);
    worst_a = std::max(worst_a, wa);
    worst_nodes = std::max(worst_nodes, wn);
  }
  out["rel_diff_contact_force"] = worst_f;
  out["rel_diff_contact_area"] = worst_a;
  out["max_diff_active_nodes"] = worst_nodes;
  out["contact"] = per;
}

}  // namespace

nlohmann::json compare_results(const fs::path& a, const fs::path& b, ComparisonSeries* series) {
  nlohmann::json out;
  ComparisonSeries cs;
  compare_displacements(a, b, out, cs);
  {
    H5File ha = open_result(a, "timeseries.h5"), hb = open_result(b, "timeseries.h5");
    const std::string time = std::string("/series/") + series_names::kTime;
    const auto ta = ha.read_double(time), tb = hb.read_double(time);
    if (ta.size() != tb.size())
      throw Error("timeseries.h5 of " + a.string() + " and " + b.string() + " differ in steps");
    const std::size_t n = tb.size();
    cs.step_time = tb;
    compare_reactions(a, ha, hb, n, out, cs);
    compare_energy(ha, hb, n, out, cs);
    compare_contact(a, b, ha, hb, n, out, cs);
  }
  if (series) *series = std::move(cs);
  return out;
}

}  // namespace tmlab
