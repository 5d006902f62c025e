#include "cli_args.hpp"

#include "commands.hpp"

#include "core/base/error.hpp"

#include <filesystem>
#include <sstream>

namespace tmlab::cli {

std::vector<std::string> split_words(const std::string& s) {
  std::istringstream in(s);
  std::vector<std::string> w;
  for (std::string x; in >> x;) w.push_back(x);
  return w;
}

std::pair<int, int> parse_cells_layers(const std::string& m) {
  const std::size_t comma = m.find(',');
  if (comma == std::string::npos) throw UsageError("--mesh needs CELLS,LAYERS, got '" + m + "'");
  return {int(parse_whole("--mesh CELLS", m.substr(0, comma), 2, 400)),
          int(parse_whole("--mesh LAYERS", m.substr(comma + 1), 1, 400))};
}

CheckpointSchedule checkpoint_schedule(const ParsedOptions& p) {
  try {
    return p.given("--checkpoint-every") ? CheckpointSchedule::parse(p.text("--checkpoint-every"))
                                         : CheckpointSchedule{};
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
}

std::string results_root(const ParsedOptions& p) {
  return p.given("--results") ? p.text("--results")
                              : (std::filesystem::path(tmlab_root()) / "results").string();
}

}  // namespace tmlab::cli
