// libFuzzer target: the Gmsh reader (ASCII 1, 2.2 and 4.1). Any input must either give a mesh
// whose node indices are in range or a tmlab::Error; a crash, a sanitizer report, a hang or any
// other exception is a bug (fuzz/README.md).
#include "core/base/error.hpp"
#include "core/mesh/gmsh_reader.hpp"
#include "core/mesh/mesh_quality.hpp"
#include "fuzz/fuzz_input.hpp"

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  tmlab::fuzz::MemoryFile file(data, size);
  try {
    const tmlab::Mesh mesh = tmlab::read_gmsh(file.path());
    for (const auto& tet : mesh.tets)
      for (tmlab::Index v : tet)
        if (v < 0 || v >= mesh.num_points()) std::abort();  // the reader promises valid indices
    (void)tmlab::analyse_mesh(mesh);
  } catch (const tmlab::Error&) {
    // A clear error is the expected outcome for malformed input.
  }
  return 0;
}
