// The checkpoint entries of a discovery and of its benchmark: see discover_checkpoint.hpp.
#include "calibration/discover/discover_checkpoint.hpp"

#include "calibration/fit/fit_checkpoint.hpp"
#include "core/base/error.hpp"
#include "core/results/unit_checkpoint.hpp"

#include <cstdint>

namespace tmlab::discover {

using nlohmann::json;

// --- discover ---------------------------------------------------------------------------------------

void put_fit_outcomes(CheckpointData& d, const std::vector<FitOutcome>& v) {
  d.put_int("fits", std::int64_t(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::string prefix = "fit." + std::to_string(i);
    if (v[i].failed)
      d.put_text(prefix + ".error", v[i].error);
    else
      fit::put_fit_result(d, prefix, v[i].result);
  }
}

std::vector<FitOutcome> get_fit_outcomes(const CheckpointData& d) {
  const std::int64_t n = d.integer("fits");
  require_consistent(n >= 0, d, "fits");
  std::vector<FitOutcome> v(static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::string prefix = "fit." + std::to_string(i);
    if (d.has(prefix + ".error")) {
      v[i].failed = true;
      v[i].error = d.text(prefix + ".error");
    } else {
      v[i].result = fit::get_fit_result(d, prefix);
    }
  }
  return v;
}

void put_benchmark_entries(CheckpointData& d, const std::vector<BenchmarkEntry>& v) {
  d.put_int("sets", std::int64_t(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) {
    const BenchmarkEntry& e = v[i];
    const std::string prefix = "set." + std::to_string(i);
    d.put_text(prefix + ".meta", unit_text({{"name", e.name},
                                            {"truth", e.truth},
                                            {"rig", e.rig},
                                            {"kind", int(e.kind)},
                                            {"found", e.found},
                                            {"unexplained", e.unexplained},
                                            {"signature", e.signature},
                                            {"correct", e.correct}}));
    d.put(prefix + ".numbers", std::vector<double>{e.rms_before, e.rms_after, e.peak, e.seconds});
  }
}

std::vector<BenchmarkEntry> get_benchmark_entries(const CheckpointData& d) {
  const std::int64_t n = d.integer("sets");
  require_consistent(n >= 0, d, "sets");
  std::vector<BenchmarkEntry> v(static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < v.size(); ++i) {
    BenchmarkEntry& e = v[i];
    const std::string prefix = "set." + std::to_string(i);
    const json m = read_unit_text(d, prefix + ".meta");
    read_unit_fields(d, prefix + ".meta", [&] {
      e.name = m.at("name").get<std::string>();
      e.truth = m.at("truth").get<std::string>();
      e.rig = m.at("rig").get<std::string>();
      const int kind = m.at("kind").get<int>();
      require_consistent(kind >= 0 && kind <= 2, d, prefix + ".meta");
      e.kind = static_cast<Truth>(kind);
      e.found = m.at("found").get<std::vector<std::string>>();
      e.unexplained = m.at("unexplained").get<bool>();
      e.signature = m.at("signature").get<std::string>();
      e.correct = m.at("correct").get<bool>();
    });
    const auto& x = d.doubles(prefix + ".numbers");
    require_consistent(x.size() == 4, d, prefix + ".numbers");
    e.rms_before = x[0];
    e.rms_after = x[1];
    e.peak = x[2];
    e.seconds = x[3];
  }
  return v;
}

}  // namespace tmlab::discover
