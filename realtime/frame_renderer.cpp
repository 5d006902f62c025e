#include "realtime/frame_renderer.hpp"

#include "core/base/error.hpp"
#include "core/mesh/mesh_ops.hpp"

#include <zlib.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>

namespace tmlab::rt {

namespace {

void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<std::uint8_t>((v >> s) & 0xFF));
}

void chunk(std::vector<std::uint8_t>& out, const char* type, const std::vector<std::uint8_t>& data) {
  put_u32(out, static_cast<std::uint32_t>(data.size()));
  const std::size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  const uLong crc = crc32(0L, out.data() + start, static_cast<uInt>(out.size() - start));
  put_u32(out, static_cast<std::uint32_t>(crc));
}

}  // namespace

void write_png(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb) {
  if (width <= 0 || height <= 0 || rgb.size() != static_cast<std::size_t>(width) * height * 3)
    throw Error("write_png: image size and pixel data disagree for " + path);
  // Scanlines with filter type 0 (none), deflated.
  std::vector<std::uint8_t> raw;
  raw.reserve(static_cast<std::size_t>(height) * (3 * width + 1));
  for (int y = 0; y < height; ++y) {
    raw.push_back(0);
    raw.insert(raw.end(), rgb.begin() + static_cast<long>(y) * 3 * width,
               rgb.begin() + static_cast<long>(y + 1) * 3 * width);
  }
  uLongf len = compressBound(static_cast<uLong>(raw.size()));
  std::vector<std::uint8_t> z(len);
  if (compress2(z.data(), &len, raw.data(), static_cast<uLong>(raw.size()), 6) != Z_OK)
    throw Error("write_png: deflate failed for " + path);
  z.resize(len);
  std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  std::vector<std::uint8_t> ihdr;
  put_u32(ihdr, static_cast<std::uint32_t>(width));
  put_u32(ihdr, static_cast<std::uint32_t>(height));
  ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});  // 8-bit, RGB, deflate, adaptive filters, no interlace
  chunk(png, "IHDR", ihdr);
  chunk(png, "IDAT", z);
  chunk(png, "IEND", {});
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  if (!out) throw Error("write_png: cannot write " + path);
}

FrameRenderer::FrameRenderer(const Mesh& mesh, int width, int height, const Vec3& view)
    : w_(width), h_(height), faces_(boundary_faces(mesh)) {
  ez_ = view.normalized();
  const Vec3 up = Vec3::UnitZ();
  ex_ = up.cross(ez_).normalized();  // screen right
  ey_ = ez_.cross(ex_);              // screen up
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  for (const Vec3& p : mesh.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  centre_ = 0.5 * (lo + hi);
  double ext_x = 0.0, ext_y = 0.0;
  for (const Vec3& p : mesh.points) {
    ext_x = std::max(ext_x, std::abs((p - centre_).dot(ex_)));
    ext_y = std::max(ext_y, std::abs((p - centre_).dot(ey_)));
  }
  // 80 % of the width, the upper 75 % of the height (the force strip below).
  scale_ = std::min(0.4 * w_ / ext_x, 0.33 * h_ / ext_y);
  rgb_.assign(static_cast<std::size_t>(w_) * h_ * 3, 0);
  zbuf_.assign(static_cast<std::size_t>(w_) * h_, 0.0);
}

void FrameRenderer::project(const Vec3& p, double& sx, double& sy, double& depth) const {
  const Vec3 d = p - centre_;
  sx = 0.5 * w_ + scale_ * d.dot(ex_);
  sy = 0.4 * h_ - scale_ * d.dot(ey_);
  depth = d.dot(ez_);  // larger = farther
}

void FrameRenderer::pixel(int x, int y, double z, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  if (x < 0 || y < 0 || x >= w_ || y >= h_) return;
  const std::size_t i = static_cast<std::size_t>(y) * w_ + x;
  if (z >= zbuf_[i]) return;
  zbuf_[i] = z;
  rgb_[3 * i] = r;
  rgb_[3 * i + 1] = g;
  rgb_[3 * i + 2] = b;
}

void FrameRenderer::line(const Vec3& a, const Vec3& b, std::uint8_t r, std::uint8_t g, std::uint8_t bl) {
  double ax, ay, az, bx, by, bz;
  project(a, ax, ay, az);
  project(b, bx, by, bz);
  const int n = static_cast<int>(std::max(std::abs(bx - ax), std::abs(by - ay))) + 1;
  for (int k = 0; k <= n; ++k) {
    const double s = static_cast<double>(k) / n;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        pixel(static_cast<int>(ax + s * (bx - ax)) + dx, static_cast<int>(ay + s * (by - ay)) + dy, -1e30, r,
              g, bl);
  }
}

const std::vector<std::uint8_t>& FrameRenderer::render(const std::vector<float>& xyz, const Vec3& probe,
                                                       double radius, const Vec3& force,
                                                       double metres_per_newton,
                                                       const std::vector<double>& history,
                                                       double history_max) {
  std::fill(rgb_.begin(), rgb_.end(), 245);
  std::fill(zbuf_.begin(), zbuf_.end(), std::numeric_limits<double>::infinity());
  const Vec3 light = (-ez_ + 0.5 * ey_).normalized();
  auto node = [&](Index i) {
    return Vec3(xyz[3 * static_cast<std::size_t>(i)], xyz[3 * static_cast<std::size_t>(i) + 1],
                xyz[3 * static_cast<std::size_t>(i) + 2]);
  };
  for (const Tri& f : faces_) {
    const Vec3 a = node(f[0]), b = node(f[1]), c = node(f[2]);
    Vec3 n = (b - a).cross(c - a);
    if (n.norm() == 0.0) continue;
    n.normalize();
    const double shade = 0.25 + 0.75 * std::abs(n.dot(light));
    const auto R = static_cast<std::uint8_t>(std::min(255.0, 200.0 * shade + 20));
    const auto G = static_cast<std::uint8_t>(std::min(255.0, 90.0 * shade + 10));
    const auto B = static_cast<std::uint8_t>(std::min(255.0, 80.0 * shade + 10));
    double x[3], y[3], z[3];
    project(a, x[0], y[0], z[0]);
    project(b, x[1], y[1], z[1]);
    project(c, x[2], y[2], z[2]);
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({x[0], x[1], x[2]}))));
    const int x1 = std::min(w_ - 1, static_cast<int>(std::ceil(std::max({x[0], x[1], x[2]}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({y[0], y[1], y[2]}))));
    const int y1 = std::min(h_ - 1, static_cast<int>(std::ceil(std::max({y[0], y[1], y[2]}))));
    const double area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
    if (std::abs(area) < 1e-12) continue;
    for (int py = y0; py <= y1; ++py)
      for (int px = x0; px <= x1; ++px) {
        const double qx = px + 0.5, qy = py + 0.5;
        const double w0 = ((x[1] - qx) * (y[2] - qy) - (x[2] - qx) * (y[1] - qy)) / area;
        const double w1 = ((x[2] - qx) * (y[0] - qy) - (x[0] - qx) * (y[2] - qy)) / area;
        const double w2 = 1.0 - w0 - w1;
        if (w0 < 0 || w1 < 0 || w2 < 0) continue;
        pixel(px, py, w0 * z[0] + w1 * z[1] + w2 * z[2], R, G, B);
      }
  }
  // The probe: a shaded disc at its centre's depth (a sphere seen orthographically).
  double cx, cy, cz;
  project(probe, cx, cy, cz);
  const double pr = radius * scale_;
  for (int py = static_cast<int>(cy - pr); py <= static_cast<int>(cy + pr); ++py)
    for (int px = static_cast<int>(cx - pr); px <= static_cast<int>(cx + pr); ++px) {
      const double dx = (px + 0.5 - cx) / pr, dy = (py + 0.5 - cy) / pr, rr = dx * dx + dy * dy;
      if (rr > 1.0) continue;
      const double nz = std::sqrt(1.0 - rr);
      const auto s = static_cast<std::uint8_t>(80 + 150 * std::max(0.0, 0.6 * nz - 0.4 * dy + 0.2 * dx));
      pixel(px, py, cz - radius * nz, s, s, static_cast<std::uint8_t>(std::min(255, s + 25)));
    }
  // The force on the probe (blue arrow, drawn on top).
  if (force.norm() > 0.0) line(probe, probe + metres_per_newton * force, 20, 60, 220);
  // Force history strip: |F| over the recent past, bottom 20 % of the image.
  const int top = static_cast<int>(0.8 * h_), bottom = h_ - 4;
  for (int x = 0; x < w_; ++x) pixel(x, top - 1, -1e30, 180, 180, 180);
  if (!history.empty() && history_max > 0.0) {
    const std::size_t n = history.size();
    for (int x = 0; x < w_; ++x) {
      const std::size_t i = static_cast<std::size_t>(static_cast<double>(x) / w_ * n);
      const double v = std::clamp(history[std::min(i, n - 1)] / history_max, 0.0, 1.0);
      const int y = bottom - static_cast<int>(v * (bottom - top));
      for (int yy = y; yy <= y + 1; ++yy) pixel(x, yy, -1e30, 20, 60, 220);
    }
  }
  return rgb_;
}

}  // namespace tmlab::rt
