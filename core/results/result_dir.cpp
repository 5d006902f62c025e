// Result-folder ownership: see result_dir.hpp.
#include "core/results/result_dir.hpp"

#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/io/atomic_file.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <iterator>
#include <random>
#include <set>

namespace fs = std::filesystem;

namespace tmlab::result_dir {

namespace {

std::string shown(const fs::path& p) { return printable(p.string(), 300); }

/// Is `a` equal to `b` or one of b's ancestors? Both absolute and normal.
bool is_same_or_ancestor(const fs::path& a, const fs::path& b) {
  auto ia = a.begin(), ib = b.begin();
  for (; ia != a.end(); ++ia, ++ib) {
    if (ia->empty()) continue;  // a trailing separator
    if (ib == b.end() || *ia != *ib) return false;
  }
  return true;
}

bool is_protocol_name(const std::string& name) {
  for (const char* n : {kMarker, kStaging, kRunning, kFailed, kInterrupted, kSummary})
    if (name == n) return true;
  return false;
}

/// A temporary of write_file_atomically beside an owned file: "<owned>.tmp" + 6 characters (mkstemp),
/// or "<owned>.tmp" (older tmlab). A crash can leave one behind; it is tmlab's.
bool is_temporary_of(const std::string& rel, const std::set<std::string>& owned) {
  const auto pos = rel.rfind(".tmp");
  if (pos == std::string::npos) return false;
  const std::size_t tail = rel.size() - pos - 4;
  if (tail != 0 && tail != 6) return false;
  const std::string base = rel.substr(0, pos);
  return owned.count(base) > 0 || is_protocol_name(base);
}

/// A listed path must be relative, normal, inside, and free of ".." and of "." components.
std::string listed_path_problem(const std::string& entry) {
  if (entry.empty()) return "is empty";
  if (entry.size() > 4096) return "is longer than 4096 characters";
  if (entry.find('\0') != std::string::npos) return "contains a NUL byte";
  const fs::path p(entry);
  if (p.is_absolute() || entry.front() == '/') return "is absolute";
  if (p.lexically_normal().generic_string() != entry) return "is not a normal relative path";
  for (const auto& part : p)
    if (part == ".." || part == ".") return "leaves the folder";
  if (is_protocol_name(p.begin()->string()) && p.begin()->string() != kSummary)
    return "names a file of the protocol itself";
  return {};
}

/// Does any folder on the way from `dir` to `dir/rel` (excluded) be a symbolic link or a non-folder?
bool passes_through_link(const fs::path& dir, const fs::path& rel) {
  fs::path at = dir;
  const fs::path parent = rel.parent_path();
  for (const auto& part : parent) {
    at /= part;
    std::error_code ec;
    const fs::file_status st = fs::symlink_status(at, ec);
    if (ec || !fs::exists(st)) return false;  // nothing there: nothing to remove through it
    if (fs::is_symlink(st) || !fs::is_directory(st)) return true;
  }
  return false;
}

std::string read_small(const fs::path& p, std::size_t limit) {
  std::ifstream in(p, std::ios::binary);
  std::string text;
  text.resize(limit + 1);
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  return text;
}

void parse_marker(const fs::path& dir, Inventory& inv) {
  const fs::path marker = dir / kMarker;
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(marker, ec);
  if (ec || !fs::exists(st)) return;
  const auto bad = [&](const std::string& why) {
    return Error(shown(marker) + ": " + why + "; it is not a marker tmlab wrote, so nothing in " +
                 shown(dir) + " was changed");
  };
  if (!fs::is_regular_file(st)) throw bad("is not a regular file");
  constexpr std::size_t kLimit = 64 << 20;
  const std::string text = read_small(marker, kLimit);
  if (text.size() > kLimit) throw bad("is larger than 64 MiB");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const std::exception& e) {
    throw bad(std::string("is not valid JSON (") + e.what() + ")");
  }
  if (!j.is_object() || j.value("format", "") != std::string(kFormat))
    throw bad(std::string("has no \"format\": \"") + kFormat + "\"");
  if (!j.contains("run_id") || !j["run_id"].is_string()) throw bad("has no \"run_id\"");
  if (!j.contains("files") || !j["files"].is_array()) throw bad("has no \"files\" list");
  for (const auto& f : j["files"]) {
    if (!f.is_string()) throw bad("lists an entry that is not a string");
    const std::string entry = f.get<std::string>();
    const std::string why = listed_path_problem(entry);
    if (!why.empty()) throw bad("lists '" + printable(entry, 100) + "', which " + why);
    if (passes_through_link(dir, entry))
      throw bad("lists '" + printable(entry, 100) + "', which passes through a symbolic link or a file");
    inv.listed.push_back(entry);
  }
  inv.run_id = j["run_id"].get<std::string>();
  inv.has_marker = true;
}

}  // namespace

fs::path resolve(const fs::path& path) {
  if (path.empty())
    throw Error(
        "the result directory is empty (\"\"): a result needs a folder of its own (e.g. results/NAME)");
  std::error_code ec;
  fs::path p = fs::absolute(path, ec);
  if (ec) throw Error(shown(path) + ": cannot resolve the result directory: " + ec.message());
  p = fs::weakly_canonical(p, ec);  // follows links among the existing part of the path
  if (ec) throw Error(shown(path) + ": cannot resolve the result directory: " + ec.message());
  if (!p.has_filename() && p != p.root_path()) p = p.parent_path();  // "a/b/" -> "a/b"
  // A link that points at nothing: its target would be created; say where, rather than guess.
  const fs::file_status lst = fs::symlink_status(path, ec);
  if (!ec && fs::is_symlink(lst) && !fs::exists(fs::status(path, ec)))
    throw Error(shown(path) + ": is a symbolic link to " + shown(fs::read_symlink(path, ec)) +
                ", which does not exist: create the target folder first, or name another folder");
  std::string what;
  const fs::path cwd = fs::weakly_canonical(fs::current_path(ec), ec);
  if (p == p.root_path()) what = "/";
  if (what.empty() && !cwd.empty() && is_same_or_ancestor(p, cwd))
    what = p == cwd ? "the current directory" : "a parent of the current directory";
  if (const char* home = std::getenv("HOME"); what.empty() && home != nullptr && *home != '\0') {
    std::error_code hec;
    if (p == fs::weakly_canonical(home, hec) && !hec) what = "the home directory";
  }
  if (!what.empty())
    throw Error(shown(path) + (p != fs::path(path) ? " (" + shown(p) + ")" : std::string()) + ": is " + what +
                ": a result needs a folder of its own, which tmlab creates or has written before (e.g. " +
                "results/NAME); nothing was written");
  return p;
}

Inventory inspect(const fs::path& dir) {
  Inventory inv;
  std::error_code ec;
  const fs::file_status st = fs::status(dir, ec);
  if (ec || !fs::exists(st)) return inv;
  if (!fs::is_directory(st)) throw Error(shown(dir) + ": result path exists and is not a directory");
  inv.exists = true;
  parse_marker(dir, inv);
  std::set<std::string> owned(inv.listed.begin(), inv.listed.end());
  std::set<std::string> parents;  // folders that hold listed files
  for (const std::string& f : inv.listed)
    for (fs::path q = fs::path(f).parent_path(); !q.empty(); q = q.parent_path())
      parents.insert(q.generic_string());
  auto it = fs::recursive_directory_iterator(dir, fs::directory_options::none, ec);
  if (ec) throw Error(shown(dir) + ": cannot read the folder: " + ec.message());
  for (; it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (ec) throw Error(shown(dir) + ": cannot read the folder: " + ec.message());
    const std::string rel = it->path().lexically_relative(dir).generic_string();
    const bool top = it.depth() == 0;
    const bool is_dir = it->is_directory(ec) && !it->is_symlink(ec);
    if (inv.has_marker && top && is_protocol_name(rel)) {
      if (is_dir) it.disable_recursion_pending();  // .incomplete/ is the staging area: all tmlab's
      continue;
    }
    if (inv.has_marker && (owned.count(rel) > 0 || is_temporary_of(rel, owned))) continue;
    if (is_dir && inv.has_marker && parents.count(rel) > 0) continue;
    inv.foreign.push_back(rel + (is_dir ? "/" : ""));
    if (is_dir) it.disable_recursion_pending();
  }
  std::sort(inv.foreign.begin(), inv.foreign.end());
  return inv;
}

void check_may_take(const fs::path& dir, const Inventory& inv) {
  if (!inv.exists || inv.foreign.empty()) return;
  std::string names;
  for (std::size_t k = 0; k < inv.foreign.size() && k < 5; ++k)
    names += (k ? ", " : "") + printable(inv.foreign[k], 80);
  if (inv.foreign.size() > 5) names += " and " + std::to_string(inv.foreign.size() - 5) + " more";
  if (!inv.has_marker)
    throw Error(
        shown(dir) + ": not a tmlab result directory (it holds " + names + " and no " + kMarker +
        " marker written by tmlab; a manifest.json proves nothing): tmlab removes nothing it did not " +
        "write, so name a new or empty folder, or empty this one yourself; nothing was changed");
  throw Error(shown(dir) + ": this tmlab result directory also holds files tmlab did not write (" + names +
              "): move them out or name another folder; nothing was changed");
}

void clear_previous(const fs::path& dir, const Inventory& inv, bool keep_staging) {
  if (!inv.exists) return;
  std::error_code ec;
  const auto remove_one = [&](const fs::path& p) {
    fs::remove(p, ec);  // a file or a symbolic link (never followed), or an empty folder
    if (ec) throw Error(shown(p) + ": cannot remove the previous result's file: " + ec.message());
  };
  // The previous run no longer describes this folder: its completeness mark goes first.
  remove_one(dir / kSummary);
  if (!inv.has_marker) return;  // an empty folder: nothing else to remove
  std::set<fs::path> folders;
  for (const std::string& f : inv.listed) {
    remove_one(dir / f);
    for (fs::path q = fs::path(f).parent_path(); !q.empty(); q = q.parent_path()) folders.insert(q);
  }
  // Temporaries a crash left beside the files (see is_temporary_of), found by a fresh look.
  const std::set<std::string> owned(inv.listed.begin(), inv.listed.end());
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    const std::string rel = it->path().lexically_relative(dir).generic_string();
    if (it.depth() == 0 && rel == kStaging) {
      it.disable_recursion_pending();
      continue;
    }
    if (!it->is_directory() && is_temporary_of(rel, owned)) fs::remove(it->path(), ec);
  }
  ec.clear();
  for (const char* name : {kRunning, kFailed, kInterrupted}) remove_one(dir / name);
  if (!keep_staging) {
    fs::remove_all(dir / kStaging, ec);  // the staging area is tmlab's whole (links are not followed)
    if (ec) throw Error(shown(dir / kStaging) + ": cannot remove the previous staging area: " + ec.message());
  }
  // Deepest first: a folder goes only when nothing is left in it.
  for (auto f = folders.rbegin(); f != folders.rend(); ++f) {
    std::error_code ignored;
    if (fs::is_empty(dir / *f, ignored)) fs::remove(dir / *f, ignored);
  }
}

std::string new_run_id() {
  std::random_device rd;
  std::array<char, 33> hex{};
  for (int k = 0; k < 4; ++k) std::snprintf(hex.data() + 8 * k, 9, "%08x", static_cast<unsigned>(rd()));
  return hex.data();
}

std::string write_marker(const fs::path& dir, const std::string& run_id,
                         const std::vector<std::string>& files) {
  const std::string id = run_id.empty() ? new_run_id() : run_id;
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&now, &tm);
  std::array<char, 32> stamp{};
  std::strftime(stamp.data(), stamp.size(), "%Y-%m-%dT%H:%M:%SZ", &tm);
  const nlohmann::json j = {
      {"format", kFormat},
      {"run_id", id},
      {"written_utc", stamp.data()},
      {"note", "written by tmlab: the files of this result, which a later run may replace"},
      {"files", files}};
  write_file_atomically(dir / kMarker, j.dump(1) + "\n");
  return id;
}

std::vector<std::string> list_files(const fs::path& root) {
  std::vector<std::string> out;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(root, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    if (it->is_directory(ec) && !it->is_symlink(ec)) continue;
    out.push_back(it->path().lexically_relative(root).generic_string());
  }
  if (ec) throw Error(shown(root) + ": cannot list the staged result: " + ec.message());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace tmlab::result_dir
