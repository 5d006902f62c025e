// Tests of read_gmsh()/read_mesh(): every repository mesh in each Gmsh format (meshes/README.md), a
// write/read round trip, and a table of malformed files that must each fail with "file:line: reason".
#include "core/base/error.hpp"
#include "core/mesh/gmsh_reader.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_quality.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace tmlab {
namespace {

namespace fs = std::filesystem;

/// A mesh of the repository's meshes/ folder (the SOFA and gmsh-made inputs are in meshes/sources/).
std::string repo_mesh(const std::string& rel) { return std::string(TMLAB_SOURCE_DIR) + "/meshes/" + rel; }

/// Writes `content` to a fresh file in the test temp directory and returns its path.
std::string write_temp(const std::string& name, const std::string& content) {
  const fs::path dir = fs::path(testing::TempDir()) / "tmlab_gmsh_reader";
  fs::create_directories(dir);
  const std::string path = (dir / name).string();
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << content;
  return path;
}

struct RepoMeshCase {
  const char* file;
  const char* version;
  Index nodes;
  Index tets;
  std::size_t triangles;
  std::size_t points;
  long skipped;
};

class RepoMeshFiles : public testing::TestWithParam<RepoMeshCase> {};

TEST_P(RepoMeshFiles, CountsMatchMeshesReadme) {
  const RepoMeshCase& c = GetParam();
  const std::string path = repo_mesh(c.file);
  ASSERT_TRUE(fs::exists(path)) << "missing " << path;
  GmshReadInfo info;
  const Mesh mesh = read_gmsh(path, &info);
  EXPECT_EQ(info.format_version, c.version);
  EXPECT_EQ(mesh.num_points(), c.nodes);
  EXPECT_EQ(mesh.num_tets(), c.tets);
  EXPECT_EQ(mesh.triangles.size(), c.triangles);
  EXPECT_EQ(mesh.vertices.size(), c.points);
  EXPECT_EQ(info.skipped_total(), c.skipped);
  EXPECT_EQ(mesh.point_file_ids.size(), mesh.points.size());
  EXPECT_EQ(mesh.tet_physical.size(), mesh.tets.size());
  EXPECT_EQ(mesh.triangle_physical.size(), mesh.triangles.size());
  EXPECT_EQ(mesh.source, path);
  const MeshReport report = analyse_mesh(mesh);
  EXPECT_TRUE(report.inverted.empty()) << c.file;  // meshes/README.md: no mesh has an inverted tet
  EXPECT_TRUE(report.degenerate.empty()) << c.file;
  EXPECT_GT(report.q_min, 0.05) << c.file;
  EXPECT_EQ(report.num_unused_points, 0) << c.file;
}

INSTANTIATE_TEST_SUITE_P(
    AllFormats, RepoMeshFiles,
    testing::Values(RepoMeshCase{"sources/sofa/liver.msh", "1", 181, 596, 0, 0, 0},
                    RepoMeshCase{"sources/sofa/liver2.msh", "1", 507, 1493, 860, 0, 71},
                    RepoMeshCase{"sources/sofa/cylinder.msh", "1", 510, 2430, 0, 0, 0},
                    RepoMeshCase{"sources/sofa/cylinder_8x30x6.msh", "1", 1446, 6750, 0, 0, 0},
                    RepoMeshCase{"sources/sofa/truthcylinder1.msh", "1", 642, 2524, 706, 0, 72},
                    RepoMeshCase{"sources/sofa/cube_low_res.msh", "2.2", 26, 44, 0, 0, 0},
                    RepoMeshCase{"sources/sofa/msh4_cube.msh", "4.1", 14, 24, 24, 8, 12},
                    RepoMeshCase{"block_indentation.msh", "2.2", 759, 3120, 572, 0, 0},
                    RepoMeshCase{"cylinder_sample.msh", "2.2", 1142, 4789, 1376, 0, 0},
                    RepoMeshCase{"sources/generated/liver2_remesh_740n_2704t.msh", "2.2", 740, 2704, 0, 0,
                                 0}));

TEST(GmshReader, Liver2KeepsNonContiguousFileIds) {
  const std::string path = repo_mesh("sources/sofa/liver2.msh");
  ASSERT_TRUE(fs::exists(path)) << "missing " << path;
  const Mesh mesh = read_gmsh(path);
  ASSERT_EQ(mesh.num_points(), 507);
  EXPECT_EQ(mesh.point_file_ids.front(), 2);
  EXPECT_EQ(*std::max_element(mesh.point_file_ids.begin(), mesh.point_file_ids.end()), 1393);
  for (const Tet& t : mesh.tets) {
    for (const Index n : t) {
      ASSERT_GE(n, 0);
      ASSERT_LT(n, mesh.num_points());
    }
  }
}

TEST(GmshReader, BlockIndentationPhysicalGroups) {
  const std::string path = repo_mesh("block_indentation.msh");
  ASSERT_TRUE(fs::exists(path)) << "missing " << path;
  const Mesh mesh = read_gmsh(path);
  ASSERT_EQ(mesh.groups.size(), 3u);
  EXPECT_EQ(mesh.groups[0].dim, 2);
  EXPECT_EQ(mesh.groups[0].tag, 2);
  EXPECT_EQ(mesh.groups[0].name, "bottom_fixed");
  EXPECT_EQ(mesh.groups[1].dim, 2);
  EXPECT_EQ(mesh.groups[1].tag, 3);
  EXPECT_EQ(mesh.groups[1].name, "top");
  EXPECT_EQ(mesh.groups[2].dim, 3);
  EXPECT_EQ(mesh.groups[2].tag, 1);
  EXPECT_EQ(mesh.groups[2].name, "tissue");
  const long bottom = std::count(mesh.triangle_physical.begin(), mesh.triangle_physical.end(), 2);
  const long top = std::count(mesh.triangle_physical.begin(), mesh.triangle_physical.end(), 3);
  EXPECT_GT(bottom, 0);
  EXPECT_GT(top, 0);
  EXPECT_EQ(static_cast<std::size_t>(bottom + top), mesh.triangles.size());
  EXPECT_TRUE(std::all_of(mesh.tet_physical.begin(), mesh.tet_physical.end(), [](int p) { return p == 1; }));
}

TEST(GmshReader, Format41PhysicalTagsFromEntities) {
  const std::string text =
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
      "$PhysicalNames\n2\n2 5 \"top face\"\n3 9 \"solid\"\n$EndPhysicalNames\n"
      "$Entities\n0 0 1 1\n"
      "1 0 0 0 1 1 0 1 5 0\n"
      "1 0 0 0 1 1 1 1 9 1 1\n"
      "$EndEntities\n"
      "$Nodes\n2 4 10 40\n"
      "2 1 0 3\n10\n20\n30\n0 0 0\n1 0 0\n0 1 0\n"
      "3 1 0 1\n40\n0 0 1\n"
      "$EndNodes\n"
      "$Elements\n3 3 1 3\n"
      "2 1 2 1\n1 10 30 20\n"
      "3 1 4 1\n2 10 20 30 40\n"
      "1 1 1 1\n3 10 20\n"  // a line in a curve entity that $Entities does not list -> error
      "$EndElements\n";
  // Curve entity 1 is not declared (0 curves): must be rejected with the block header line.
  const std::string bad = write_temp("v41_missing_entity.msh", text);
  try {
    read_gmsh(bad);
    FAIL() << "expected tmlab::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(bad + ":33:"), std::string::npos) << e.what();
  }
  std::string good_text = text;
  good_text.replace(good_text.find("3 3 1 3\n"), 8, "2 2 1 2\n");
  good_text.erase(good_text.find("1 1 1 1\n3 10 20\n"), 16);
  GmshReadInfo info;
  const Mesh mesh = read_gmsh(write_temp("v41_good.msh", good_text), &info);
  EXPECT_EQ(info.format_version, "4.1");
  ASSERT_EQ(mesh.num_points(), 4);
  EXPECT_EQ(mesh.point_file_ids, (std::vector<long>{10, 20, 30, 40}));
  ASSERT_EQ(mesh.num_tets(), 1);
  EXPECT_EQ(mesh.tets[0], (Tet{0, 1, 2, 3}));
  EXPECT_EQ(mesh.tet_physical[0], 9);
  EXPECT_EQ(mesh.tet_file_ids, (std::vector<long>{2}));  // the element tag, for messages
  EXPECT_EQ(mesh.tet_name(0), "tetrahedron 0 (Gmsh element 2)");
  ASSERT_EQ(mesh.triangles.size(), 1u);
  EXPECT_EQ(mesh.triangle_physical[0], 5);
  ASSERT_EQ(mesh.groups.size(), 2u);
  EXPECT_EQ(mesh.groups[0].name, "top face");
  EXPECT_EQ(mesh.groups[1].name, "solid");
}

TEST(GmshReader, WriteReadRoundTripIsExact) {
  const std::string path = repo_mesh("block_indentation.msh");
  ASSERT_TRUE(fs::exists(path)) << "missing " << path;
  const Mesh a = read_gmsh(path);
  const std::string out = write_temp("roundtrip.msh", "");
  write_gmsh22(a, out);
  const Mesh b = read_gmsh(out);
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) EXPECT_EQ(a.points[i], b.points[i]) << i;
  EXPECT_EQ(a.tets, b.tets);
  EXPECT_EQ(a.tet_physical, b.tet_physical);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.triangle_physical, b.triangle_physical);
  ASSERT_EQ(a.groups.size(), b.groups.size());
  for (std::size_t g = 0; g < a.groups.size(); ++g) {
    EXPECT_EQ(a.groups[g].dim, b.groups[g].dim);
    EXPECT_EQ(a.groups[g].tag, b.groups[g].tag);
    EXPECT_EQ(a.groups[g].name, b.groups[g].name);
  }
}

TEST(GmshReader, ReadMeshDispatchesOnExtension) {
  const std::string path = repo_mesh("sources/sofa/liver.msh");
  ASSERT_TRUE(fs::exists(path)) << "missing " << path;
  EXPECT_EQ(read_mesh(path).num_tets(), 596);
  const std::string upper = write_temp("CUBE.MSH",
                                       "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n0\n$EndNodes\n"
                                       "$Elements\n0\n$EndElements\n");
  EXPECT_EQ(read_mesh(upper).num_points(), 0);
  try {
    read_mesh("/nonexistent/liver.vtk");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("liver.vtk"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("unsupported mesh file extension"), std::string::npos);
  }
  EXPECT_THROW(read_mesh("/nonexistent/no_extension"), Error);
  try {
    read_mesh("/nonexistent/missing.msh");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/missing.msh: cannot open"), std::string::npos)
        << e.what();
  }
}

TEST(GmshReader, SkipsUnknownSectionsAndCrLf) {
  const std::string text =
      "$MeshFormat\r\n2.2 0 8\r\n$EndMeshFormat\r\n$Comments\r\nanything $here\r\n$EndComments\r\n"
      "$Nodes\r\n4\r\n1 0 0 0\r\n2 1 0 0\r\n3 0 1 0\r\n4 0 0 1\r\n$EndNodes\r\n"
      "$Elements\r\n2\r\n1 1 2 0 1 1 2\r\n2 4 0 1 2 3 4\r\n$EndElements\r\n\r\n";
  GmshReadInfo info;
  const Mesh mesh = read_gmsh(write_temp("crlf.msh", text), &info);
  EXPECT_EQ(mesh.num_tets(), 1);
  EXPECT_EQ(mesh.tet_physical[0], 0);
  EXPECT_TRUE(mesh.groups.empty());
  EXPECT_EQ(info.skipped_elements.at(1), 1);
}

TEST(GmshReader, EveryTruncationIsAnError) {
  // Cutting a file anywhere before its final $EndElements must give tmlab::Error, never a crash or
  // a silently shorter mesh.
  for (const char* rel : {"sources/sofa/msh4_cube.msh", "sources/sofa/cube_low_res.msh"}) {
    const std::string path = repo_mesh(rel);
    ASSERT_TRUE(fs::exists(path)) << "missing " << path;
    std::ifstream in(path, std::ios::binary);
    const std::string full((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t complete = full.rfind("$EndElements") + std::string("$EndElements").size();
    // Cut points: before and in the middle of every line (cheaper than every byte, same coverage of
    // section states: a cut mid-line leaves a short or half-written record).
    std::vector<std::size_t> cuts;
    for (std::size_t start = 0; start < complete; start = full.find('\n', start) + 1) {
      cuts.push_back(start);
      const std::size_t end = std::min(full.find('\n', start), complete);
      if (end > start + 1) cuts.push_back(start + (end - start) / 2);
      if (end >= complete) break;
    }
    cuts.push_back(complete - 1);
    for (const std::size_t len : cuts) {
      const std::string cut = write_temp("truncated.msh", full.substr(0, len));
      EXPECT_THROW(read_gmsh(cut), Error) << rel << " cut at byte " << len;
    }
    EXPECT_NO_THROW(read_gmsh(write_temp("complete.msh", full.substr(0, complete))));
  }
}

// ---- malformed inputs -----------------------------------------------------------------------

const char* const kGood22 =
    "$MeshFormat\n"        // 1
    "2.2 0 8\n"            // 2
    "$EndMeshFormat\n"     // 3
    "$Nodes\n"             // 4
    "4\n"                  // 5
    "1 0 0 0\n"            // 6
    "2 1 0 0\n"            // 7
    "3 0 1 0\n"            // 8
    "4 0 0 1\n"            // 9
    "$EndNodes\n"          // 10
    "$Elements\n"          // 11
    "1\n"                  // 12
    "1 4 2 1 1 1 2 3 4\n"  // 13
    "$EndElements\n";      // 14

const char* const kGood1 =
    "$NOD\n"               // 1
    "4\n"                  // 2
    "1 0 0 0\n"            // 3
    "2 1 0 0\n"            // 4
    "3 0 1 0\n"            // 5
    "4 0 0 1\n"            // 6
    "$ENDNOD\n"            // 7
    "$ELM\n"               // 8
    "1\n"                  // 9
    "1 4 1 1 4 1 2 3 4\n"  // 10
    "$ENDELM\n";           // 11

/// Replaces line `line` (1-based) of `text` by `with` (no newline; "" removes the line).
std::string replace_line(const std::string& text, int line, const std::string& with) {
  std::vector<std::string> lines;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t end = text.find('\n', pos);
    lines.push_back(text.substr(pos, end - pos));
    pos = end + 1;
  }
  std::string out;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (static_cast<int>(i) + 1 == line) {
      if (!with.empty()) out += with + "\n";
    } else {
      out += lines[i] + "\n";
    }
  }
  return out;
}

/// The first `n` lines of `text`.
std::string head(const std::string& text, int n) {
  std::size_t pos = 0;
  for (int i = 0; i < n; ++i) pos = text.find('\n', pos) + 1;
  return text.substr(0, pos);
}

struct BadCase {
  const char* name;
  std::string content;
  long line;           // expected line in the message (0: no line)
  const char* reason;  // expected substring
};

class MalformedGmsh : public testing::TestWithParam<BadCase> {};

TEST_P(MalformedGmsh, ThrowsWithFileLineAndReason) {
  const BadCase& c = GetParam();
  const std::string path = write_temp(std::string(c.name) + ".msh", c.content);
  try {
    const Mesh mesh = read_gmsh(path);
    FAIL() << c.name << ": no error, read " << mesh.num_points() << " points";
  } catch (const Error& e) {
    const std::string msg = e.what();
    const std::string where = c.line > 0 ? path + ":" + std::to_string(c.line) + ": " : path + ": ";
    EXPECT_EQ(msg.rfind(where, 0), 0u)
        << c.name << ": message '" << msg << "' does not start with '" << where << "'";
    EXPECT_NE(msg.find(c.reason), std::string::npos)
        << c.name << ": '" << msg << "' lacks '" << c.reason << "'";
  }
}

std::vector<BadCase> bad_cases() {
  const std::string g = kGood22;
  const std::string v1 = kGood1;
  return {
      {"empty", "", 0, "empty file"},
      {"not_gmsh", "hello world\n", 1, "not a Gmsh mesh file"},
      {"truncated_in_nodes", head(g, 8), 8, "unexpected end of file in $Nodes"},
      {"truncated_in_elements", head(g, 12), 12, "unexpected end of file in $Elements"},
      {"missing_end_elements", head(g, 13), 13, "$EndElements missing"},
      {"missing_end_nodes", replace_line(g, 10, ""), 10, "expected $EndNodes"},
      {"missing_end_meshformat", replace_line(g, 3, ""), 3, "expected $EndMeshFormat"},
      {"no_elements_section", head(g, 10), 10, "no $Elements section"},
      {"node_count_too_high", replace_line(g, 5, "5"), 10, "expected 5 nodes, read 4"},
      {"node_count_too_low", replace_line(g, 5, "3"), 9, "expected $EndNodes"},
      {"element_count_too_high", replace_line(g, 12, "2"), 14, "expected 2 elements, read 1"},
      {"negative_count", replace_line(g, 5, "-4"), 5, "out of range"},
      {"non_number_coordinate", replace_line(g, 7, "2 1 0 abc"), 7, "'abc' is not a number"},
      {"non_finite_coordinate", replace_line(g, 7, "2 nan 0 0"), 7, "not finite"},
      {"non_integer_node_id", replace_line(g, 7, "2.5 1 0 0"), 7, "'2.5' is not an integer"},
      {"node_missing_field", replace_line(g, 7, "2 1 0"), 7, "expected 4 fields"},
      {"duplicate_node_id", replace_line(g, 7, "1 1 0 0"), 7,
       "duplicate node id 1 (first defined on line 6)"},
      {"second_order_type_11", replace_line(g, 13, "1 11 2 1 1 1 2 3 4 1 2 3 4 1 2"), 13,
       "set mesh.element = p2"},
      {"unknown_type_99", replace_line(g, 13, "1 99 2 1 1 1 2 3 4"), 13, "unknown element type 99"},
      {"hexahedron", replace_line(g, 13, "1 5 2 1 1 1 2 3 4 1 2 3 4"), 13, "only 4-node tetrahedra"},
      {"dangling_node", replace_line(g, 13, "1 4 2 1 1 1 2 3 7"), 13, "undefined node id 7"},
      {"tet_repeated_node", replace_line(g, 13, "1 4 2 1 1 1 2 3 3"), 13, "uses node id 3 twice"},
      {"tet_too_few_nodes", replace_line(g, 13, "1 4 2 1 1 1 2 3"), 13, "expected 9 fields"},
      {"duplicate_tet", replace_line(replace_line(g, 12, "2"), 13, "1 4 2 1 1 1 2 3 4\n2 4 2 1 1 4 3 2 1"),
       14, "same nodes as the tetrahedron on line 13"},
      {"binary_header", std::string("$MeshFormat\n4.1 1 8\n\x01\x00\x00\x00\n$EndMeshFormat\n", 40), 2,
       "binary .msh not supported, re-save as ASCII"},
      {"format_40", replace_line(g, 2, "4 0 8"), 2, "unsupported Gmsh format version '4'"},
      {"elements_before_nodes", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Elements\n0\n$EndElements\n", 4,
       "$Elements before $Nodes"},
      {"stray_end_marker", replace_line(g, 11, "$EndFoo\n$Elements"), 11, "unmatched section end marker"},
      {"unterminated_unknown_section", head(g, 10) + "$NodeData\n1\n", 12, "$EndNodeData missing"},
      {"v1_truncated", head(v1, 5), 5, "unexpected end of file in $NOD"},
      {"v1_declared_node_count", replace_line(v1, 10, "1 4 1 1 3 1 2 3"), 10, "declares 3 nodes, expected 4"},
      {"v1_missing_endnod", replace_line(v1, 7, ""), 7, "expected $ENDNOD"},
      {"v1_dangling", replace_line(v1, 10, "1 4 1 1 4 1 2 3 9"), 10, "undefined node id 9"},
      {"v41_block_count",
       "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 3 1 2\n0 1 0 2\n1\n2\n0 0 0\n1 0 0\n$EndNodes\n"
       "$Elements\n0 0 0 0\n$EndElements\n",
       5, "declares 3 nodes, but the blocks hold 2"},
  };
}

INSTANTIATE_TEST_SUITE_P(Table, MalformedGmsh, testing::ValuesIn(bad_cases()),
                         [](const testing::TestParamInfo<BadCase>& p) { return std::string(p.param.name); });

}  // namespace
}  // namespace tmlab
