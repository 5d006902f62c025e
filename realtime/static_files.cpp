#include "realtime/static_files.hpp"

#include "core/base/error.hpp"

#include <algorithm>

namespace tmlab::rt {

namespace fs = std::filesystem;

namespace {

int hex(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

/// Percent-decodes once; nullopt for a malformed escape.
std::optional<std::string> percent_decode(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '%') {
      out += s[i];
      continue;
    }
    if (i + 2 >= s.size()) return std::nullopt;
    const int hi = hex(s[i + 1]), lo = hex(s[i + 2]);
    if (hi < 0 || lo < 0) return std::nullopt;
    out += static_cast<char>(hi * 16 + lo);
    i += 2;
  }
  return out;
}

bool allowed_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '_' ||
         c == '-' || c == '/';
}

/// True when `p` (canonical) lies inside `root` (canonical).
bool inside(const fs::path& p, const fs::path& root) {
  auto r = root.begin(), q = p.begin();
  for (; r != root.end(); ++r, ++q)
    if (q == p.end() || *q != *r) return false;
  return true;
}

}  // namespace

void StaticFiles::mount(const std::string& url_prefix, const fs::path& dir) {
  if (url_prefix.empty() || url_prefix.front() != '/' || url_prefix.back() != '/')
    throw Error("static files: mount prefix '" + url_prefix + "' must start and end with '/'");
  mounts_.push_back({url_prefix, dir});
  std::stable_sort(mounts_.begin(), mounts_.end(),
                   [](const Mount& a, const Mount& b) { return a.prefix.size() > b.prefix.size(); });
}

std::optional<fs::path> StaticFiles::resolve(std::string_view target) const {
  target = target.substr(0, target.find_first_of("?#"));
  const std::optional<std::string> decoded = percent_decode(target);
  if (!decoded || decoded->empty() || decoded->front() != '/') return std::nullopt;
  std::string path = *decoded;
  if (!std::all_of(path.begin(), path.end(), allowed_char)) return std::nullopt;
  if (path.back() == '/') path += "index.html";
  // Every segment after the leading '/' must be a plain name: not empty, not "." or "..".
  for (std::size_t b = 1; b <= path.size();) {
    const std::size_t e = std::min(path.find('/', b), path.size());
    const std::string_view seg = std::string_view(path).substr(b, e - b);
    if (seg.empty() || seg == "." || seg == "..") return std::nullopt;
    b = e + 1;
  }
  for (const Mount& m : mounts_) {
    if (path.compare(0, m.prefix.size(), m.prefix) != 0) continue;
    std::error_code ec;
    const fs::path root = fs::canonical(m.dir, ec);
    if (ec) return std::nullopt;
    const fs::path file = fs::canonical(root / path.substr(m.prefix.size()), ec);
    if (ec || !inside(file, root) || !fs::is_regular_file(file, ec)) return std::nullopt;
    return file;
  }
  return std::nullopt;
}

std::string StaticFiles::content_type(const fs::path& file) {
  const std::string ext = file.extension().string();
  if (ext == ".html") return "text/html; charset=utf-8";
  if (ext == ".js" || ext == ".mjs") return "text/javascript; charset=utf-8";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".json") return "application/json";
  if (ext == ".png") return "image/png";
  if (ext == ".svg") return "image/svg+xml";
  if (ext == ".txt" || ext == ".md") return "text/plain; charset=utf-8";
  return "application/octet-stream";
}

}  // namespace tmlab::rt
