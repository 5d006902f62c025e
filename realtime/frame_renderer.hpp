// Offscreen frames of a recorded run: a tiny software rasteriser (orthographic view, z-buffer, flat
// Lambert shading of the boundary triangles) and a PNG writer (zlib deflate, crc32). Why not
// python/matplotlib: a 3-D matplotlib plot of ~1,500 triangles costs about a second per frame and
// sorts faces instead of depth-testing them; this costs milliseconds per frame, needs only zlib
// (already a dependency of HDF5) and gives the same pixels on every machine.
#pragma once

#include "core/mesh/mesh.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace tmlab::rt {

/// Writes an 8-bit RGB PNG (rgb: width*height*3 bytes, rows top to bottom). Throws tmlab::Error.
void write_png(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb);

class FrameRenderer {
 public:
  /// The view is fitted to the rest mesh; `view` is the direction the camera looks along.
  FrameRenderer(const Mesh& mesh, int width, int height, const Vec3& view = Vec3(0.35, 1.0, -0.6));
  /// Draws the surface at node positions `xyz` (3 per node), the probe (centre, radius) and the force
  /// on it (arrow from the centre, `metres_per_newton` long per newton), and a force-history strip
  /// along the bottom (`history`: |F| samples, newest last, scaled to `history_max` N).
  const std::vector<std::uint8_t>& render(const std::vector<float>& xyz, const Vec3& probe, double radius,
                                          const Vec3& force, double metres_per_newton,
                                          const std::vector<double>& history, double history_max);
  int width() const { return w_; }
  int height() const { return h_; }

 private:
  void project(const Vec3& p, double& sx, double& sy, double& depth) const;
  void pixel(int x, int y, double z, std::uint8_t r, std::uint8_t g, std::uint8_t b);
  void line(const Vec3& a, const Vec3& b, std::uint8_t r, std::uint8_t g, std::uint8_t bl);
  int w_, h_;
  std::vector<Tri> faces_;
  Vec3 ex_, ey_, ez_, centre_;
  double scale_ = 1.0;
  std::vector<std::uint8_t> rgb_;
  std::vector<double> zbuf_;
};

}  // namespace tmlab::rt
