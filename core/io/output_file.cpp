// check_output_files: see output_file.hpp.
#include "core/io/output_file.hpp"

#include "core/base/error.hpp"
#include "core/base/format.hpp"

namespace fs = std::filesystem;

namespace tmlab {

void check_output_files(const std::vector<fs::path>& targets, const std::vector<fs::path>& inputs,
                        bool overwrite, const std::string& overwrite_option) {
  for (const fs::path& t : targets) {
    const std::string shown = printable(t.string(), 300);
    std::error_code ec;
    if (fs::is_symlink(fs::symlink_status(t, ec)) && !fs::exists(fs::status(t, ec)))
      throw Error(shown + ": is a symbolic link to " + printable(fs::read_symlink(t, ec).string(), 300) +
                  ", which does not exist: writing it would create a file elsewhere; name another output");
    const fs::file_status st = fs::status(t, ec);
    if (!fs::exists(st)) continue;
    for (const fs::path& in : inputs) {
      std::error_code eq;
      if (fs::equivalent(t, in, eq) && !eq)
        throw Error(shown + ": is the input " + printable(in.string(), 300) +
                    ": tmlab never writes over an input; name another output folder or file");
    }
    if (!fs::is_regular_file(st))
      throw Error(shown + ": exists and is not a regular file; name another output folder or file");
    if (!overwrite)
      throw Error(shown + ": exists already; nothing was written (give " + overwrite_option +
                  " to replace it, or name another output folder)");
  }
}

}  // namespace tmlab
