#include "cranesim/model/arc.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

namespace cranesim {

ArcNodes arcNodes(const Vec3& start, const Vec3& end, const ArcSpec& arc, int segments) {
  const Vec3 a = start - arc.centre, b = end - arc.centre;
  ArcNodes out;
  out.radius = a.norm();
  if (!(out.radius > 0.0)) throw SceneError(arc.where, "the arc's centre lies on its start");
  const double tolerance = 1e-6 * out.radius;
  if (std::abs(b.norm() - out.radius) > tolerance)
    throw SceneError(arc.where, fmt::format("the arc's end lies {:.9g} m from its centre, its start {:.9g} m: an arc keeps "
                                            "one radius",
                                            b.norm(), out.radius));
  Vec3 axis = arc.axis;
  if (axis.isZero()) {
    axis = a.cross(b);
    if (axis.norm() <= 1e-9 * out.radius * out.radius)
      throw SceneError(arc.where, "the arc's start, centre and end lie in one line: give the arc's axis (axis: [x, y, z])");
  }
  axis.normalize();
  if (std::abs(a.dot(axis)) > tolerance || std::abs(b.dot(axis)) > tolerance)
    throw SceneError(arc.where, "the arc's start and end must lie in the plane through its centre normal to its axis");
  out.angle = std::atan2(axis.dot(a.cross(b)), a.dot(b));
  if (out.angle <= tolerance / out.radius) out.angle += 2.0 * std::numbers::pi;  // about the axis, the long way
  for (int i = 0; i <= segments; ++i) {
    const Vec3 radial = Eigen::AngleAxisd(out.angle * i / segments, axis) * a;
    const Vec3 tangent = axis.cross(radial).normalized();
    Mat3 frame;
    frame << tangent, axis.cross(tangent), axis;
    out.positions.push_back(i == segments ? end : arc.centre + radial);
    out.frames.push_back(frame);
  }
  return out;
}

}  // namespace cranesim
