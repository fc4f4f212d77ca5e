#pragma once
// The crane's slewing axis seen from the map's plane. An engineer gives a lift's pick and set as
// the end point's radius from the slewing axis and its height; the map works in the plane's
// (x, z). With the axis vertical through c and the plane at y = y_m (the end point's y as drawn),
// the plane's point x lies at the radius
//   r = √((x − c_x)² + (y_m − c_y)²),
// and the radius r at x = c_x + s √(r² − (y_m − c_y)²), s the side of the axis the end point is on.

#include <Eigen/Dense>

#include <optional>
#include <string>

#include "cranesim/model/scene.hpp"

namespace cranesim {

struct SlewingAxis {
  std::string constraint;                           // the revolute constraint it is the axis of
  Eigen::Vector2d point = Eigen::Vector2d::Zero();  // (x, y) where the vertical axis stands, m
  double plane_y = 0.0;                             // the map plane's y, m
  double side = -1.0;                               // sign of x − c_x where the end point is

  double radiusAt(double x) const;
  /// The plane's x at `radius`; std::domain_error when the radius is shorter than the plane's
  /// distance from the axis.
  double xAtRadius(double radius) const;
};

/// The vertical axis of the scene's revolute constraint `constraint` through its first joint and
/// the plane through `end_point`, both as drawn at the scene's start. Throws std::invalid_argument
/// when the constraint is missing, not revolute or its axis not vertical.
SlewingAxis slewingAxisOf(const Scene& scene, const std::string& constraint, const std::string& end_point);

}  // namespace cranesim
