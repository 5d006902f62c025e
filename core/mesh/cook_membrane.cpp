#include "core/mesh/cook_membrane.hpp"

#include "core/base/error.hpp"
#include "core/mesh/mesh_generator.hpp"

#include <cmath>

namespace tmlab {

static_assert(int{kCookClamped} == int{kBoxXmin} && int{kCookLoaded} == int{kBoxXmax} &&
                  int{kCookBottom} == int{kBoxYmin} && int{kCookTop} == int{kBoxYmax} &&
                  int{kCookBack} == int{kBoxZmin} && int{kCookFront} == int{kBoxZmax} &&
                  int{kCookBody} == int{kBoxBody},
              "the Cook membrane's tags are the box mesh's");

Mesh make_cook_membrane_mesh(const CookMembraneSpec& s) {
  for (double v : {s.length, s.left, s.right, s.thickness})
    if (!(v > 0.0) || !std::isfinite(v))
      throw Error("make_cook_membrane_mesh: the panel's length, heights and thickness must be positive");
  if (s.cells < 1 || s.layers < 1)
    throw Error("make_cook_membrane_mesh: cells and layers must be at least 1");
  Mesh mesh = make_box_mesh(Vec3::Zero(), Vec3::Ones(), s.cells, s.cells, s.layers);
  const Vec3 p0(0.0, 0.0, 0.0), p1(s.length, s.left, 0.0), p2(s.length, s.left + s.right, 0.0),
      p3(0.0, s.left, 0.0);
  for (Vec3& p : mesh.points) {
    const double u = p.x(), r = p.y(), z = p.z();
    Vec3 x = (1.0 - u) * (1.0 - r) * p0 + u * (1.0 - r) * p1 + u * r * p2 + (1.0 - u) * r * p3;
    x.z() = s.thickness * z;
    p = x;
  }
  for (PhysicalGroup& g : mesh.groups) {
    if (g.dim == 2 && g.tag == kCookClamped) g.name = "clamped";
    if (g.dim == 2 && g.tag == kCookLoaded) g.name = "loaded";
    if (g.dim == 2 && g.tag == kCookBottom) g.name = "bottom";
    if (g.dim == 2 && g.tag == kCookTop) g.name = "top";
    if (g.dim == 2 && g.tag == kCookBack) g.name = "back";
    if (g.dim == 2 && g.tag == kCookFront) g.name = "front";
  }
  return mesh;
}

double cook_membrane_volume(const CookMembraneSpec& s) {
  return 0.5 * s.length * (s.left + s.right) * s.thickness;
}

}  // namespace tmlab
