// Which folders tmlab may write a result into, and which files in them are tmlab's.
//
// A result directory proves that tmlab wrote it with an ownership marker, `.tmlab-result`:
//
//   {"format": "tmlab-result/1", "run_id": "<32 hex digits>", "created_utc": "...",
//    "files": ["manifest.json", "summary.json", "vtu/step_000001.vtu", ...]}
//
// written by RunOutput when it takes a folder and rewritten, listing every file of the finished result,
// just before the result is moved into place. A folder is taken only when it does not exist, is empty,
// or holds a valid marker; replacing a previous result removes exactly the files its marker lists
// (plus the protocol's own: RUNNING, FAILED, INTERRUPTED, summary.json, .incomplete/), never anything
// else: a folder that holds files its marker does not list is refused, and so is a marker that lists a
// path outside the folder or through a symbolic link. A `manifest.json` proves nothing (issue 26).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace tmlab::result_dir {

inline constexpr const char* kMarker = ".tmlab-result";
inline constexpr const char* kFormat = "tmlab-result/1";
// The protocol's own entries (RunOutput): always tmlab's in a folder that holds a marker.
inline constexpr const char* kStaging = ".incomplete";
inline constexpr const char* kRunning = "RUNNING";
inline constexpr const char* kFailed = "FAILED";
inline constexpr const char* kInterrupted = "INTERRUPTED";
inline constexpr const char* kSummary = "summary.json";

/// The folder a result path names, resolved as the result will be written: "" is refused; a
/// symbolic link is followed (the result goes into its target; the link stays a link), as are links
/// among its parents; "a/b/" is "a/b". Refused (tmlab::Error naming the path and the rule) when it
/// resolves to the current directory, one of its ancestors, the home directory or "/": a result
/// needs a folder of its own. The folder need not exist.
std::filesystem::path resolve(const std::filesystem::path& path);

/// What a folder holds from tmlab's point of view.
struct Inventory {
  bool exists = false;               ///< the folder exists
  bool has_marker = false;           ///< a valid `.tmlab-result` marker
  std::string run_id;                ///< the marker's run id
  std::vector<std::string> listed;   ///< files the marker lists (relative, checked)
  std::vector<std::string> foreign;  ///< entries tmlab did not write (relative; "dir/" for folders)
};

/// Reads `dir` (never writes). tmlab::Error, naming the folder and what is wrong, for a marker that
/// is not valid JSON of the format or lists a path that is absolute, empty, leaves the folder ("..")
/// or passes through a symbolic link.
Inventory inspect(const std::filesystem::path& dir);

/// Throws tmlab::Error unless `dir` may be taken for a new result: it does not exist, is empty, or
/// holds a valid marker and nothing else tmlab did not write. The message names the folder and up to
/// five of the foreign entries, and says that nothing was changed.
void check_may_take(const std::filesystem::path& dir, const Inventory& inv);

/// Removes what a previous result in `dir` left: summary.json first, then every file the marker lists,
/// the protocol files, and `.incomplete/` unless `keep_staging`; then the folders that held listed files
/// when they are empty. Never touches anything else. tmlab::Error naming the file that cannot be removed.
void clear_previous(const std::filesystem::path& dir, const Inventory& inv, bool keep_staging);

/// Writes the marker (atomically) with a new run id or the given one and the file list.
/// Returns the run id written.
std::string write_marker(const std::filesystem::path& dir, const std::string& run_id,
                         const std::vector<std::string>& files);

/// A new random run id: 32 hex digits.
std::string new_run_id();

/// Every regular file and symbolic link under `root`, as sorted relative paths ("a/b.vtu").
std::vector<std::string> list_files(const std::filesystem::path& root);

}  // namespace tmlab::result_dir
