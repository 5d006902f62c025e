// The PNG writer produces a valid file (signature, chunk CRCs, inflated pixels equal to the input),
// and the renderer draws the liver, the probe and the force arrow where they project.
#include "realtime/frame_renderer.hpp"

#include "core/base/error.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/testing/temp_dir.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <fstream>
#include <iterator>

namespace tmlab::rt {
namespace {

std::uint32_t be32(const std::vector<std::uint8_t>& b, std::size_t i) {
  return (std::uint32_t(b[i]) << 24) | (std::uint32_t(b[i + 1]) << 16) | (std::uint32_t(b[i + 2]) << 8) |
         b[i + 3];
}

class Png : public tmlab::testing::TempDirTest {};

TEST_F(Png, RoundTripsThroughZlib) {
  const int w = 5, h = 3;
  std::vector<std::uint8_t> rgb(w * h * 3);
  for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<std::uint8_t>(i * 7);
  const std::string path = (dir_ / "a.png").string();
  write_png(path, w, h, rgb);
  std::ifstream in(path, std::ios::binary);
  const std::vector<std::uint8_t> b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(b.size(), 8u);
  EXPECT_EQ(b[0], 0x89);
  EXPECT_EQ(std::string(b.begin() + 1, b.begin() + 4), "PNG");
  std::size_t i = 8;
  std::vector<std::uint8_t> idat;
  std::vector<std::string> types;
  while (i < b.size()) {
    const std::uint32_t len = be32(b, i);
    const std::string type(b.begin() + i + 4, b.begin() + i + 8);
    types.push_back(type);
    const uLong crc = crc32(0L, b.data() + i + 4, len + 4);
    EXPECT_EQ(be32(b, i + 8 + len), crc) << type;
    if (type == "IHDR") {
      EXPECT_EQ(be32(b, i + 8), std::uint32_t(w));
      EXPECT_EQ(be32(b, i + 12), std::uint32_t(h));
    }
    if (type == "IDAT") idat.insert(idat.end(), b.begin() + i + 8, b.begin() + i + 8 + len);
    i += 12 + len;
  }
  EXPECT_EQ(types, (std::vector<std::string>{"IHDR", "IDAT", "IEND"}));
  std::vector<std::uint8_t> raw((3 * w + 1) * h);
  uLongf n = raw.size();
  ASSERT_EQ(uncompress(raw.data(), &n, idat.data(), idat.size()), Z_OK);
  ASSERT_EQ(n, raw.size());
  for (int y = 0; y < h; ++y) {
    EXPECT_EQ(raw[y * (3 * w + 1)], 0);  // filter none
    for (int k = 0; k < 3 * w; ++k) EXPECT_EQ(raw[y * (3 * w + 1) + 1 + k], rgb[y * 3 * w + k]);
  }
  EXPECT_THROW(write_png(path, 4, 3, rgb), Error);
}

TEST(FrameRenderer, DrawsTheMeshAndTheProbe) {
  const Mesh mesh = make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), 2, 2, 2);
  FrameRenderer r(mesh, 64, 48);
  std::vector<float> xyz;
  for (const Vec3& p : mesh.points)
    for (int c = 0; c < 3; ++c) xyz.push_back(static_cast<float>(p[c]));
  const auto& img = r.render(xyz, Vec3(0.5, 0.5, 1.5), 0.2, Vec3(0, 0, 1), 0.1, {0.0, 0.5, 1.0}, 1.0);
  ASSERT_EQ(img.size(), 64u * 48u * 3u);
  long background = 0, mesh_red = 0;
  for (std::size_t i = 0; i < img.size(); i += 3) {
    if (img[i] == 245 && img[i + 1] == 245 && img[i + 2] == 245) ++background;
    if (img[i] > img[i + 1] + 40) ++mesh_red;
  }
  EXPECT_GT(background, 100);
  EXPECT_GT(mesh_red, 100);  // the reddish tissue is drawn
}

}  // namespace
}  // namespace tmlab::rt
