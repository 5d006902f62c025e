// The messages of the live page (live_protocol.hpp): frames round-trip bit for bit, the hello
// describes the surface, and page messages are checked and clamped.
#include "realtime/live_protocol.hpp"

#include "core/base/error.hpp"
#include "core/mesh/mesh_ops.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace {

using namespace tmlab;
using namespace tmlab::rt;

Mesh one_tet() {
  Mesh m;
  m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 2, 0), Vec3(0, 0, 3)};
  m.tets = {{0, 1, 2, 3}};
  return m;
}

TEST(LiveProtocol, FrameRoundTrip) {
  LiveFrame f;
  f.index = 7;
  f.t = 1.25;
  f.force = Vec3(0.5, -0.25, 2.0);
  f.probe = Vec3(0.1, 0.2, 1.5);
  f.xyz = {1.f, 2.f, 3.f, 4.f, 5.f, 6.f};
  std::vector<std::uint8_t> bytes;
  encode_frame(f, bytes);
  ASSERT_EQ(bytes.size(), kLiveFrameHeader + 6 * sizeof(float));
  EXPECT_EQ(bytes[0], 'T');
  EXPECT_EQ(bytes[3], 'F');
  const LiveFrame g = decode_frame(bytes.data(), bytes.size());
  EXPECT_EQ(g.index, 7u);
  EXPECT_EQ(g.t, 1.25);
  EXPECT_EQ(g.force, f.force);  // exact in float
  EXPECT_EQ(g.probe.cast<float>(), f.probe.cast<float>());
  EXPECT_EQ(g.xyz, f.xyz);
  bytes.pop_back();
  EXPECT_THROW(decode_frame(bytes.data(), bytes.size()), Error);
  bytes[0] = 'X';
  EXPECT_THROW(decode_frame(bytes.data(), 40), Error);
}

TEST(LiveProtocol, HelloDescribesTheSurface) {
  const Mesh m = one_tet();
  const Box box = probe_box(m, 0.5);
  EXPECT_EQ(box.min, Vec3(-0.5, -0.5, -0.5));
  EXPECT_EQ(box.max, Vec3(1.5, 2.5, 3.5));
  const auto j = nlohmann::json::parse(hello_message(m, 0.1, Vec3(0, 0, 4), box, "tet", 40.0));
  EXPECT_EQ(j["type"], "hello");
  EXPECT_EQ(j["nodes"], 4);
  EXPECT_EQ(j["triangles"].size(), 3u * boundary_faces(m).size());
  EXPECT_EQ(j["triangles"].size(), 12u);
  EXPECT_EQ(j["probe_radius"], 0.1);
  EXPECT_EQ(j["bounds"]["max"][2], 3.0);
  EXPECT_EQ(j["probe_box"]["min"][0], -0.5);
}

TEST(LiveProtocol, ProbeMessagesAreCheckedAndClamped) {
  const Box box{Vec3(-1, -1, -1), Vec3(1, 1, 1)};
  std::string err;
  auto x = parse_probe_message(R"({"type":"probe","x":[0.5,-0.25,0]})", box, err);
  ASSERT_TRUE(x) << err;
  EXPECT_EQ(*x, Vec3(0.5, -0.25, 0.0));
  x = parse_probe_message(R"({"type":"probe","x":[5,-1e300,0.5]})", box, err);
  ASSERT_TRUE(x) << err;
  EXPECT_EQ(*x, Vec3(1.0, -1.0, 0.5));  // clamped into the box
  for (const char* bad : {"", "nonsense", "[1,2,3]", R"({"type":"move","x":[0,0,0]})", R"({"x":[0,0,0]})",
                          R"({"type":"probe","x":[0,0]})", R"({"type":"probe","x":[0,0,"1"]})",
                          R"({"type":"probe","x":[0,0,null]})", R"({"type":"probe"})"}) {
    err.clear();
    EXPECT_FALSE(parse_probe_message(bad, box, err)) << bad;
    EXPECT_FALSE(err.empty()) << bad;
  }
}

}  // namespace
