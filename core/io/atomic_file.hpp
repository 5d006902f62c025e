// Crash-safe file writing for results: content goes to a temporary file next to the target, which
// is then renamed over it (atomic on POSIX), so a crash never leaves a half-written file under the
// final name.
#pragma once

#include <filesystem>
#include <string>

namespace tmlab {

/// Writes `content` to `path` via a fresh temporary "<path>.tmpXXXXXX" (created exclusively, so no
/// file that was there is ever written into) and a rename; mode 0644. Throws tmlab::Error naming the
/// file (the temporary is removed on failure).
void write_file_atomically(const std::filesystem::path& path, const std::string& content);

}  // namespace tmlab
