// libFuzzer target: the real-time case file of `tmlab realtime` (realtime/realtime_case.hpp: strict
// JSON, the liver, control, probe, trajectory, haptic and visual sections; every key in
// docs/realtime.md). The case's mesh is the unit cube of the Gmsh corpus, copied into a scratch
// root as m.msh, so cases naming "m.msh" get past the mesh. Any input must give a case or a
// tmlab::Error; a case read has positive rates, a whole number of model steps per haptic tick, a
// finite probe start and a trajectory whose positions are finite.
#include "core/base/error.hpp"
#include "fuzz/fuzz_input.hpp"
#include "realtime/realtime_case.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#ifndef TMLAB_FUZZ_CUBE_MESH
#error "TMLAB_FUZZ_CUBE_MESH: the corpus mesh the cases name (set by fuzz/CMakeLists.txt)"
#endif

namespace {
/// A scratch tmlab root holding m.msh.
std::string scratch_root() {
  const std::filesystem::path d =
      std::filesystem::temp_directory_path() / ("tmlab-fuzz-rt-" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  std::filesystem::copy_file(TMLAB_FUZZ_CUBE_MESH, d / "m.msh",
                             std::filesystem::copy_options::overwrite_existing);
  return d.string();
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string root = scratch_root();
  tmlab::fuzz::MemoryFile file(data, size);
  try {
    const tmlab::rt::RealtimeCase c = tmlab::rt::load_realtime_case(file.path(), root);
    if (!(c.haptic_hz > 0.0) || !(c.visual_hz > 0.0) || !(c.duration > 0.0) || c.substeps < 1) std::abort();
    if (!c.probe_start.allFinite() || !c.trajectory) std::abort();
    for (const double t : {0.0, 0.5 * c.trajectory->duration(), c.trajectory->duration() + 1.0})
      if (!c.trajectory->position(t).allFinite()) std::abort();
  } catch (const tmlab::Error&) {
  }
  return 0;
}
