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

/// The force on each rigid contact body of run b (series contact_<body>_force_{x,y,z}), step by
/// step: |F_a - F_b| / max_t |F_b| per body; run a must have the same bodies.
void compare_contact(const fs::path& a, const H5File& ha, const H5File& hb, std::size_t n,
                     nlohmann::json& out) {
  const std::string pre = "contact_", suf = "_force_x";
  nlohmann::json per = nlohmann::json::object();
  double worst = 0.0;
  for (const auto& name : hb.list("/series")) {
    if (name.rfind(pre, 0) != 0 || name.size() <= pre.size() + suf.size() ||
        name.compare(name.size() - suf.size(), suf.size(), suf) != 0)
      continue;
    const std::string body = name.substr(pre.size(), name.size() - pre.size() - suf.size());
    std::array<std::vector<double>, 3> A, B;
    for (int k = 0; k < 3; ++k) {
      const std::string ds = "/series/" + series_names::component(series_names::contact(body) + "_force",
                                                                  series_names::kComponents[k]);
      if (!ha.exists(ds))
        throw Error((a / "timeseries.h5").string() + ": no " + ds + " (different contact bodies?)");
      A[k] = ha.read_double(ds);
      B[k] = hb.read_double(ds);
    }
    double scale = 0.0, w = 0.0;
    for (std::size_t s = 0; s < n; ++s)
      scale = std::max(scale, std::sqrt(B[0][s] * B[0][s] + B[1][s] * B[1][s] + B[2][s] * B[2][s]));
    if (scale == 0.0) scale = 1.0;
    for (std::size_t s = 0; s < n; ++s) {
      const double dx = A[0][s] - B[0][s], dy = A[1][s] - B[1][s], dz = A[2][s] - B[2][s];
      w = std::max(w, std::sqrt(dx * dx + dy * dy + dz * dz) / scale);
    }
    per[body] = {{"rel_diff_force", w},
                 {"final_a_N", {A[0].back(), A[1].back(), A[2].back()}},
                 {"final_b_N", {B[0].back(), B[1].back(), B[2].back()}}};
    worst = std::max(worst, w);
  }
  if (per.empty()) return;
  out["contact"] = per;
  out["rel_diff_contact_force"] = worst;
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
    compare_contact(a, ha, hb, n, out);
  }
  if (series) *series = std::move(cs);
  return out;
}

}  // namespace tmlab
