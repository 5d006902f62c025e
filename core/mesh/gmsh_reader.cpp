// Gmsh ASCII reader (formats 1, 2.x, 4.1). The file is read whole and walked line by line; every
// record is one line, and every check reports the 1-based line number of the offending line.
#include "core/mesh/gmsh_reader.hpp"

#include "core/base/error.hpp"

#include <algorithm>
#include <cassert>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

namespace tmlab {

long GmshReadInfo::skipped_total() const {
  long total = 0;
  for (const auto& entry : skipped_elements) total += entry.second;
  return total;
}

namespace {

enum class ElemKind { Keep, Skip, OtherVolume, HighOrder, Unknown };

struct ElemType {
  int num_nodes = 0;
  int dim = -1;
  ElemKind kind = ElemKind::Unknown;
  const char* name = "unknown";
};

ElemType element_type(long type) {
  switch (type) {
    case 1:
      return {2, 1, ElemKind::Skip, "2-node line"};
    case 2:
      return {3, 2, ElemKind::Keep, "3-node triangle"};
    case 3:
      return {4, 2, ElemKind::Skip, "4-node quadrangle"};
    case 4:
      return {4, 3, ElemKind::Keep, "4-node tetrahedron"};
    case 5:
      return {8, 3, ElemKind::OtherVolume, "8-node hexahedron"};
    case 6:
      return {6, 3, ElemKind::OtherVolume, "6-node prism"};
    case 7:
      return {5, 3, ElemKind::OtherVolume, "5-node pyramid"};
    case 8:
      return {3, 1, ElemKind::HighOrder, "3-node second-order line"};
    case 9:
      return {6, 2, ElemKind::HighOrder, "6-node second-order triangle"};
    case 10:
      return {9, 2, ElemKind::HighOrder, "9-node second-order quadrangle"};
    case 11:
      return {10, 3, ElemKind::HighOrder, "10-node second-order tetrahedron"};
    case 12:
      return {27, 3, ElemKind::HighOrder, "27-node second-order hexahedron"};
    case 13:
      return {18, 3, ElemKind::HighOrder, "18-node second-order prism"};
    case 14:
      return {14, 3, ElemKind::HighOrder, "14-node second-order pyramid"};
    case 15:
      return {1, 0, ElemKind::Keep, "1-node point"};
    case 16:
      return {8, 2, ElemKind::HighOrder, "8-node second-order quadrangle"};
    case 17:
      return {20, 3, ElemKind::HighOrder, "20-node second-order hexahedron"};
    case 18:
      return {15, 3, ElemKind::HighOrder, "15-node second-order prism"};
    case 19:
      return {13, 3, ElemKind::HighOrder, "13-node second-order pyramid"};
    default:
      break;
  }
  if (type >= 20 && type <= 31) return {0, -1, ElemKind::HighOrder, "higher-order element"};
  return {};
}

/// 'text' for messages, shortened, with non-printable bytes shown as '?'.
std::string quote(std::string_view text) {
  constexpr std::size_t kMax = 48;
  std::string out = "'";
  for (std::size_t i = 0; i < text.size() && i < kMax; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    out += std::isprint(c) != 0 ? static_cast<char>(c) : '?';
  }
  if (text.size() > kMax) out += "...";
  return out + "'";
}

/// Walks the file line by line, splitting each non-blank line into whitespace-separated fields.
class LineSource {
 public:
  LineSource(std::string path, std::string text) : path_(std::move(path)), text_(std::move(text)) {}

  const std::string& path() const { return path_; }

  /// Advances to the next non-blank line; false at end of file.
  bool next() {
    while (pos_ < text_.size()) {
      std::size_t end = text_.find('\n', pos_);
      if (end == std::string::npos) end = text_.size();
      std::string_view line(text_.data() + pos_, end - pos_);
      pos_ = end + 1;
      ++line_no_;
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      split(line);
      if (!fields_.empty()) {
        current_ = line;
        return true;
      }
    }
    fields_.clear();
    current_ = {};
    return false;
  }

  long line() const { return line_no_; }
  std::string_view text() const { return current_; }
  std::size_t size() const { return fields_.size(); }
  std::string_view field(std::size_t i) const { return fields_.at(i); }
  bool is_section_marker() const { return !fields_.empty() && fields_[0].front() == '$'; }

  [[noreturn]] void fail(const std::string& reason) const { throw input_error(path_, line_no_, reason); }

  /// Fails unless the current line has exactly n fields.
  void expect_fields(std::size_t n, const std::string& what) const {
    if (fields_.size() != n) {
      fail(what + ": expected " + std::to_string(n) + " fields, found " + std::to_string(fields_.size()) +
           " in " + quote(current_));
    }
  }

  /// Fails unless the current line has at least n fields.
  void expect_min_fields(std::size_t n, const std::string& what) const {
    if (fields_.size() < n) {
      fail(what + ": expected at least " + std::to_string(n) + " fields, found " +
           std::to_string(fields_.size()) + " in " + quote(current_));
    }
  }

  long long integer(std::size_t i, const std::string& what) const {
    assert(i < fields_.size());
    const std::string_view f = fields_[i];
    long long value = 0;
    const char* first = f.data();
    if (!f.empty() && f.front() == '+') ++first;
    const auto res = std::from_chars(first, f.data() + f.size(), value);
    if (res.ec == std::errc::result_out_of_range) fail(what + ": integer " + quote(f) + " is out of range");
    if (res.ec != std::errc() || res.ptr != f.data() + f.size()) {
      fail(what + ": " + quote(f) + " is not an integer");
    }
    return value;
  }

  /// Integer that must lie in [lo, hi].
  long long integer_in(std::size_t i, long long lo, long long hi, const std::string& what) const {
    const long long v = integer(i, what);
    if (v < lo || v > hi) {
      fail(what + ": " + std::to_string(v) + " is out of range [" + std::to_string(lo) + ", " +
           std::to_string(hi) + "]");
    }
    return v;
  }

  double real(std::size_t i, const std::string& what) const {
    assert(i < fields_.size());
    const std::string_view f = fields_[i];
    double value = 0.0;
    const char* first = f.data();
    if (!f.empty() && f.front() == '+') ++first;
    const auto res = std::from_chars(first, f.data() + f.size(), value);
    if (res.ec == std::errc::result_out_of_range) fail(what + ": " + quote(f) + " is out of range");
    if (res.ec != std::errc() || res.ptr != f.data() + f.size()) {
      fail(what + ": " + quote(f) + " is not a number");
    }
    if (!std::isfinite(value)) fail(what + ": " + quote(f) + " is not finite");
    return value;
  }

  /// Moves to the next line of a section body; fails at end of file or at a '$' marker.
  void record(const std::string& section, const std::string& progress) {
    if (!next()) {
      const std::string end = section == "NOD" || section == "ELM" ? "$END" + section : "$End" + section;
      fail("unexpected end of file in $" + section + " (" + progress + "; file truncated or " + end +
           " missing)");
    }
    if (is_section_marker()) {
      fail("found " + quote(current_) + " inside $" + section + " (" + progress + ")");
    }
  }

  /// Moves to the next line, which must be exactly `marker`.
  void expect_marker(const std::string& marker, const std::string& context) {
    if (!next()) fail("unexpected end of file: " + marker + " missing (" + context + ")");
    if (size() != 1 || field(0) != marker) {
      fail("expected " + marker + " (" + context + "), found " + quote(current_));
    }
  }

 private:
  void split(std::string_view line) {
    fields_.clear();
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      const std::size_t start = i;
      while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      if (i > start) fields_.push_back(line.substr(start, i - start));
    }
  }

  std::string path_;
  std::string text_;
  std::size_t pos_ = 0;
  long line_no_ = 0;
  std::string_view current_;
  std::vector<std::string_view> fields_;
};

std::string count_progress(const char* what, long long expected, long long read) {
  return "expected " + std::to_string(expected) + " " + what + ", read " + std::to_string(read);
}

struct GroupKey {
  int dim;
  int tag;
  bool operator<(const GroupKey& o) const { return dim != o.dim ? dim < o.dim : tag < o.tag; }
  bool operator==(const GroupKey& o) const { return dim == o.dim && tag == o.tag; }
};

/// Accumulates the mesh while the sections are parsed.
class MeshBuilder {
 public:
  explicit MeshBuilder(LineSource& src) : src_(src) {}

  void add_node(long long file_id, const Vec3& x) {
    if (file_id <= 0) src_.fail("node id " + std::to_string(file_id) + " is not positive");
    if (mesh_.points.size() >= static_cast<std::size_t>(std::numeric_limits<Index>::max())) {
      src_.fail("too many nodes");
    }
    const auto index = static_cast<Index>(mesh_.points.size());
    const auto inserted = id_to_index_.emplace(file_id, index);
    if (!inserted.second) {
      src_.fail("duplicate node id " + std::to_string(file_id) + " (first defined on line " +
                std::to_string(node_lines_[static_cast<std::size_t>(inserted.first->second)]) + ")");
    }
    mesh_.points.push_back(x);
    mesh_.point_file_ids.push_back(static_cast<long>(file_id));
    node_lines_.push_back(src_.line());
  }

  /// Checks an element type code; returns its description or fails with a clear reason.
  ElemType check_type(long long code) const {
    const ElemType et = element_type(code);
    const std::string id = "element type " + std::to_string(code);
    switch (et.kind) {
      case ElemKind::Keep:
      case ElemKind::Skip:
        return et;
      case ElemKind::OtherVolume:
        src_.fail("unsupported " + id + " (" + et.name + "): only 4-node tetrahedra are supported");
      case ElemKind::HighOrder:
        src_.fail(
            "unsupported " + id + " (" + et.name +
            "): mesh files hold linear elements only; re-mesh with Mesh.ElementOrder = 1 (for quadratic "
            "tets set mesh.element = p2: tmlab adds the midside nodes to the linear mesh)");
      case ElemKind::Unknown:
        break;
    }
    src_.fail("unknown " + id);
  }

  /// Adds one element. `fields` holds the file node ids starting at field index `first`.
  void add_element(long long id, long long code, const ElemType& et, std::size_t first, int physical) {
    if (et.kind == ElemKind::Skip) {
      ++skipped_[static_cast<int>(code)];
      return;
    }
    assert(et.kind == ElemKind::Keep);
    std::array<Index, 4> nodes{};
    for (int k = 0; k < et.num_nodes; ++k) {
      const long long node_id = src_.integer(first + static_cast<std::size_t>(k), "element node id");
      const auto it = id_to_index_.find(node_id);
      if (it == id_to_index_.end()) {
        src_.fail("element refers to undefined node id " + std::to_string(node_id));
      }
      nodes[static_cast<std::size_t>(k)] = it->second;
    }
    for (int a = 0; a < et.num_nodes; ++a) {
      for (int b = a + 1; b < et.num_nodes; ++b) {
        if (nodes[static_cast<std::size_t>(a)] == nodes[static_cast<std::size_t>(b)]) {
          src_.fail(std::string(et.name) + " uses node id " +
                    std::to_string(
                        mesh_.point_file_ids[static_cast<std::size_t>(nodes[static_cast<std::size_t>(a)])]) +
                    " twice");
        }
      }
    }
    if (physical < 0) src_.fail("negative physical tag " + std::to_string(physical));
    if (physical != 0) used_groups_.push_back({et.dim, physical});
    if (et.dim == 3) {
      mesh_.tets.push_back({nodes[0], nodes[1], nodes[2], nodes[3]});
      mesh_.tet_physical.push_back(physical);
      mesh_.tet_file_ids.push_back(static_cast<long>(id));
      tet_lines_.push_back(src_.line());
    } else if (et.dim == 2) {
      mesh_.triangles.push_back({nodes[0], nodes[1], nodes[2]});
      mesh_.triangle_physical.push_back(physical);
    } else {
      assert(et.dim == 0);
      mesh_.vertices.push_back(nodes[0]);
      mesh_.vertex_physical.push_back(physical);
    }
  }

  void add_physical_name(int dim, int tag, std::string name) {
    const GroupKey key{dim, tag};
    const auto inserted = named_.emplace(key, std::make_pair(std::move(name), src_.line()));
    if (!inserted.second) {
      src_.fail("physical group (dim " + std::to_string(dim) + ", tag " + std::to_string(tag) +
                ") named twice (first on line " + std::to_string(inserted.first->second.second) + ")");
    }
  }

  /// Final checks (duplicate tets) and group assembly.
  Mesh finish(GmshReadInfo* info) {
    check_duplicate_tets();
    std::map<GroupKey, std::string> groups;
    for (const auto& entry : named_) {
      if (entry.first.dim == 0 || entry.first.dim == 2 || entry.first.dim == 3) {
        groups[entry.first] = entry.second.first;
      }
    }
    for (const GroupKey& key : used_groups_) groups.emplace(key, std::string());
    for (const auto& entry : groups) mesh_.groups.push_back({entry.first.dim, entry.first.tag, entry.second});
    mesh_.source = src_.path();
    if (info != nullptr) info->skipped_elements = skipped_;
    return std::move(mesh_);
  }

  Index num_nodes() const { return static_cast<Index>(mesh_.points.size()); }

 private:
  void check_duplicate_tets() const {
    std::vector<std::pair<Tet, std::size_t>> sorted;
    sorted.reserve(mesh_.tets.size());
    for (std::size_t t = 0; t < mesh_.tets.size(); ++t) {
      Tet key = mesh_.tets[t];
      std::sort(key.begin(), key.end());
      sorted.emplace_back(key, t);
    }
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t k = 1; k < sorted.size(); ++k) {
      if (sorted[k].first == sorted[k - 1].first) {
        const std::size_t a = std::min(sorted[k].second, sorted[k - 1].second);
        const std::size_t b = std::max(sorted[k].second, sorted[k - 1].second);
        throw input_error(
            src_.path(), tet_lines_[b],
            "duplicate tetrahedron: same nodes as the tetrahedron on line " + std::to_string(tet_lines_[a]));
      }
    }
  }

  LineSource& src_;
  Mesh mesh_;
  std::unordered_map<long long, Index> id_to_index_;
  std::vector<long> node_lines_;
  std::vector<long> tet_lines_;
  std::map<int, long> skipped_;
  std::map<GroupKey, std::pair<std::string, long>> named_;
  std::vector<GroupKey> used_groups_;
};

constexpr long long kMaxCount = std::numeric_limits<Index>::max();

// ---- counted sections (formats 1 and 2.x) ----------------------------------------------------
// $NOD/$ELM (format 1), $Nodes/$Elements (2.x) and $PhysicalNames (2.x, 4.1) share one layout: a
// line with the number of records, one record per line, the end marker. read_counted_section()
// reads that layout once for all of them; the per-record readers below differ only where the
// formats do (the element line).

/// Names used in the messages of one counted section.
struct CountedSection {
  const char* name;     ///< section name without '$': "NOD", "Nodes", ...
  const char* end;      ///< its end marker: "$ENDNOD", "$EndNodes", ...
  const char* records;  ///< what one record is, plural: "nodes"
  const char* count;    ///< what the count line holds: "number of nodes"
};

constexpr CountedSection kV1Nodes{"NOD", "$ENDNOD", "nodes", "number of nodes"};
constexpr CountedSection kV1Elements{"ELM", "$ENDELM", "elements", "number of elements"};
constexpr CountedSection kV2Nodes{"Nodes", "$EndNodes", "nodes", "number of nodes"};
constexpr CountedSection kV2Elements{"Elements", "$EndElements", "elements", "number of elements"};
constexpr CountedSection kPhysicalNames{"PhysicalNames", "$EndPhysicalNames", "names",
                                        "number of physical names"};

/// Reads the count line, calls `read_record()` with each record line current, then expects the end
/// marker. A short section, a '$' line among the records and a missing end marker each fail with
/// the section's name and how many records were read.
template <class ReadRecord>
void read_counted_section(LineSource& src, const CountedSection& s, ReadRecord read_record) {
  src.record(s.name, std::string("expected the number of ") + s.records);
  src.expect_fields(1, std::string("$") + s.name + " header");
  const long long n = src.integer_in(0, 0, kMaxCount, s.count);
  for (long long k = 0; k < n; ++k) {
    src.record(s.name, count_progress(s.records, n, k));
    read_record();
  }
  src.expect_marker(s.end, "after " + std::to_string(n) + " " + s.records);
}

/// A node line of format 1 or 2.x: "id x y z".
void read_node_line(LineSource& src, MeshBuilder& mb) {
  src.expect_fields(4, "node");
  const long long id = src.integer(0, "node id");
  mb.add_node(id, Vec3(src.real(1, "node x"), src.real(2, "node y"), src.real(3, "node z")));
}

/// A format 1 element line: "id type reg-phys reg-elem number-of-nodes node ...".
void read_v1_element_line(LineSource& src, MeshBuilder& mb) {
  src.expect_min_fields(5, "element");
  const long long id = src.integer(0, "element id");
  const long long code = src.integer(1, "element type");
  const ElemType et = mb.check_type(code);
  const long long phys = src.integer_in(2, 0, std::numeric_limits<int>::max(), "physical tag");
  src.integer(3, "elementary tag");
  const long long nn = src.integer(4, "number of element nodes");
  if (nn != et.num_nodes) {
    src.fail("element of type " + std::to_string(code) + " (" + et.name + ") declares " + std::to_string(nn) +
             " nodes, expected " + std::to_string(et.num_nodes));
  }
  src.expect_fields(5 + static_cast<std::size_t>(et.num_nodes), "element");
  mb.add_element(id, code, et, 5, static_cast<int>(phys));
}

/// A format 2.x element line: "id type number-of-tags tag ... node ..."; the first tag is the
/// physical group.
void read_v2_element_line(LineSource& src, MeshBuilder& mb) {
  src.expect_min_fields(3, "element");
  const long long id = src.integer(0, "element id");
  const long long code = src.integer(1, "element type");
  const ElemType et = mb.check_type(code);
  const long long ntags = src.integer_in(2, 0, 64, "number of element tags");
  const std::size_t first = 3 + static_cast<std::size_t>(ntags);
  src.expect_fields(first + static_cast<std::size_t>(et.num_nodes),
                    std::string("element (") + et.name + ", " + std::to_string(ntags) + " tags)");
  long long phys = 0;
  if (ntags >= 1) phys = src.integer_in(3, 0, std::numeric_limits<int>::max(), "physical tag");
  for (std::size_t t = 4; t < first; ++t) src.integer(t, "element tag");
  mb.add_element(id, code, et, first, static_cast<int>(phys));
}

/// A $PhysicalNames line: "dim tag "name"" (an unquoted single-word name is accepted).
void read_physical_name_line(LineSource& src, MeshBuilder& mb) {
  src.expect_min_fields(3, "physical name");
  const int dim = static_cast<int>(src.integer_in(0, 0, 3, "physical name dimension"));
  const int tag = static_cast<int>(src.integer_in(1, 1, std::numeric_limits<int>::max(), "physical tag"));
  const std::string_view line = src.text();
  const std::size_t open = line.find('"');
  std::string name;
  if (open == std::string_view::npos) {
    if (src.size() != 3) src.fail("physical name must be quoted: " + quote(line));
    name = std::string(src.field(2));
  } else {
    const std::size_t close = line.rfind('"');
    if (close == open) src.fail("unterminated quoted physical name in " + quote(line));
    name = std::string(line.substr(open + 1, close - open - 1));
  }
  mb.add_physical_name(dim, tag, std::move(name));
}

/// Skips an unknown section up to its $End marker.
void skip_section(LineSource& src, const std::string& name) {
  const long start = src.line();
  const std::string end = "$End" + name;
  while (src.next()) {
    if (src.size() == 1 && src.field(0) == end) return;
  }
  src.fail("unexpected end of file: " + end + " missing (section $" + name + " opened on line " +
           std::to_string(start) + ")");
}

// ---- format 4.1 ------------------------------------------------------------------------------

using EntityMap = std::map<GroupKey, std::vector<int>>;  // (dim, entity tag) -> physical tags

void read_v4_entities(LineSource& src, EntityMap& entities) {
  src.record("Entities", "expected the numbers of points, curves, surfaces, volumes");
  src.expect_fields(4, "$Entities header");
  std::array<long long, 4> counts{};
  for (std::size_t d = 0; d < 4; ++d) counts[d] = src.integer_in(d, 0, kMaxCount, "number of entities");
  for (int dim = 0; dim < 4; ++dim) {
    const long long n = counts[static_cast<std::size_t>(dim)];
    for (long long k = 0; k < n; ++k) {
      src.record("Entities", count_progress(("entities of dimension " + std::to_string(dim)).c_str(), n, k));
      const std::size_t nphys_at = dim == 0 ? 4 : 7;
      src.expect_min_fields(nphys_at + 1, "entity");
      const int tag = static_cast<int>(src.integer_in(0, 1, std::numeric_limits<int>::max(), "entity tag"));
      for (std::size_t c = 1; c < nphys_at; ++c) src.real(c, "entity coordinate");
      const long long nphys = src.integer_in(nphys_at, 0, 1 << 20, "number of physical tags");
      std::vector<int> phys;
      std::size_t expected = nphys_at + 1 + static_cast<std::size_t>(nphys);
      if (dim > 0) {
        src.expect_min_fields(expected + 1, "entity");
        const long long nbound = src.integer_in(expected, 0, 1 << 20, "number of bounding entities");
        expected += 1 + static_cast<std::size_t>(nbound);
      }
      src.expect_fields(expected, "entity of dimension " + std::to_string(dim));
      for (long long p = 0; p < nphys; ++p) {
        // Gmsh writes negative physical tags for reversed orientation; the group is |tag|.
        const long long v = src.integer(nphys_at + 1 + static_cast<std::size_t>(p), "physical tag");
        if (v == 0 || v > std::numeric_limits<int>::max() || v < -std::numeric_limits<int>::max()) {
          src.fail("invalid physical tag " + std::to_string(v));
        }
        phys.push_back(static_cast<int>(v < 0 ? -v : v));
      }
      if (!entities.emplace(GroupKey{dim, tag}, std::move(phys)).second) {
        src.fail("duplicate entity (dim " + std::to_string(dim) + ", tag " + std::to_string(tag) + ")");
      }
    }
  }
  src.expect_marker("$EndEntities", "after the declared entities");
}

/// Names used in the messages of a 4.1 $Nodes or $Elements section.
struct BlockSection {
  const char* name;  ///< "Nodes"
  const char* one;   ///< "node"
  const char* many;  ///< "nodes"
  const char* tag;   ///< the header's spelling: "Node" as in numNodes, minNodeTag
};

constexpr BlockSection kV4Nodes{"Nodes", "node", "nodes", "Node"};
constexpr BlockSection kV4Elements{"Elements", "element", "elements", "Element"};

/// Counts of a 4.1 block section, from its header and as its blocks are read.
struct BlockCounts {
  long header_line = 0;
  long long blocks = 0;    ///< numEntityBlocks
  long long declared = 0;  ///< numNodes / numElements
  long long held = 0;      ///< sum of the blocks read so far
};

/// Reads "numEntityBlocks numX minXTag maxXTag".
BlockCounts read_block_header(LineSource& src, const BlockSection& s) {
  const std::string tag = s.tag;
  src.record(s.name,
             "expected numEntityBlocks num" + std::string(s.name) + " min" + tag + "Tag max" + tag + "Tag");
  src.expect_fields(4, std::string("$") + s.name + " header");
  BlockCounts c;
  c.header_line = src.line();
  c.blocks = src.integer_in(0, 0, kMaxCount, "number of " + std::string(s.one) + " blocks");
  c.declared = src.integer_in(1, 0, kMaxCount, std::string("number of ") + s.many);
  src.integer(2, "minimum " + std::string(s.one) + " tag");
  src.integer(3, "maximum " + std::string(s.one) + " tag");
  return c;
}

/// Adds a block of n entries; fails when the blocks hold more than the header declared.
void add_block(LineSource& src, const BlockSection& s, BlockCounts& c, long long n) {
  if (c.held + n > c.declared) {
    src.fail(std::string(s.one) + " blocks hold more " + s.many + " than the " + std::to_string(c.declared) +
             " declared on line " + std::to_string(c.header_line));
  }
  c.held += n;
}

/// Expects the end marker after the last block, then that the blocks held what the header said.
void finish_block_section(LineSource& src, const BlockSection& s, const BlockCounts& c) {
  const std::string end = std::string("$End") + s.name;
  if (!src.next()) src.fail("unexpected end of file: " + end + " missing");
  if (src.size() != 1 || src.field(0) != end) {
    src.fail("expected " + end + " after " + std::to_string(c.blocks) + " " + s.one + " blocks, found " +
             quote(src.text()));
  }
  if (c.held != c.declared) {
    throw input_error(src.path(), c.header_line,
                      std::string("$") + s.name + " header declares " + std::to_string(c.declared) + " " +
                          s.many + ", but the blocks hold " + std::to_string(c.held));
  }
}

void read_v4_nodes(LineSource& src, MeshBuilder& mb) {
  BlockCounts counts = read_block_header(src, kV4Nodes);
  std::vector<long long> tags;
  for (long long b = 0; b < counts.blocks; ++b) {
    src.record("Nodes", count_progress("node blocks", counts.blocks, b));
    src.expect_fields(4, "node block header (entityDim entityTag parametric numNodesInBlock)");
    const long long dim = src.integer_in(0, 0, 3, "entity dimension");
    src.integer(1, "entity tag");
    const long long parametric = src.integer_in(2, 0, 1, "parametric flag");
    const long long n = src.integer_in(3, 0, kMaxCount, "number of nodes in block");
    add_block(src, kV4Nodes, counts, n);
    tags.clear();
    for (long long k = 0; k < n; ++k) {
      src.record("Nodes", count_progress("node tags in block", n, k));
      src.expect_fields(1, "node tag");
      tags.push_back(src.integer(0, "node tag"));
    }
    const std::size_t ncoord = 3 + (parametric != 0 ? static_cast<std::size_t>(dim) : 0);
    for (long long k = 0; k < n; ++k) {
      src.record("Nodes", count_progress("node coordinates in block", n, k));
      src.expect_fields(ncoord, "node coordinates");
      mb.add_node(tags[static_cast<std::size_t>(k)],
                  Vec3(src.real(0, "node x"), src.real(1, "node y"), src.real(2, "node z")));
      for (std::size_t c = 3; c < ncoord; ++c) src.real(c, "node parametric coordinate");
    }
  }
  finish_block_section(src, kV4Nodes, counts);
}

void read_v4_elements(LineSource& src, MeshBuilder& mb, const EntityMap& entities, bool have_entities) {
  BlockCounts counts = read_block_header(src, kV4Elements);
  const std::vector<int> no_physical;
  for (long long b = 0; b < counts.blocks; ++b) {
    src.record("Elements", count_progress("element blocks", counts.blocks, b));
    src.expect_fields(4, "element block header (entityDim entityTag elementType numElementsInBlock)");
    const int dim = static_cast<int>(src.integer_in(0, 0, 3, "entity dimension"));
    const int tag = static_cast<int>(src.integer_in(1, 1, std::numeric_limits<int>::max(), "entity tag"));
    const long long code = src.integer(2, "element type");
    const ElemType et = mb.check_type(code);
    if (et.dim != dim) {
      src.fail("element type " + std::to_string(code) + " (" + et.name + ") in a block of dimension " +
               std::to_string(dim));
    }
    const long long n = src.integer_in(3, 0, kMaxCount, "number of elements in block");
    add_block(src, kV4Elements, counts, n);
    const std::vector<int>* phys = &no_physical;
    if (have_entities) {
      const auto it = entities.find(GroupKey{dim, tag});
      if (it == entities.end()) {
        src.fail("element block refers to entity (dim " + std::to_string(dim) + ", tag " +
                 std::to_string(tag) + ") not listed in $Entities");
      }
      phys = &it->second;
    }
    for (long long k = 0; k < n; ++k) {
      src.record("Elements", count_progress("elements in block", n, k));
      src.expect_fields(1 + static_cast<std::size_t>(et.num_nodes), std::string("element (") + et.name + ")");
      const long long id = src.integer(0, "element tag");
      if (phys->empty()) {
        mb.add_element(id, code, et, 1, 0);
      } else if (dim == 3) {
        mb.add_element(id, code, et, 1, phys->front());
      } else {
        for (const int p : *phys) mb.add_element(id, code, et, 1, p);
      }
    }
  }
  finish_block_section(src, kV4Elements, counts);
}

enum class Format { V1, V2, V41 };

/// The node and element sections of a format (4.1 keeps the 2.x names, with another layout).
const CountedSection& nodes_section(Format f) { return f == Format::V1 ? kV1Nodes : kV2Nodes; }
const CountedSection& elements_section(Format f) { return f == Format::V1 ? kV1Elements : kV2Elements; }

/// Parses the $MeshFormat body and its end marker; returns the format.
Format read_mesh_format(LineSource& src, std::string& version) {
  src.record("MeshFormat", "expected 'version file-type data-size'");
  src.expect_min_fields(3, "$MeshFormat");
  version = std::string(src.field(0));
  const long long file_type = src.integer(1, "file type");
  if (file_type == 1) src.fail("binary .msh not supported, re-save as ASCII (Mesh.Binary = 0)");
  if (file_type != 0) src.fail("unknown file type " + std::to_string(file_type) + " (0 = ASCII)");
  const double v = src.real(0, "format version");
  Format format = Format::V2;
  if (v >= 2.0 && v < 3.0) {
    format = Format::V2;
  } else if (version == "4.1") {
    format = Format::V41;
  } else {
    src.fail("unsupported Gmsh format version " + quote(version) +
             " (supported: 1, 2.x, 4.1); re-save with "
             "Mesh.MshFileVersion = 2.2 or 4.1");
  }
  src.expect_marker("$EndMeshFormat", "after the format line");
  return format;
}

Mesh parse(LineSource& src, GmshReadInfo* info) {
  MeshBuilder mb(src);
  std::string version;
  bool have_format = false;
  bool have_nodes = false;
  bool have_elements = false;
  bool have_entities = false;
  Format format = Format::V2;
  EntityMap entities;

  if (!src.next()) src.fail("empty file, not a Gmsh mesh");
  bool first = true;
  do {
    if (!src.is_section_marker()) {
      src.fail(first ? "not a Gmsh mesh file: expected $MeshFormat or $NOD, found " + quote(src.text())
                     : "expected a section marker ($Name), found " + quote(src.text()));
    }
    const std::string name(src.field(0).substr(1));
    if (src.size() != 1) src.fail("unexpected text after section marker " + quote(src.text()));
    if (first) {
      if (name == "MeshFormat") {
        format = read_mesh_format(src, version);
        have_format = true;
      } else if (name == "NOD" || name == "ELM") {
        format = Format::V1;
        version = "1";
      } else {
        src.fail("not a Gmsh mesh file: expected $MeshFormat or $NOD, found " + quote(src.text()));
      }
      first = false;
      if (have_format) continue;
    } else if (name == "MeshFormat") {
      src.fail("second $MeshFormat section");
    }

    // Formats 1 and 2.x read nodes and elements with the same counted-section reader; only the
    // section names and the element line differ. Format 4.1 has blocks per entity instead.
    const CountedSection& nodes = nodes_section(format);
    const CountedSection& elements = elements_section(format);
    if (name == nodes.name) {
      if (have_nodes) src.fail("second $" + name + " section");
      if (format == Format::V41) {
        read_v4_nodes(src, mb);
      } else {
        read_counted_section(src, nodes, [&] { read_node_line(src, mb); });
      }
      have_nodes = true;
    } else if (name == elements.name) {
      if (!have_nodes) src.fail("$" + name + " before $" + nodes.name);
      if (have_elements) src.fail("second $" + name + " section");
      if (format == Format::V41) {
        read_v4_elements(src, mb, entities, have_entities);
      } else {
        const auto read_line = format == Format::V1 ? read_v1_element_line : read_v2_element_line;
        read_counted_section(src, elements, [&] { read_line(src, mb); });
      }
      have_elements = true;
    } else if (format == Format::V1) {
      src.fail("unexpected section $" + name + " in a format 1 file (expected $NOD or $ELM)");
    } else if (name == "PhysicalNames") {
      read_counted_section(src, kPhysicalNames, [&] { read_physical_name_line(src, mb); });
    } else if (name == "Entities" && format == Format::V41) {
      if (have_entities) src.fail("second $Entities section");
      if (have_elements) src.fail("$Entities after $Elements");
      read_v4_entities(src, entities);
      have_entities = true;
    } else if (name.rfind("End", 0) == 0) {
      src.fail("unmatched section end marker " + quote(src.text()));
    } else {
      skip_section(src, name);  // $NodeData, $Periodic, $Comments, ...
    }
  } while (src.next());

  if (!have_nodes) src.fail(std::string("no $") + nodes_section(format).name + " section (file truncated?)");
  if (!have_elements)
    src.fail(std::string("no $") + elements_section(format).name + " section (file truncated?)");
  if (info != nullptr) info->format_version = version;
  return mb.finish(info);
}

}  // namespace

Mesh read_gmsh(const std::string& path, GmshReadInfo* info) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw input_error(path, 0, "cannot open mesh file");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw input_error(path, 0, "error while reading mesh file");
  std::string text = buffer.str();

  LineSource src(path, std::move(text));
  GmshReadInfo local;
  Mesh mesh = parse(src, info != nullptr ? info : &local);
  return mesh;
}

Mesh read_mesh(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  const std::size_t dot = path.find_last_of('.');
  std::string ext;
  if (dot != std::string::npos && (slash == std::string::npos || dot > slash)) ext = path.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".msh") return read_gmsh(path);
  throw input_error(path, 0,
                    "unsupported mesh file extension " + (ext.empty() ? std::string("(none)") : quote(ext)) +
                        " (supported: .msh, Gmsh ASCII format 1, 2.x or 4.1)");
}

}  // namespace tmlab
