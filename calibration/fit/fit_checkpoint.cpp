// The checkpoint entries of a fit: see fit_checkpoint.hpp.
#include "calibration/fit/fit_checkpoint.hpp"

#include "core/base/error.hpp"
#include "core/results/unit_checkpoint.hpp"

#include <cstdint>
#include <utility>

namespace tmlab::fit {

using nlohmann::json;

namespace {

std::vector<std::int64_t> as_ints(const std::vector<std::size_t>& v) { return {v.begin(), v.end()}; }

}  // namespace

// --- fit units --------------------------------------------------------------------------------------

void put_fit_units(CheckpointData& d, const FitUnits& u) {
  const std::size_t p = u.candidates.empty() ? 0 : u.candidates[0].size();
  d.put("units", std::vector<std::int64_t>{u.global_done ? 1 : 0, std::int64_t(u.local_runs.size()),
                                           std::int64_t(u.profile.size()), std::int64_t(p),
                                           std::int64_t(u.candidates.size())});
  std::vector<double> cand;
  for (const auto& c : u.candidates) cand.insert(cand.end(), c.begin(), c.end());
  d.put("global.candidates", cand);
  d.put("global.order", as_ints(u.order));
  d.put("global.start_costs", u.start_costs);
  d.put("global.global_costs", u.global_costs);
  d.put("global.solves", std::vector<std::int64_t>{u.solves, u.global_solves});
  std::vector<double> t, cost;
  std::vector<std::int64_t> iterations, solves;
  json reasons = json::array();
  for (const auto& r : u.local_runs) {
    t.insert(t.end(), r.t.begin(), r.t.end());
    cost.push_back(r.cost);
    iterations.push_back(r.iterations);
    solves.push_back(r.solves);
    reasons.push_back(r.reason);
  }
  d.put("local.t", t);
  d.put("local.cost", cost);
  d.put("local.iterations", iterations);
  d.put("local.solves", solves);
  d.put_text("local.reasons", unit_text(reasons));
  std::vector<double> sse;
  std::vector<std::int64_t> psolves;
  for (const auto& q : u.profile) {
    sse.push_back(q.sse);
    psolves.push_back(q.solves);
  }
  d.put("profile.sse", sse);
  d.put("profile.solves", psolves);
}

FitUnits get_fit_units(const CheckpointData& d) {
  FitUnits u;
  const auto& n = d.ints("units");
  require_consistent(n.size() == 5 && n[1] >= 0 && n[2] >= 0 && n[3] >= 0 && n[4] >= 0, d, "units");
  const auto runs = std::size_t(n[1]), points = std::size_t(n[2]), p = std::size_t(n[3]),
             starts = std::size_t(n[4]);
  u.global_done = n[0] != 0;
  const auto& cand = d.doubles("global.candidates");
  require_consistent(cand.size() == p * starts, d, "global.candidates");
  for (std::size_t c = 0; c < starts; ++c)
    u.candidates.emplace_back(cand.begin() + long(c * p), cand.begin() + long((c + 1) * p));
  for (const std::int64_t o : d.ints("global.order")) {
    require_consistent(o >= 0 && std::size_t(o) < starts, d, "global.order");
    u.order.push_back(std::size_t(o));
  }
  u.start_costs = d.doubles("global.start_costs");
  u.global_costs = d.doubles("global.global_costs");
  const auto& gs = d.ints("global.solves");
  require_consistent(gs.size() == 2, d, "global.solves");
  u.solves = gs[0];
  u.global_solves = gs[1];
  const auto& t = d.doubles("local.t");
  const auto& cost = d.doubles("local.cost");
  const auto& it = d.ints("local.iterations");
  const auto& ls = d.ints("local.solves");
  const json reasons = read_unit_text(d, "local.reasons");
  require_consistent(t.size() == runs * p && cost.size() == runs && it.size() == runs && ls.size() == runs &&
                         reasons.is_array() && reasons.size() == runs,
                     d, "local");
  for (std::size_t r = 0; r < runs; ++r)
    u.local_runs.push_back({std::vector<double>(t.begin() + long(r * p), t.begin() + long((r + 1) * p)),
                            cost[r], int(it[r]), reasons[r].get<std::string>(), ls[r]});
  const auto& sse = d.doubles("profile.sse");
  const auto& ps = d.ints("profile.solves");
  require_consistent(sse.size() == points && ps.size() == points, d, "profile");
  for (std::size_t k = 0; k < points; ++k) u.profile.push_back({sse[k], ps[k]});
  return u;
}

std::string describe(const FitUnits& u) {
  if (!u.global_done) return "nothing";
  std::string s = "the global stage";
  if (!u.local_runs.empty())
    s += (u.profile.empty() ? " and " : ", ") + std::to_string(u.local_runs.size()) + " local run(s)";
  if (!u.profile.empty()) s += " and " + std::to_string(u.profile.size()) + " profile-likelihood point(s)";
  return s;
}

// --- fit results ------------------------------------------------------------------------------------

void put_fit_result(CheckpointData& d, const std::string& prefix, const FitResult& r) {
  json m = {{"model_name", r.model_name},
            {"model_description", r.model_description},
            {"cost_name", r.cost_name},
            {"global_stage", r.global_stage},
            {"global_model_name", r.global_model_name},
            {"stop_reason", r.stop_reason},
            {"free_names", r.free_names},
            {"notes", r.notes},
            {"n", r.n},
            {"k", r.k},
            {"forward_solves", r.forward_solves},
            {"global_solves", r.global_solves},
            {"threads", r.threads},
            {"iterations", r.iterations},
            {"local_runs", r.local_runs},
            {"correlation_size", r.correlation.size()},
            {"profile",
             {{"parameter", r.profile.parameter},
              {"lower_found", r.profile.lower_found},
              {"upper_found", r.profile.upper_found}}},
            {"parameters", json::array()},
            {"confounded", json::array()}};
  std::vector<double> params, corr, profile, confounded;
  for (const auto& q : r.parameters) {
    m["parameters"].push_back({{"name", q.name},
                               {"unit", q.unit},
                               {"fixed", q.fixed},
                               {"transform", q.transform},
                               {"identifiable", q.identifiable}});
    params.insert(params.end(), {q.value, q.standard_error, q.lower95, q.upper95});
  }
  for (const auto& row : r.correlation) {
    if (row.size() != r.correlation.size())
      throw Error("checkpoint: a fit's correlation matrix is not square");
    corr.insert(corr.end(), row.begin(), row.end());
  }
  for (const auto& q : r.profile.points) profile.insert(profile.end(), {q.value, q.sse});
  for (const auto& c : r.confounded) {
    m["confounded"].push_back({{"a", c.a}, {"b", c.b}, {"note", c.note}});
    confounded.push_back(c.correlation);
  }
  d.put_text(prefix + ".meta", unit_text(m));
  d.put(prefix + ".scalars",
        std::vector<double>{r.cost, r.sse, r.rms, r.rms_percent_peak, r.aic, r.bic, r.prior_cost,
                            r.noise_sigma, r.wall_seconds, r.profile.lower95, r.profile.upper95});
  d.put(prefix + ".parameters", params);
  d.put(prefix + ".correlation", corr);
  d.put(prefix + ".start_costs", r.start_costs);
  d.put(prefix + ".global_costs", r.global_costs);
  d.put(prefix + ".prediction", r.prediction);
  d.put(prefix + ".profile", profile);
  d.put(prefix + ".confounded", confounded);
}

FitResult get_fit_result(const CheckpointData& d, const std::string& prefix) {
  FitResult r;
  const json m = read_unit_text(d, prefix + ".meta");
  read_unit_fields(d, prefix + ".meta", [&] {
    r.model_name = m.at("model_name").get<std::string>();
    r.model_description = m.at("model_description").get<std::string>();
    r.cost_name = m.at("cost_name").get<std::string>();
    r.global_stage = m.at("global_stage").get<std::string>();
    r.global_model_name = m.at("global_model_name").get<std::string>();
    r.stop_reason = m.at("stop_reason").get<std::string>();
    r.free_names = m.at("free_names").get<std::vector<std::string>>();
    r.notes = m.at("notes").get<std::vector<std::string>>();
    r.n = m.at("n").get<std::size_t>();
    r.k = m.at("k").get<std::size_t>();
    r.forward_solves = m.at("forward_solves").get<long>();
    r.global_solves = m.at("global_solves").get<long>();
    r.threads = m.at("threads").get<int>();
    r.iterations = m.at("iterations").get<int>();
    r.local_runs = m.value("local_runs", 0);  // absent from checkpoints of earlier builds
    r.profile.parameter = m.at("profile").at("parameter").get<std::string>();
    r.profile.lower_found = m.at("profile").at("lower_found").get<bool>();
    r.profile.upper_found = m.at("profile").at("upper_found").get<bool>();
    const auto& params = d.doubles(prefix + ".parameters");
    require_consistent(params.size() == 4 * m.at("parameters").size(), d, prefix + ".parameters");
    std::size_t i = 0;
    for (const auto& q : m.at("parameters")) {
      ParameterResult p;
      p.name = q.at("name").get<std::string>();
      p.unit = q.at("unit").get<std::string>();
      p.fixed = q.at("fixed").get<bool>();
      p.transform = q.at("transform").get<std::string>();
      p.identifiable = q.at("identifiable").get<bool>();
      p.value = params[i++];
      p.standard_error = params[i++];
      p.lower95 = params[i++];
      p.upper95 = params[i++];
      r.parameters.push_back(p);
    }
    const auto& conf = d.doubles(prefix + ".confounded");
    require_consistent(conf.size() == m.at("confounded").size(), d, prefix + ".confounded");
    i = 0;
    for (const auto& c : m.at("confounded"))
      r.confounded.push_back({c.at("a").get<std::string>(), c.at("b").get<std::string>(), conf[i++],
                              c.at("note").get<std::string>()});
    const auto cs = m.at("correlation_size").get<std::size_t>();
    const auto& corr = d.doubles(prefix + ".correlation");
    require_consistent(corr.size() == cs * cs, d, prefix + ".correlation");
    for (std::size_t a = 0; a < cs; ++a)
      r.correlation.emplace_back(corr.begin() + long(a * cs), corr.begin() + long((a + 1) * cs));
  });
  const auto& s = d.doubles(prefix + ".scalars");
  require_consistent(s.size() == 11, d, prefix + ".scalars");
  r.cost = s[0];
  r.sse = s[1];
  r.rms = s[2];
  r.rms_percent_peak = s[3];
  r.aic = s[4];
  r.bic = s[5];
  r.prior_cost = s[6];
  r.noise_sigma = s[7];
  r.wall_seconds = s[8];
  r.profile.lower95 = s[9];
  r.profile.upper95 = s[10];
  r.start_costs = d.doubles(prefix + ".start_costs");
  r.global_costs = d.doubles(prefix + ".global_costs");
  r.prediction = d.doubles(prefix + ".prediction");
  const auto& pr = d.doubles(prefix + ".profile");
  require_consistent(pr.size() % 2 == 0, d, prefix + ".profile");
  for (std::size_t k = 0; k < pr.size(); k += 2) r.profile.points.push_back({pr[k], pr[k + 1]});
  return r;
}

// --- the file of one fit -----------------------------------------------------------------------

FitCheckpoint::FitCheckpoint(const std::filesystem::path& dir, const nlohmann::json& fingerprint,
                             const CheckpointSchedule& schedule)
    : ck_(dir / result_dir::kStaging / "checkpoint.h5", "fit", fingerprint, schedule, [this] {
        CheckpointData d;
        put_fit_units(d, latest_);
        return d;
      }) {}

void FitCheckpoint::restore(FitOptions& o, std::ostream& log) {
  restored_ = get_fit_units(ck_.read());
  ck_.resumed_from(describe(restored_));
  o.resume.restored = &restored_;
  log << "tmlab fit: resuming from " << ck_.path().string() << ": " << describe(restored_)
      << " taken from it, the rest runs\n";
}

void FitCheckpoint::record(FitOptions& o) {
  o.resume.unit_finished = [this](const FitUnits& u) {
    latest_ = u;
    ck_.unit_finished(describe(u));
  };
}

}  // namespace tmlab::fit
