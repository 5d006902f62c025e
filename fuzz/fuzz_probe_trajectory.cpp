// libFuzzer target: the probe trajectory CSV of `tmlab realtime` (header t,x,y,z, strictly increasing
// times from 0, '#' comments; realtime/probe_trajectory.hpp), read without and with a bounding box.
// Any input must give a trajectory or a tmlab::Error; a trajectory read has finite samples and
// positions, and its CSV form (write_csv) reads back to the same samples bit for bit.
#include "core/base/error.hpp"
#include "fuzz/fuzz_input.hpp"
#include "realtime/probe_trajectory.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

namespace {

using tmlab::rt::ProbeBounds;
using tmlab::rt::ProbeTrajectory;

void check(const ProbeTrajectory& p, const std::string& scratch) {
  const auto& t = p.sample_times();
  const auto& x = p.sample_points();
  if (t.empty() || t.size() != x.size() || t.front() != 0.0) std::abort();
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (!std::isfinite(t[i]) || !x[i].allFinite()) std::abort();
    if (i > 0 && !(t[i] > t[i - 1])) std::abort();
  }
  if (!std::isfinite(p.duration()) || p.duration() < 0.0) std::abort();
  // Positions between and beyond the samples are finite (linear interpolation, held at the ends).
  for (const double s : {-1.0, 0.0, 0.5 * p.duration(), p.duration(), 2.0 * p.duration() + 1.0})
    if (!p.position(s).allFinite()) std::abort();
  // The written form reads back to the same samples.
  ProbeTrajectory::write_csv(scratch, t, x);
  const ProbeTrajectory back = ProbeTrajectory::read_csv(scratch);
  if (back.sample_times() != t) std::abort();
  for (std::size_t i = 0; i < x.size(); ++i)
    if (back.sample_points()[i] != x[i]) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string scratch = (std::filesystem::temp_directory_path() /
                                      ("tmlab-fuzz-trajectory-" + std::to_string(::getpid()) + ".csv"))
                                         .string();
  tmlab::fuzz::MemoryFile file(data, size);
  try {
    check(ProbeTrajectory::read_csv(file.path()), scratch);
  } catch (const tmlab::Error&) {
  }
  const ProbeBounds box{tmlab::Vec3(-1.0, -1.0, -1.0), tmlab::Vec3(1.0, 1.0, 1.0), "the fuzz box"};
  try {
    const ProbeTrajectory p = ProbeTrajectory::read_csv(file.path(), &box);
    for (const auto& q : p.sample_points())
      if ((q.array() < box.min.array()).any() || (q.array() > box.max.array()).any()) std::abort();
    check(p, scratch);
  } catch (const tmlab::Error&) {
  }
  return 0;
}
