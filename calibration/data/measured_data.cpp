// The tmlab-measured/1 reader and writer (measured_data.hpp, docs/measured-data.md).
#include "calibration/data/measured_data.hpp"

#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/base/number.hpp"
#include "core/config/config_reader.hpp"
#include "core/io/atomic_file.hpp"
#include "core/io/output_file.hpp"
#include "core/io/xml_text.hpp"  // format_double: the shortest text that reads back to the same double

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <set>
#include <string_view>

namespace tmlab::measured {

namespace fs = std::filesystem;
using nlohmann::json;

// ---------------------------------------------------------------------------------------------
// Names of things
// ---------------------------------------------------------------------------------------------

std::string to_string(TestType t) {
  switch (t) {
    case TestType::indentation:
      return "indentation";
    case TestType::unconfined_compression:
      return "unconfined_compression";
    case TestType::confined_compression:
      return "confined_compression";
    case TestType::uniaxial_tension:
      return "uniaxial_tension";
  }
  return "?";
}
std::string to_string(IndenterShape s) {
  switch (s) {
    case IndenterShape::sphere:
      return "sphere";
    case IndenterShape::flat_punch:
      return "flat_punch";
    case IndenterShape::cylinder:
      return "cylinder";
  }
  return "?";
}
std::string to_string(SampleShape s) {
  switch (s) {
    case SampleShape::block:
      return "block";
    case SampleShape::cylinder:
      return "cylinder";
    case SampleShape::half_space:
      return "half_space";
  }
  return "?";
}
std::string to_string(Interface i) { return i == Interface::bonded ? "bonded" : "frictionless"; }
bool is_compression(TestType t) {
  return t == TestType::unconfined_compression || t == TestType::confined_compression;
}

fs::path metadata_path(const fs::path& csv) {
  fs::path j = csv;
  j.replace_extension(".json");
  return j;
}

namespace {

/// "file:line:column: reason", the form of every error of this reader.
Error located(const std::string& file, long line, long column, const std::string& reason) {
  return Error(file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + reason);
}
std::string where(const std::string& file, long line, long column) {
  return file + ":" + std::to_string(line) + ":" + std::to_string(column);
}

/// What a file that is not a regular file is, for a message ("is a directory, not a file").
std::string not_a_file(fs::file_type t) {
  switch (t) {
    case fs::file_type::not_found:
      return "no such file";
    case fs::file_type::directory:
      return "is a directory, not a file";
    case fs::file_type::fifo:
      return "is not a regular file (a FIFO)";
    case fs::file_type::socket:
      return "is not a regular file (a socket)";
    case fs::file_type::block:
    case fs::file_type::character:
      return "is not a regular file (a device)";
    default:
      return "is not a regular file";
  }
}
fs::file_type type_of_mode(mode_t m) {
  if (S_ISREG(m)) return fs::file_type::regular;
  if (S_ISDIR(m)) return fs::file_type::directory;
  if (S_ISFIFO(m)) return fs::file_type::fifo;
  if (S_ISSOCK(m)) return fs::file_type::socket;
  if (S_ISBLK(m)) return fs::file_type::block;
  if (S_ISCHR(m)) return fs::file_type::character;
  return fs::file_type::unknown;
}

/// A file descriptor closed when it goes out of scope.
class Fd {
 public:
  explicit Fd(int fd) : fd_(fd) {}
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  ~Fd() {
    if (fd_ >= 0) ::close(fd_);
  }
  int get() const { return fd_; }

 private:
  int fd_;
};

/// Columns count characters, not bytes: UTF-8 continuation bytes do not start one.
bool starts_character(char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }
}  // namespace

std::string name_problem(const std::string& s) {
  if (s.empty()) return "is empty";
  // The length first: a long name of good characters is refused for its length, with the limit.
  const std::size_t chars = std::size_t(std::count_if(s.begin(), s.end(), starts_character));
  if (chars > kMaxNameLength)
    return "is " + std::to_string(chars) + " characters long: at most " + std::to_string(kMaxNameLength) +
           " (it becomes a file name)";
  const bool plain = s[0] != '.' && s[0] != '-' && std::all_of(s.begin(), s.end(), [](char c) {
                       return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                              c == '_' || c == '-' || c == '.';
                     });
  if (plain) return "";
  return "must be a plain file stem: letters, digits, '_', '-', '.', not starting with '.' or '-' (got \"" +
         printable(s, 60) + "\")";
}

std::string read_input_file(const fs::path& p) {
  std::error_code ec;
  const fs::file_type type = fs::status(p, ec).type();
  if (type != fs::file_type::regular) {
    if (ec && type != fs::file_type::not_found)
      throw Error(p.string() + ": cannot read (" + ec.message() + ")");
    throw Error(p.string() + ": " + not_a_file(type));
  }
  // Non-blocking: should the path have become a FIFO since, opening it does not wait for a writer;
  // fstat then refuses it before a read could wait.
  Fd fd(::open(p.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC));
  if (fd.get() < 0) throw Error(p.string() + ": cannot open file (" + std::strerror(errno) + ")");
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0) throw Error(p.string() + ": cannot read (" + std::strerror(errno) + ")");
  if (!S_ISREG(st.st_mode)) throw Error(p.string() + ": " + not_a_file(type_of_mode(st.st_mode)));
  std::string text;
  text.reserve(std::size_t(st.st_size));
  char buf[65536];
  for (;;) {
    const ssize_t n = ::read(fd.get(), buf, sizeof buf);
    if (n == 0) break;
    if (n < 0) {
      if (errno == EINTR) continue;
      throw Error(p.string() + ": read error (" + std::strerror(errno) + ")");
    }
    text.append(buf, std::size_t(n));
  }
  return text;
}

namespace {

bool valid_identifier(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
  });
}

// Units: a name carries its unit as a suffix, quantity_unit, where unit is an atom or
// atom_per_atom[_per_atom...] ("speed_m_per_s"); "_1" marks a dimensionless number.
std::set<std::string> unit_atoms() {
  return {"1",   "percent", "s",   "ms", "us",  "min", "h", "Hz", "m",  "cm",  "mm",
          "um",  "m2",      "mm2", "m3", "mm3", "s2",  "N", "mN", "kN", "Pa",  "kPa",
          "MPa", "GPa",     "kg",  "g",  "J",   "mJ",  "W", "C",  "K",  "rad", "deg"};
}
}  // namespace

bool has_unit_suffix(const std::string& name) {
  std::vector<std::string> t;
  std::string cur;
  for (char c : name) {
    if (c == '_') {
      t.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  t.push_back(cur);
  if (t.size() < 2) return false;
  std::size_t k = t.size() - 1;  // index of the first token of the unit
  const std::set<std::string> atoms = unit_atoms();
  if (!atoms.count(t[k])) return false;
  while (k >= 3 && t[k - 1] == "per" && atoms.count(t[k - 2])) k -= 2;
  if (t[k - 1] == "per") return false;  // "speed_per_s": a rate without its numerator unit
  for (std::size_t i = 0; i < k; ++i)
    if (t[i].empty()) return false;
  return true;
}

void check_json_depth(const std::string& text, const std::string& file) {
  // The JSON parser's duplicate-key guard copies the key path at every level (quadratic in the
  // depth): 100k levels took half a minute. Counting brackets outside strings and comments, as the
  // parser would see them, refuses such a file at its 65th level instead.
  enum class In { code, string, escape, line_comment, block_comment };
  In in = In::code;
  bool skip = false;  // the second character of a comment's "/*" or "*/"
  int depth = 0;
  long line = 1, column = 1;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    const char next = i + 1 < text.size() ? text[i + 1] : '\0';
    if (skip) {
      skip = false;
    } else if (in == In::code) {
      if (c == '"') {
        in = In::string;
      } else if (c == '/' && next == '/') {
        in = In::line_comment;
      } else if (c == '/' && next == '*') {
        in = In::block_comment;
        skip = true;
      } else if (c == '[' || c == '{') {
        if (++depth > kMaxJsonDepth)
          throw located(file, line, column,
                        "nested deeper than " + std::to_string(kMaxJsonDepth) +
                            " levels (not a tmlab-measured/1 file)");
      } else if ((c == ']' || c == '}') && depth > 0) {
        --depth;
      }
    } else if (in == In::string) {
      if (c == '\\') in = In::escape;
      if (c == '"') in = In::code;
    } else if (in == In::escape) {
      in = In::string;
    } else if (in == In::line_comment) {
      if (c == '\n') in = In::code;
    } else if (c == '*' && next == '/') {
      in = In::code;
      skip = true;
    }
    if (c == '\n') {
      ++line;
      column = 1;
    } else if (starts_character(next)) {
      ++column;
    }
  }
}

namespace {

// ---------------------------------------------------------------------------------------------
// Where each JSON value is. nlohmann::json keeps no positions, so after ConfigReader::parse_file
// has accepted the text (syntax, duplicate keys, number range) this scanner walks the same text
// once and records the line and column of every value under its key path ("sample.size_m[2]").
// ---------------------------------------------------------------------------------------------
struct Position {
  long line = 1;
  long column = 1;
};

class JsonPositions {
 public:
  JsonPositions(const std::string& text, std::string file) : s_(text), file_(std::move(file)) {
    skip_space();
    value("", 0);
  }
  /// The position of `path`, else of the nearest enclosing value that has one.
  Position at(std::string path) const {
    for (;;) {
      if (auto it = pos_.find(path); it != pos_.end()) return it->second;
      if (path.empty()) return {};
      const std::size_t cut = path.find_last_of(".[");
      path = cut == std::string::npos ? "" : path.substr(0, cut);
    }
  }

 private:
  static constexpr int kMaxDepth = kMaxJsonDepth;  // check_json_depth() refuses deeper text first
  bool done() const { return i_ >= s_.size(); }
  char peek() const { return done() ? '\0' : s_[i_]; }
  void advance() {
    if (done()) return;
    if (s_[i_] == '\n') {
      ++line_;
      column_ = 1;
    } else if (i_ + 1 < s_.size() && starts_character(s_[i_ + 1])) {
      ++column_;
    }
    ++i_;
  }
  void skip_space() {
    for (;;) {
      while (!done() && (peek() == ' ' || peek() == '\t' || peek() == '\r' || peek() == '\n')) advance();
      if (peek() == '/' && i_ + 1 < s_.size() && s_[i_ + 1] == '/') {
        while (!done() && peek() != '\n') advance();
      } else if (peek() == '/' && i_ + 1 < s_.size() && s_[i_ + 1] == '*') {
        advance();
        advance();
        while (!done() && !(peek() == '*' && i_ + 1 < s_.size() && s_[i_ + 1] == '/')) advance();
        advance();
        advance();
      } else {
        return;
      }
    }
  }
  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }
  void value(const std::string& path, int depth) {
    if (depth > kMaxDepth)
      throw located(
          file_, line_, column_,
          "nested deeper than " + std::to_string(kMaxDepth) + " levels (not a tmlab-measured/1 file)");
    pos_.emplace(path, Position{line_, column_});
    const char c = peek();
    if (c == '{' || c == '[') {
      const bool object = c == '{';
      const char close = object ? '}' : ']';
      advance();
      skip_space();
      for (int index = 0; !done() && peek() != close; ++index) {
        const std::size_t before = i_;
        std::string child = path + "[" + std::to_string(index) + "]";
        if (object) {
          child = join(path, string());
          skip_space();
          if (peek() == ':') advance();
          skip_space();
        }
        value(child, depth + 1);
        skip_space();
        if (peek() == ',') advance();
        skip_space();
        if (i_ == before) return;  // not JSON after all: stop rather than loop
      }
      advance();
    } else if (c == '"') {
      string();
    } else {
      while (!done() && std::string_view(",]} \t\r\n/").find(peek()) == std::string_view::npos) advance();
    }
  }
  /// A JSON string at the cursor, decoded enough to match nlohmann's keys (escapes, \uXXXX).
  std::string string() {
    std::string out;
    if (peek() != '"') return out;
    advance();
    while (!done() && peek() != '"') {
      if (peek() != '\\') {
        out += peek();
        advance();
        continue;
      }
      advance();
      const char e = peek();
      advance();
      switch (e) {
        case 'n':
          out += '\n';
          break;
        case 't':
          out += '\t';
          break;
        case 'r':
          out += '\r';
          break;
        case 'b':
          out += '\b';
          break;
        case 'f':
          out += '\f';
          break;
        case 'u': {
          unsigned cp = 0;
          for (int k = 0; k < 4 && !done(); ++k) {
            const char h = peek();
            advance();
            cp = cp * 16 + unsigned(h >= 'a' ? h - 'a' + 10 : h >= 'A' ? h - 'A' + 10 : h - '0');
          }
          // UTF-8 of a BMP code point (a surrogate pair gives a different key: the position then
          // falls back to the enclosing object, which is still the right place to look).
          if (cp < 0x80) {
            out += char(cp);
          } else if (cp < 0x800) {
            out += char(0xC0 | (cp >> 6));
            out += char(0x80 | (cp & 0x3F));
          } else {
            out += char(0xE0 | (cp >> 12));
            out += char(0x80 | ((cp >> 6) & 0x3F));
            out += char(0x80 | (cp & 0x3F));
          }
          break;
        }
        default:
          out += e;
      }
    }
    advance();
    return out;
  }

  const std::string& s_;
  std::string file_;
  std::size_t i_ = 0;
  long line_ = 1;
  long column_ = 1;
  std::map<std::string, Position> pos_;
};

// ---------------------------------------------------------------------------------------------
// NAME.json
// ---------------------------------------------------------------------------------------------

/// A JSON value for a message, cut to 60 characters.
std::string shown(const json& v) {
  const std::string s = v.dump();
  return s.size() <= 60 ? s : s.substr(0, 57) + "...";
}

/// Does this value hold a number anywhere outside nested objects (a number or an array of them)?
bool holds_number(const json& v) {
  if (v.is_number()) return true;
  if (v.is_array()) return std::any_of(v.begin(), v.end(), [](const json& e) { return holds_number(e); });
  return false;
}

class MetadataParser {
 public:
  MetadataParser(const json& doc, const std::string& text, std::string file, std::vector<Note>& notes)
      : doc_(doc), pos_(text, file), file_(std::move(file)), notes_(notes) {}

  Metadata parse() {
    if (!doc_.is_object()) throw error("", "the document must be a JSON object");
    Metadata m;
    // Unit-less numbers and unknown keys first: "radius": 0.005 is reported as a number without
    // its unit, not as a missing radius_m.
    const std::set<std::string> top = {"format",        "name",   "test",    "indenter", "sample",
                                       "temperature_C", "source", "license", "notes"};
    const std::string format = string(doc_, "", "format");
    if (format != kFormat)
      throw error("format",
                  "must be \"" + std::string(kFormat) + "\" (got \"" + printable(format, 60) + "\")");
    keep_unknown(doc_, "", top, m);
    m.name = string(doc_, "", "name");
    if (const std::string why = name_problem(m.name); !why.empty()) throw error("name", why);
    m.test = choice<TestType>(doc_, "", "test",
                              {TestType::indentation, TestType::unconfined_compression,
                               TestType::confined_compression, TestType::uniaxial_tension});
    if (m.test == TestType::indentation) {
      m.indenter = indenter(m);
    } else if (doc_.contains("indenter")) {
      throw error("indenter", "is only for indentation tests (test is " + to_string(m.test) + ")");
    }
    m.sample = sample(m);
    if (doc_.contains("temperature_C")) m.temperature_C = number(doc_, "", "temperature_C", false);
    for (const char* k : {"source", "license", "notes"}) {
      if (!doc_.contains(k)) continue;
      const std::string s = string(doc_, "", k);
      if (std::string(k) == "source") m.source = s;
      if (std::string(k) == "license") m.license = s;
      if (std::string(k) == "notes") m.notes = s;
    }
    return m;
  }

 private:
  Error error(const std::string& path, const std::string& reason) const {
    const Position p = pos_.at(path);
    return located(file_, p.line, p.column,
                   path.empty() ? reason : "key '" + printable(path) + "' " + reason);
  }
  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }

  /// Keys of `obj` outside `known`: numbers need a unit in their name (recursively); the rest is
  /// kept in m.extra with a note.
  void keep_unknown(const json& obj, const std::string& path, const std::set<std::string>& known,
                    Metadata& m) {
    for (auto it = obj.begin(); it != obj.end(); ++it) {
      if (known.count(it.key())) continue;
      check_units(it.key(), it.value(), join(path, it.key()));
      m.extra.push_back({path, it.key(), it.value()});
      const Position p = pos_.at(join(path, it.key()));
      notes_.push_back(
          {where(file_, p.line, p.column),
           "key '" + printable(join(path, it.key())) + "' is not part of " + kFormat + ": kept, not used"});
    }
  }
  void check_units(const std::string& key, const json& v, const std::string& path) const {
    if (holds_number(v) && !has_unit_suffix(key))
      throw error(path,
                  "is a unit-less number: the name must end in its unit (radius_m, temperature_C, "
                  "speed_m_per_s; _1 for a dimensionless number)");
    if (v.is_object())
      for (auto it = v.begin(); it != v.end(); ++it) check_units(it.key(), it.value(), join(path, it.key()));
    if (v.is_array())
      for (std::size_t i = 0; i < v.size(); ++i)
        if (v[i].is_object())
          for (auto it = v[i].begin(); it != v[i].end(); ++it)
            check_units(it.key(), it.value(), path + "[" + std::to_string(i) + "]." + it.key());
  }

  /// "missing key" with a hint when the object holds the quantity in another unit (radius_mm).
  Error missing(const json& obj, const std::string& path, const std::string& key) const {
    std::string hint;
    const std::string quantity = key.substr(0, key.rfind('_') + 1);
    for (auto it = obj.begin(); it != obj.end(); ++it)
      if (!quantity.empty() && it.key().rfind(quantity, 0) == 0)
        hint = " (found '" + printable(it.key(), 60) + "': the format wants SI units, " + key + ")";
    const Position p = pos_.at(path);
    return located(
        file_, p.line, p.column,
        "missing key '" + join(path, key) + "'" + (path.empty() ? "" : " in '" + path + "'") + hint);
  }
  const json& value(const json& obj, const std::string& path, const std::string& key) const {
    if (!obj.contains(key)) throw missing(obj, path, key);
    return obj.at(key);
  }
  std::string string(const json& obj, const std::string& path, const std::string& key) const {
    const json& v = value(obj, path, key);
    if (!v.is_string()) throw error(join(path, key), "must be a string (got " + shown(v) + ")");
    return v.get<std::string>();
  }
  double number(const json& obj, const std::string& path, const std::string& key, bool positive) const {
    const json& v = value(obj, path, key);
    if (!v.is_number()) throw error(join(path, key), "must be a number (got " + shown(v) + ")");
    const double d = v.get<double>();
    if (!std::isfinite(d)) throw error(join(path, key), "must be finite");
    if (positive && !(d > 0.0)) throw error(join(path, key), "must be > 0 (got " + shown(v) + ")");
    return d;
  }
  const json& object(const json& obj, const std::string& path, const std::string& key) const {
    const json& v = value(obj, path, key);
    if (!v.is_object())
      throw error(join(path, key), "must be an object (got " + std::string(v.type_name()) + ")");
    return v;
  }
  template <class E>
  E choice(const json& obj, const std::string& path, const std::string& key, std::vector<E> options) const {
    const std::string s = string(obj, path, key);
    std::string list;
    for (E e : options) {
      if (to_string(e) == s) return e;
      list += (list.empty() ? "" : ", ") + to_string(e);
    }
    throw error(join(path, key), "must be one of " + list + " (got \"" + printable(s, 60) + "\")");
  }
  /// A key that must not be there for this shape or test.
  void refuse(const json& obj, const std::string& path, const std::string& key,
              const std::string& why) const {
    if (obj.contains(key)) throw error(join(path, key), why);
  }

  Indenter indenter(Metadata& m) {
    const json& o = object(doc_, "", "indenter");
    keep_unknown(o, "indenter", {"shape", "radius_m", "length_m"}, m);
    Indenter ind;
    ind.shape = choice<IndenterShape>(
        o, "indenter", "shape", {IndenterShape::sphere, IndenterShape::flat_punch, IndenterShape::cylinder});
    ind.radius_m = number(o, "indenter", "radius_m", true);
    if (ind.shape == IndenterShape::cylinder) {
      if (o.contains("length_m")) ind.length_m = number(o, "indenter", "length_m", true);
    } else {
      refuse(o, "indenter", "length_m", "is only for a cylinder indenter");
    }
    return ind;
  }

  Sample sample(Metadata& m) {
    const json& o = object(doc_, "", "sample");
    keep_unknown(o, "sample", {"shape", "size_m", "radius_m", "height_m", "bottom", "platens"}, m);
    Sample s;
    s.shape = choice<SampleShape>(o, "sample", "shape",
                                  {SampleShape::block, SampleShape::cylinder, SampleShape::half_space});
    const std::string not_for = "is not a dimension of a " + to_string(s.shape) + " sample";
    if (s.shape == SampleShape::block) {
      const json& v = value(o, "sample", "size_m");
      if (!v.is_array() || v.size() != 3)
        throw error("sample.size_m",
                    "must be [x, y, z] in metres, z the loaded direction (got " + shown(v) + ")");
      for (int i = 0; i < 3; ++i) {
        const std::string p = "sample.size_m[" + std::to_string(i) + "]";
        if (!v[i].is_number()) throw error(p, "must be a number (got " + shown(v[i]) + ")");
        s.size_m[i] = v[i].get<double>();
        if (!(s.size_m[i] > 0.0) || !std::isfinite(s.size_m[i])) throw error(p, "must be > 0");
      }
      refuse(o, "sample", "radius_m", not_for);
      refuse(o, "sample", "height_m", not_for);
    } else if (s.shape == SampleShape::cylinder) {
      s.radius_m = number(o, "sample", "radius_m", true);
      s.height_m = number(o, "sample", "height_m", true);
      refuse(o, "sample", "size_m", not_for);
    } else {
      for (const char* k : {"size_m", "radius_m", "height_m"}) refuse(o, "sample", k, not_for);
    }
    if (m.test != TestType::indentation && s.shape == SampleShape::half_space)
      throw error("sample.shape", "half_space is only for indentation tests");
    interfaces(o, m.test, s);
    return s;
  }

  /// sample.bottom and sample.platens. Between two platens the bottom platen is the bottom: a
  /// compression test needs `platens` and takes `bottom` from it when `bottom` is absent. A
  /// `bottom` given as well is kept as written; when it differs from `platens` a note says that the
  /// compression rigs use `platens` for both.
  void interfaces(const json& o, TestType test, Sample& s) const {
    const std::vector<Interface> both = {Interface::bonded, Interface::frictionless};
    if (!is_compression(test)) {
      if (s.shape != SampleShape::half_space || o.contains("bottom"))
        s.bottom = choice<Interface>(o, "sample", "bottom", both);
      refuse(o, "sample", "platens", "is only for compression tests (test is " + to_string(test) + ")");
      return;
    }
    if (!o.contains("platens") && o.contains("bottom"))
      throw located(
          file_, pos_.at("sample").line, pos_.at("sample").column,
          "missing key 'sample.platens' in 'sample' (a sample compressed between two platens needs "
          "their interface, bonded or frictionless: 'bottom' alone does not say what the top platen "
          "is; 'platens' alone says both)");
    s.platens = choice<Interface>(o, "sample", "platens", both);
    s.bottom = s.platens;
    if (!o.contains("bottom")) return;
    s.bottom = choice<Interface>(o, "sample", "bottom", both);
    if (*s.bottom == *s.platens) return;
    const Position p = pos_.at("sample.bottom");
    notes_.push_back({where(file_, p.line, p.column),
                      "key 'sample.bottom' is \"" + to_string(*s.bottom) + "\" but 'sample.platens' is \"" +
                          to_string(*s.platens) +
                          "\": between two platens the bottom platen is the bottom, "
                          "and the compression rigs (tmlab rig, fit, discover) use 'platens' for both"});
  }

  const json& doc_;
  JsonPositions pos_;
  std::string file_;
  std::vector<Note>& notes_;
};

Metadata parse_metadata(const json& doc, const std::string& text, const std::string& file,
                        std::vector<Note>& notes) {
  return MetadataParser(doc, text, file, notes).parse();
}

// ---------------------------------------------------------------------------------------------
// NAME.csv
// ---------------------------------------------------------------------------------------------

struct Field {
  std::string_view text;
  long column = 1;
};

/// Splits a line at commas, trimming blanks around each field; columns count characters.
std::vector<Field> split_fields(std::string_view line) {
  std::vector<Field> out;
  std::size_t start = 0;
  for (;;) {
    std::size_t end = line.find(',', start);
    if (end == std::string_view::npos) end = line.size();
    std::size_t a = start, b = end;
    while (a < b && (line[a] == ' ' || line[a] == '\t')) ++a;
    while (b > a && (line[b - 1] == ' ' || line[b - 1] == '\t')) --b;
    long column = 1;
    for (std::size_t k = 0; k < a; ++k)
      if (starts_character(line[k])) ++column;
    out.push_back({line.substr(a, b - a), column});
    if (end == line.size()) break;
    start = end + 1;
  }
  return out;
}

}  // namespace

bool parse_decimal(std::string_view s, double& out, std::string& why) {
  // The grammar is tmlab's one number grammar (core/base/number); only the words for a missing or
  // non-finite sample are the measurement's own.
  if (s.empty()) {
    why = "empty field (every sample needs a value)";
    return false;
  }
  std::string lower;
  for (char c : s.substr(0, 4)) lower += char(std::tolower(static_cast<unsigned char>(c)));
  const std::string_view body =
      (lower[0] == '+' || lower[0] == '-') ? std::string_view(lower).substr(1) : std::string_view(lower);
  if (body.rfind("nan", 0) == 0) {
    why = "NaN is not a measurement (remove the sample or the test)";
    return false;
  }
  if (body.rfind("inf", 0) == 0) {
    why = "an infinite value is not a measurement";
    return false;
  }
  return tmlab::parse_decimal(s, out, why);
}

namespace {

std::vector<Test> parse_samples(const std::string& text, const std::string& file, std::vector<Note>& notes) {
  enum Role { kId, kTime, kDisplacement, kForce, kExtra };
  std::vector<Role> roles;
  std::vector<std::string> names;
  std::vector<std::size_t> extra_index;  // per column: index into Test::extra (kExtra only)
  std::vector<std::string> extra_names;
  bool header_done = false;
  long header_line = 0;
  std::vector<Test> tests;
  std::set<std::string> ids_seen;
  long line_no = 0;
  long last_line = 0;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string_view line(text.data() + start, end - start);
    start = end + 1;
    ++line_no;
    last_line = line_no;
    if (line_no == 1 && line.substr(0, 3) == "\xEF\xBB\xBF") line.remove_prefix(3);  // UTF-8 BOM
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    const std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string_view::npos || line[first] == '#') continue;  // blank or comment
    const std::vector<Field> fields = split_fields(line);

    if (!header_done) {
      header_done = true;
      header_line = line_no;
      std::set<std::string> seen;
      for (const Field& f : fields) {
        const std::string n(f.text);
        if (n.empty()) throw located(file, line_no, f.column, "empty column name in the header");
        if (!valid_identifier(n))
          throw located(file, line_no, f.column,
                        "column name '" + printable(n, 60) +
                            "' is not a tmlab-measured/1 name (letters, digits and '_', the unit last: "
                            "time_s, displacement_m, force_N; 'tmlab data convert' reads other layouts)");
        if (!seen.insert(n).second)
          throw located(file, line_no, f.column, "column '" + n + "' appears twice");
        names.push_back(n);
        extra_index.push_back(0);
        if (n == "test_id") {
          roles.push_back(kId);
        } else if (n == "time_s") {
          roles.push_back(kTime);
        } else if (n == "displacement_m") {
          roles.push_back(kDisplacement);
        } else if (n == "force_N") {
          roles.push_back(kForce);
        } else if (!has_unit_suffix(n)) {
          throw located(file, line_no, f.column,
                        "column '" + n +
                            "' is a unit-less number: the name must end in its unit (time_s, "
                            "displacement_m, force_N; _1 for a dimensionless column)");
        } else {
          roles.push_back(kExtra);
          extra_index.back() = extra_names.size();
          extra_names.push_back(n);
          notes.push_back({where(file, line_no, f.column),
                           "column '" + n + "' is not part of " + std::string(kFormat) + ": kept, not used"});
        }
      }
      for (const char* required : {"time_s", "displacement_m", "force_N"}) {
        if (seen.count(required)) continue;
        const std::string r = required;
        const std::string quantity = r.substr(0, r.find('_') + 1);
        std::string hint;
        for (const std::string& n : names)
          if (n.rfind(quantity, 0) == 0) hint = " (found '" + n + "': the format wants SI units, " + r + ")";
        throw located(file, line_no, 1, "missing column '" + r + "'" + hint);
      }
      continue;
    }

    if (fields.size() != names.size()) {
      const long column = fields.size() > names.size()
                              ? fields[names.size()].column
                              : fields.back().column + long(fields.back().text.size());
      throw located(file, line_no, column,
                    std::to_string(fields.size()) + " fields, but the header (line " +
                        std::to_string(header_line) + ") has " + std::to_string(names.size()) + " columns");
    }
    // Which test: the test_id column, else the one test of the file.
    std::string id;
    for (std::size_t c = 0; c < fields.size(); ++c) {
      if (roles[c] != kId) continue;
      id = std::string(fields[c].text);
      if (id.empty()) throw located(file, line_no, fields[c].column, "column 'test_id': empty test_id");
      if (const std::string why = name_problem(id); !why.empty())
        throw located(file, line_no, fields[c].column, "column 'test_id': test_id " + why);
    }
    if (tests.empty() || tests.back().id != id) {
      if (!ids_seen.insert(id).second) {
        const Test& earlier =
            *std::find_if(tests.begin(), tests.end(), [&](const Test& t) { return t.id == id; });
        throw located(file, line_no, 1,
                      "test '" + id + "' (begun at line " + std::to_string(earlier.first_line) +
                          ") continues after test '" + tests.back().id +
                          "': a test's samples must be contiguous");
      }
      Test t;
      t.id = id;
      t.first_line = line_no;
      for (const std::string& n : extra_names) t.extra.push_back({n, {}});
      tests.push_back(std::move(t));
    }
    Test& t = tests.back();
    for (std::size_t c = 0; c < fields.size(); ++c) {
      if (roles[c] == kId) continue;
      double v = 0.0;
      std::string why;
      if (!parse_decimal(fields[c].text, v, why))
        throw located(file, line_no, fields[c].column, "column '" + names[c] + "': " + why);
      switch (roles[c]) {
        case kTime:
          if (!t.time_s.empty() && !(v > t.time_s.back()))
            throw located(file, line_no, fields[c].column,
                          "column 'time_s': time " + printable(fields[c].text, 40) +
                              " does not increase (the sample before has " + format_double(t.time_s.back()) +
                              ")" + (t.id.empty() ? "" : " in test '" + t.id + "'"));
          t.time_s.push_back(v);
          break;
        case kDisplacement:
          t.displacement_m.push_back(v);
          break;
        case kForce:
          t.force_N.push_back(v);
          break;
        case kExtra:
          t.extra[extra_index[c]].values.push_back(v);
          break;
        case kId:
          break;
      }
    }
  }
  if (!header_done) throw located(file, std::max(1L, last_line), 1, "no header line (an empty file)");
  if (tests.empty()) throw located(file, header_line + 1, 1, "no samples after the header (an empty test)");
  return tests;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Public functions
// ---------------------------------------------------------------------------------------------

DataSet read_data_set(const fs::path& csv) { return read_data_set(csv, metadata_path(csv)); }

DataSet read_data_set(const fs::path& csv, const fs::path& json_file) {
  DataSet d;
  // Both files are read only if they are regular files (a directory or a FIFO is named as such;
  // a FIFO never blocks). Metadata first: a data set without its description is not usable.
  const std::string samples = read_input_file(csv);
  std::error_code ec;
  if (fs::symlink_status(json_file, ec).type() == fs::file_type::not_found)
    throw Error(json_file.string() + ": missing (every " + csv.filename().string() +
                " needs its metadata file beside it, with the same name and .json)");
  const std::string text = read_input_file(json_file);
  check_json_depth(text, json_file.string());  // before the parser, which is slow on deep nesting
  const json doc = ConfigReader::parse_file(json_file.string());
  d.meta = parse_metadata(doc, text, json_file.string(), d.notes);
  d.tests = parse_samples(samples, csv.string(), d.notes);
  if (d.meta.name != csv.stem().string())
    d.notes.push_back({json_file.string(), "name '" + d.meta.name + "' differs from the file name '" +
                                               csv.stem().string() + "'"});
  return d;
}

std::string format_metadata(const Metadata& m) {
  try {
    nlohmann::ordered_json o;
    o["format"] = kFormat;
    o["name"] = m.name;
    o["test"] = to_string(m.test);
    if (m.indenter) {
      o["indenter"]["shape"] = to_string(m.indenter->shape);
      o["indenter"]["radius_m"] = m.indenter->radius_m;
      if (m.indenter->length_m) o["indenter"]["length_m"] = *m.indenter->length_m;
    }
    auto& s = o["sample"];
    s["shape"] = to_string(m.sample.shape);
    if (m.sample.shape == SampleShape::block) s["size_m"] = m.sample.size_m;
    if (m.sample.shape == SampleShape::cylinder) {
      s["radius_m"] = m.sample.radius_m;
      s["height_m"] = m.sample.height_m;
    }
    if (m.sample.bottom) s["bottom"] = to_string(*m.sample.bottom);
    if (m.sample.platens) s["platens"] = to_string(*m.sample.platens);
    if (m.temperature_C) o["temperature_C"] = *m.temperature_C;
    if (!m.source.empty()) o["source"] = m.source;
    if (!m.license.empty()) o["license"] = m.license;
    if (!m.notes.empty()) o["notes"] = m.notes;
    // Unknown keys go back into the object they came from ("sample.colour" into "sample").
    for (const ExtraKey& x : m.extra) {
      const nlohmann::ordered_json v = nlohmann::ordered_json::parse(x.value.dump());
      if (x.object.empty())
        o[x.key] = v;
      else if (x.object == "indenter" || x.object == "sample")
        o[x.object][x.key] = v;
      else
        throw Error("metadata of '" + printable(m.name) + "': unknown key '" + printable(x.key) +
                    "' in an unknown object '" + printable(x.object) + "'");
    }
    return o.dump(2) + "\n";
  } catch (const nlohmann::json::exception& e) {
    // Strings made in memory that are not UTF-8 (the reader only ever yields valid UTF-8).
    throw Error("metadata of '" + printable(m.name) + "': " + printable(e.what()));
  }
}

std::string format_samples(const DataSet& d) {
  const bool ids = d.tests.size() > 1 || (!d.tests.empty() && !d.tests.front().id.empty());
  std::string out;
  out += ids ? "test_id,time_s,displacement_m,force_N" : "time_s,displacement_m,force_N";
  if (!d.tests.empty())
    for (const Column& c : d.tests.front().extra) out += "," + c.name;
  out += "\n";
  for (const Test& t : d.tests) {
    for (std::size_t i = 0; i < t.size(); ++i) {
      if (ids) out += t.id + ",";
      out += format_double(t.time_s[i]) + "," +
             format_double(i < t.displacement_m.size() ? t.displacement_m[i] : NAN) + "," +
             format_double(i < t.force_N.size() ? t.force_N[i] : NAN);
      for (const Column& c : t.extra) out += "," + format_double(i < c.values.size() ? c.values[i] : NAN);
      out += "\n";
    }
  }
  return out;
}

void validate(const DataSet& d) {
  // The writer's output must read back: check it with the reader itself (one set of rules).
  const std::string label = d.meta.name.empty() ? std::string("(data set)") : printable(d.meta.name);
  for (const Test& t : d.tests) {
    if (t.displacement_m.size() != t.size() || t.force_N.size() != t.size())
      throw Error(label + ": test '" + t.id + "': time, displacement and force have different lengths");
    if (d.tests.size() > 1 && t.id.empty()) throw Error(label + ": several tests need a test_id each");
    if (t.extra.size() != d.tests.front().extra.size())
      throw Error(label + ": test '" + t.id + "': every test needs the same extra columns");
    for (std::size_t k = 0; k < t.extra.size(); ++k)
      if (t.extra[k].name != d.tests.front().extra[k].name || t.extra[k].values.size() != t.size())
        throw Error(label + ": test '" + t.id + "': extra column '" + t.extra[k].name + "' does not match");
  }
  std::vector<Note> ignored;
  const std::string text = format_metadata(d.meta);
  parse_metadata(json::parse(text), text, label + ".json (as it would be written)", ignored);
  parse_samples(format_samples(d), label + ".csv (as it would be written)", ignored);
}

namespace {

/// Writes a validated data set: the CSV, then the metadata (a CSV without its JSON does not read as
/// a data set), each through a fresh temporary file and a rename.
fs::path write_valid(const DataSet& d, const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw Error(dir.string() + ": cannot create directory (" + ec.message() + ")");
  const fs::path csv = dir / (d.meta.name + ".csv");
  write_file_atomically(csv, format_samples(d));
  write_file_atomically(metadata_path(csv), format_metadata(d.meta));
  return csv;
}

}  // namespace

fs::path write_data_set(const DataSet& d, const fs::path& dir) {
  validate(d);
  return write_valid(d, dir);
}

fs::path write_data_set(const DataSet& d, const fs::path& dir, const std::vector<fs::path>& inputs,
                        bool overwrite) {
  validate(d);
  const fs::path csv = dir / (d.meta.name + ".csv");
  check_output_files({csv, metadata_path(csv)}, inputs, overwrite);  // both, before either is written
  return write_valid(d, dir);
}

}  // namespace tmlab::measured
