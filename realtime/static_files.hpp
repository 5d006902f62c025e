// The files `tmlab realtime --serve` may send: URL prefixes mounted on directories (the page in
// realtime/web/page/, three.js installed at set-up in build/npm/node_modules/three/). Nothing
// outside the mounted directories can be named:
//   - the target is percent-decoded once; the query and fragment are dropped;
//   - only [A-Za-z0-9._-] path segments separated by '/' are accepted: no "..", ".", empty
//     segment, backslash, NUL, '%' left after decoding or other character;
//   - the file must be a regular file whose canonical path (symlinks resolved) lies inside the
//     canonical mount directory.
// Kept free of network code: tested on its own (test_static_files) and over HTTP (test_live_server).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tmlab::rt {

class StaticFiles {
 public:
  /// Serves `dir` under `url_prefix` (starts and ends with '/'; "/" for the root). A directory
  /// request ("/" or ".../") means its index.html. A missing directory is allowed (its files are
  /// then simply not found; the page says what to install).
  void mount(const std::string& url_prefix, const std::filesystem::path& dir);
  /// The file for a request target, or nullopt (not found, or not allowed: the caller answers 404).
  std::optional<std::filesystem::path> resolve(std::string_view target) const;
  /// The Content-Type for a file name (by extension; application/octet-stream otherwise).
  static std::string content_type(const std::filesystem::path& file);

 private:
  struct Mount {
    std::string prefix;
    std::filesystem::path dir;
  };
  std::vector<Mount> mounts_;  // longest prefix first
};

}  // namespace tmlab::rt
