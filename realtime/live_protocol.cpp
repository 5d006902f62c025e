#include "realtime/live_protocol.hpp"

#include "core/base/error.hpp"
#include "core/mesh/mesh_ops.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace tmlab::rt {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the live frame is little-endian on the wire");

namespace {

template <class T>
void put(std::uint8_t*& p, T v) {
  std::memcpy(p, &v, sizeof(T));
  p += sizeof(T);
}
template <class T>
T get(const std::uint8_t*& p) {
  T v{};
  std::memcpy(&v, p, sizeof(T));
  p += sizeof(T);
  return v;
}

nlohmann::json vec(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

void encode_frame(const LiveFrame& f, std::vector<std::uint8_t>& out) {
  out.resize(kLiveFrameHeader + f.xyz.size() * sizeof(float));
  std::uint8_t* p = out.data();
  put<std::uint32_t>(p, kLiveFrameMagic);
  put<std::uint32_t>(p, f.index);
  put<std::uint32_t>(p, static_cast<std::uint32_t>(f.xyz.size() / 3));
  put<std::uint32_t>(p, 0u);
  put<double>(p, f.t);
  for (int i = 0; i < 3; ++i) put<float>(p, static_cast<float>(f.force[i]));
  for (int i = 0; i < 3; ++i) put<float>(p, static_cast<float>(f.probe[i]));
  if (!f.xyz.empty()) std::memcpy(p, f.xyz.data(), f.xyz.size() * sizeof(float));
}

LiveFrame decode_frame(const std::uint8_t* data, std::size_t size) {
  if (size < kLiveFrameHeader)
    throw Error("live frame: " + std::to_string(size) + " bytes, less than the header");
  const std::uint8_t* p = data;
  LiveFrame f;
  if (get<std::uint32_t>(p) != kLiveFrameMagic) throw Error("live frame: wrong magic");
  f.index = get<std::uint32_t>(p);
  const std::uint32_t n = get<std::uint32_t>(p);
  (void)get<std::uint32_t>(p);
  if (size != kLiveFrameHeader + 12u * static_cast<std::size_t>(n))
    throw Error("live frame: " + std::to_string(size) + " bytes for " + std::to_string(n) + " nodes");
  f.t = get<double>(p);
  for (int i = 0; i < 3; ++i) f.force[i] = get<float>(p);
  for (int i = 0; i < 3; ++i) f.probe[i] = get<float>(p);
  f.xyz.resize(3u * n);
  std::memcpy(f.xyz.data(), p, f.xyz.size() * sizeof(float));
  return f;
}

Box probe_box(const Mesh& mesh, double margin) {
  Box b;
  if (mesh.points.empty()) return b;
  b.min = b.max = mesh.points.front();
  for (const Vec3& x : mesh.points) {
    b.min = b.min.cwiseMin(x);
    b.max = b.max.cwiseMax(x);
  }
  b.min.array() -= margin;
  b.max.array() += margin;
  return b;
}

std::string hello_message(const Mesh& mesh, double probe_radius, const Vec3& probe, const Box& box,
                          const std::string& case_name, double visual_hz) {
  std::vector<Index> tri;
  for (const Tri& f : boundary_faces(mesh)) tri.insert(tri.end(), f.begin(), f.end());
  const Box bounds = probe_box(mesh, 0.0);
  const nlohmann::json j = {{"type", "hello"},
                            {"nodes", mesh.num_points()},
                            {"triangles", tri},
                            {"probe_radius", probe_radius},
                            {"probe", vec(probe)},
                            {"bounds", {{"min", vec(bounds.min)}, {"max", vec(bounds.max)}}},
                            {"probe_box", {{"min", vec(box.min)}, {"max", vec(box.max)}}},
                            {"case", case_name},
                            {"visual_hz", visual_hz}};
  return j.dump();
}

std::optional<Vec3> parse_probe_message(const std::string& text, const Box& box, std::string& error) {
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object()) {
    error = "not a JSON object";
    return std::nullopt;
  }
  const auto type = j.find("type");
  if (type == j.end() || !type->is_string() || type->get<std::string>() != "probe") {
    error = "not a probe message (\"type\": \"probe\" expected)";
    return std::nullopt;
  }
  const auto x = j.find("x");
  if (x == j.end() || !x->is_array() || x->size() != 3) {
    error = "probe message: \"x\" must be three numbers";
    return std::nullopt;
  }
  Vec3 c;
  for (int i = 0; i < 3; ++i) {
    const auto& v = (*x)[static_cast<std::size_t>(i)];
    if (!v.is_number() || !std::isfinite(v.get<double>())) {
      error = "probe message: \"x\" must be three finite numbers";
      return std::nullopt;
    }
    c[i] = std::clamp(v.get<double>(), box.min[i], box.max[i]);
  }
  return c;
}

}  // namespace tmlab::rt
