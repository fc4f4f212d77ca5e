#pragma once
// The crane's vertical plane turned about its slewing axis (docs/planning.md). The static map
// describes the crane in one vertical plane: the end point at (x, y_m, z), world coordinates at
// the scene's slewing angle, y_m the plane's constant offset. Slewed by φ about the vertical axis
// through c, that point lies at
//   P = c + R_z(φ) ((x, y_m, z) − c).
// A point moving in the turning plane, l(t) = (x(t) − c_x, y_m − c_y) horizontally, accelerates as
//   P̈_h = R_z(φ) (l̈ + 2φ̇ J l̇ + φ̈ J l − φ̇² l),   P̈_z = z̈,   J = [[0, −1], [1, 0]]
// (relative, Coriolis, tangential and centripetal accelerations), which is what a load on a
// slewing crane's rope feels.

#include <Eigen/Dense>
#include <cmath>

#include "cranesim/math/types.hpp"

namespace cranesim {

/// A point of the map's plane and the slewing angle that turns the plane onto it.
struct PlanePoint {
  double x = 0.0, z = 0.0;  // map coordinates (world x, z at the scene's slewing angle), m
  double phi = 0.0;         // slewing angle relative to the scene's, rad
};

class SlewingPlane {
 public:
  /// A plane that does not turn: place() puts (x, y_m, z), locate() reads x and z back.
  explicit SlewingPlane(double plane_y = 0.0) : plane_y_(plane_y) {}
  /// A plane turning about the vertical axis through `axis_point`, its points at y = plane_y when
  /// φ = 0; `side` (+1 or −1) is the sign of x − c_x on the map's side of the axis.
  SlewingPlane(const Vec3& axis_point, double plane_y, double side);

  bool turns() const { return turns_; }
  /// A point of the slewing axis, and the y of the plane's points at φ = 0.
  const Vec3& axisPoint() const { return axis_point_; }
  double planeY() const { return plane_y_; }

  /// The world point of map point (x, z) with the plane turned by φ.
  Vec3 place(double x, double z, double phi) const;

  /// The horizontal unit vector along the plane (its x axis) turned by φ.
  Vec3 along(double phi) const { return {std::cos(phi), std::sin(phi), 0.0}; }

  /// The world acceleration of a point moving in the turning plane with map coordinates x(t),
  /// z(t) and slewing angle φ(t) (first and second derivatives given).
  Vec3 acceleration(double x, double dx, double ddx, double ddz, double phi, double dphi, double ddphi) const;

  /// The map point and slewing angle that place() turns onto P, with φ taken within ±π of
  /// `phi_near`. Throws std::domain_error when P lies closer to the axis than the plane's offset.
  PlanePoint locate(const Vec3& P, double phi_near) const;

 private:
  Vec3 axis_point_ = Vec3::Zero();
  double plane_y_ = 0.0, side_ = -1.0;
  bool turns_ = false;
};

}  // namespace cranesim
