// The messages of `tmlab realtime --serve` (docs/realtime.md, "The live page"), kept free of any
// network code so that they are tested on their own and shared by the server and the test client.
//
// server -> page, once per connection (text, JSON):
//   {"type": "hello", "nodes": N, "triangles": [i0, j0, k0, i1, ...] (the boundary faces),
//    "probe_radius": R, "probe": [x, y, z], "bounds": {"min": [...], "max": [...]},
//    "probe_box": {"min": [...], "max": [...]}, "case": "...", "visual_hz": 40}
// server -> page, every new visual frame (binary, little-endian, 48-byte header then the nodes):
//   u32 magic 'TMLF' | u32 frame index | u32 nodes N | u32 0 | f64 t (s, wall time of the loop) |
//   f32 force on the probe [3] (N) | f32 probe centre [3] (m) | f32 node positions [3 N] (m)
// page -> server (text, JSON): {"type": "probe", "x": [x, y, z]}, the probe target in metres in
//   the mesh frame. It is checked (finite numbers, nothing else) and clamped into the probe box
//   (the rest mesh's bounding box grown by 2 probe radii), so no input can put the probe far away.
#pragma once

#include "core/mesh/mesh.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace tmlab::rt {

/// One visual frame as the server sends it.
struct LiveFrame {
  std::uint32_t index = 0;
  double t = 0.0;
  Vec3 force = Vec3::Zero(), probe = Vec3::Zero();
  std::vector<float> xyz;  ///< 3 per node
};

struct Box {
  Vec3 min = Vec3::Zero(), max = Vec3::Zero();
};

inline constexpr std::uint32_t kLiveFrameMagic = 0x464C4D54u;  // "TMLF" read as little-endian bytes
inline constexpr std::size_t kLiveFrameHeader = 48;

/// Encodes `f` into `out` (resized; no allocation once `out` has the capacity).
void encode_frame(const LiveFrame& f, std::vector<std::uint8_t>& out);
/// Decodes a binary frame; throws tmlab::Error for a wrong magic or size.
LiveFrame decode_frame(const std::uint8_t* data, std::size_t size);

/// The probe box of a mesh: its bounding box grown by `margin` on every side.
Box probe_box(const Mesh& mesh, double margin);

/// The hello message (above) for the mesh's boundary faces.
std::string hello_message(const Mesh& mesh, double probe_radius, const Vec3& probe, const Box& box,
                          const std::string& case_name, double visual_hz);

/// Parses a page message; returns the probe target clamped into `box`, or nullopt with `error`
/// set (the message is not JSON, not a probe message, or its x is not three finite numbers).
std::optional<Vec3> parse_probe_message(const std::string& text, const Box& box, std::string& error);

}  // namespace tmlab::rt
