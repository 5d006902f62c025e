#include "verification/studies/study_plot.hpp"

namespace tmlab::tm {

ProcessStatus draw_study_plot(const std::string& tmlab_root, const std::string& script,
                              const std::filesystem::path& dir, const ProcessOutput& output) {
  const std::filesystem::path path =
      std::filesystem::path(tmlab_root) / "verification" / "studies" / "python" / script;
  return run_python(path, {dir.string()}, output);
}

}  // namespace tmlab::tm
