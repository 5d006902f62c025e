// write_file_atomically: see atomic_file.hpp.
#include "core/io/atomic_file.hpp"

#include "core/base/error.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <system_error>

#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

namespace tmlab {

void write_file_atomically(const std::filesystem::path& path, const std::string& content) {
  // A fresh temporary beside the target ("<path>.tmpXXXXXX", O_EXCL): never a file that was there.
  std::string tmpl = path.string() + ".tmpXXXXXX";
  const int fd = ::mkstemp(tmpl.data());
  if (fd < 0) throw Error(path.string() + ": cannot write (" + std::strerror(errno) + ")");
  const std::filesystem::path tmp = tmpl;
  ::fchmod(fd, 0644);  // mkstemp makes 0600; results are ordinary readable files
  std::size_t done = 0;
  bool ok = true;
  while (ok && done < content.size()) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0 && errno == EINTR) continue;
    ok = n > 0;
    if (ok) done += static_cast<std::size_t>(n);
  }
  ok = ok && ::fsync(fd) == 0;  // the data is on disk before the name points at it
  const int saved_errno = errno;
  ok = (::close(fd) == 0) && ok;
  if (!ok) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw Error(path.string() + ": write failed (" + std::strerror(saved_errno != 0 ? saved_errno : errno) +
                ")");
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
