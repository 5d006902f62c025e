// Shared by the harness tests: a scratch directory, a file writer and a good case file.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace tmlab::verify::test {

/// A fresh directory under the system temp directory, removed again by the destructor.
class TempDir {
 public:
  TempDir()
      : dir_(std::filesystem::temp_directory_path() / ("tmlab_verify_test_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  ~TempDir() { std::filesystem::remove_all(dir_); }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return dir_; }

 private:
  std::filesystem::path dir_;
};

inline void write(const std::filesystem::path& p, const std::string& text) {
  std::filesystem::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

/// A complete, valid verify.json (kind test.power_law: one metric check, one convergence check).
inline const char* const kGoodCase = R"({
  "title": "t", "what": "w", "reference": "r", "labels": ["kernel"], "suite": "fast",
  "kind": "test.power_law",
  "parameters": {"order": 2.0},
  "checks": [{"metric": "e", "max": 1e-3, "rationale": "because"}],
  "convergence": [{"series": "s", "expected_order": 2, "order_tolerance": 0.1, "finest_max": 1e-3,
                   "fit_points": 3, "rationale": "P1"}]
})";

}  // namespace tmlab::verify::test
