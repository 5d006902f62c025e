#include "studies/common/study_plot.hpp"

namespace tmlab::tm {

ProcessStatus draw_study_plot(const std::string& tmlab_root, const std::string& study,
                              const std::string& script, const std::filesystem::path& dir,
                              const ProcessOutput& output) {
  const std::filesystem::path path =
      std::filesystem::path(tmlab_root) / "studies" / study / "python" / script;
  return run_python(path, {dir.string()}, output);
}

}  // namespace tmlab::tm
