// libFuzzer target: the verification catalogue's case reader (verify.json: checks, tolerances,
// rationales, labels, suite). Any input must give a case or a tmlab::Error.
#include "core/base/error.hpp"
#include "verification/harness/case_spec.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace {
std::filesystem::path case_dir() {
  const std::filesystem::path d = std::filesystem::temp_directory_path() /
                                  ("tmlab-fuzz-verify-" + std::to_string(::getpid())) / "fuzz-case";
  std::filesystem::create_directories(d);
  std::ofstream(d / "README.md") << "# fuzz-case\n";
  return d;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path dir = case_dir();
  {
    std::ofstream out(dir / "verify.json", std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    (void)tmlab::verify::load_case(dir);
  } catch (const tmlab::Error&) {
  }
  return 0;
}
