// write_file_atomically: see atomic_file.hpp.
#include "core/io/atomic_file.hpp"

#include "core/base/error.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <system_error>

#include <unistd.h>

namespace tmlab {

void write_file_atomically(const std::filesystem::path& path, const std::string& content) {
  std::filesystem::path tmp = path;
  tmp += ".tmp";
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (f == nullptr) {
    throw Error(path.string() + ": cannot write (" + std::strerror(errno) + ")");
  }
  const std::size_t written = content.empty() ? 0 : std::fwrite(content.data(), 1, content.size(), f);
  bool ok = written == content.size();
  ok = (std::fflush(f) == 0) && ok;
  ok = (::fsync(::fileno(f)) == 0) && ok;  // the data is on disk before the name points at it
  const int saved_errno = errno;
  ok = (std::fclose(f) == 0) && ok;
  if (!ok) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw Error(path.string() + ": write failed (" + std::strerror(saved_errno) + ")");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw Error(path.string() + ": cannot move finished file into place (" + ec.message() + ")");
  }
}

}  // namespace tmlab
