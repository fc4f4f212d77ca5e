#pragma once
// Obstacles on a job site and their signed distance to the crane's parts (docs/planning.md,
// "Obstacles and clearance"): boxes, vertical cylinders and convex prisms against points,
// spheres, segments and capsules. Negative distances are penetration depths.

#include <cmath>
#include <string>
#include <variant>
#include <vector>

#include "cranesim/math/types.hpp"
#include "cranesim/model/source_location.hpp"

namespace cranesim {

/// A box of edge lengths `size` about `centre`, turned by `yaw` (rad) about the vertical.
struct BoxShape {
  BoxShape() = default;
  BoxShape(const Vec3& centre_, const Vec3& size_, double yaw)
      : centre(centre_), size(size_), cos_yaw(std::cos(yaw)), sin_yaw(std::sin(yaw)) {}
  Vec3 centre = Vec3::Zero();
  Vec3 size = Vec3::Ones();
  double cos_yaw = 1.0, sin_yaw = 0.0;  // the yaw's, taken once: a lift's clearances ask for millions of distances
};

/// A vertical cylinder standing on `base` (the centre of its bottom face).
struct CylinderShape {
  Vec3 base = Vec3::Zero();
  double radius = 1.0, height = 1.0;
};

/// A convex footprint in x–y (counter-clockwise) extruded from `bottom` to `top`.
struct PrismShape {
  std::vector<Eigen::Vector2d> footprint;
  double bottom = 0.0, top = 1.0;
};

using ObstacleShape = std::variant<BoxShape, CylinderShape, PrismShape>;

struct Obstacle {
  std::string name;
  ObstacleShape shape;
  SourceLocation where;
};

/// A part of the crane: the segment from `a` to `b` swept by a ball of `radius` (a capsule; a
/// sphere when a = b; the bare segment when the radius is 0).
struct Capsule {
  Vec3 a = Vec3::Zero(), b = Vec3::Zero();
  double radius = 0.0;
};

/// Signed distance from a point to the shape (exact).
double signedDistance(const ObstacleShape& shape, const Vec3& p);

/// A signed distance and its gradient in the point.
struct DistanceWithGradient {
  double distance = 0.0;
  Vec3 gradient = Vec3::Zero();
};

/// Signed distance from a point to the shape and its gradient (exact): outside, the unit vector
/// from the shape's nearest point, continuous (the distance to a convex set is C¹ outside it);
/// inside, the outward normal of the nearest face, which jumps where two faces are equally near.
DistanceWithGradient signedDistanceWithGradient(const ObstacleShape& shape, const Vec3& p);

/// How closely signedDistance(shape, capsule) finds the segment's closest point: the segment's
/// parameter within this, so the distance within it times the segment's length.
inline constexpr double kSegmentParameterTolerance = 1e-12;

/// Signed distance from a capsule to the shape: the smallest signed distance of a point of its
/// segment, less the radius. The signed distance to a convex set is convex along a line, so a
/// golden-section search over the segment finds it (to kSegmentParameterTolerance).
double signedDistance(const ObstacleShape& shape, const Capsule& part);

/// Whether a polygon (either orientation) is strictly convex; ordered counter-clockwise in place
/// when it is.
bool makeConvexCounterClockwise(std::vector<Eigen::Vector2d>& polygon);

}  // namespace cranesim
