// Files a command writes into a folder the user names (not a result directory): `data convert`'s
// NAME.csv + NAME.json, `rig`'s NAME.msh + NAME.json, `mesh check --repair OUT.msh`. tmlab never
// writes over one of the command's own inputs, and never over an existing file unless the user says
// so (--overwrite); both are checked for every target before the first byte is written.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace tmlab {

/// Throws tmlab::Error naming the file when any of `targets` is one of `inputs` (the same file, also
/// through links or another spelling of the path), is a directory or another non-regular file, or
/// exists while `overwrite` is false (the message names `overwrite_option`, e.g. "--overwrite").
void check_output_files(const std::vector<std::filesystem::path>& targets,
                        const std::vector<std::filesystem::path>& inputs, bool overwrite,
                        const std::string& overwrite_option = "--overwrite");

}  // namespace tmlab
