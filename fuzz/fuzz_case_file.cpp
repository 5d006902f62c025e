// libFuzzer target: the case-file reader (strict JSON with duplicate-key, number and type checks,
// then parse_case with its selectors, time functions, Prony series, solver and output sections) and
// the effective-configuration round trip. Any input must give a case or a tmlab::Error.
#include "core/base/error.hpp"
#include "core/config/case_config.hpp"
#include "core/config/config_reader.hpp"
#include "fuzz/fuzz_input.hpp"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace {
/// A directory with a mesh file named m.msh, so that cases naming it get past the file check.
std::string search_dir() {
  const std::filesystem::path d =
      std::filesystem::temp_directory_path() / ("tmlab-fuzz-" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  std::ofstream(d / "m.msh") << "placeholder\n";
  return d.string();
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string dir = search_dir();
  tmlab::fuzz::MemoryFile file(data, size);
  try {
    const nlohmann::json doc = tmlab::ConfigReader::parse_file(file.path());
    const tmlab::CaseConfig c = tmlab::parse_case(doc, file.path(), {dir});
    // The effective configuration must parse back to the same case.
    const nlohmann::json e = tmlab::effective_case_json(c);
    if (tmlab::effective_case_json(tmlab::parse_case(e, "effective", {dir})) != e) std::abort();
  } catch (const tmlab::Error&) {
  }
  return 0;
}
