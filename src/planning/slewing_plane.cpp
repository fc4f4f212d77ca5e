#include "cranesim/planning/slewing_plane.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace cranesim {
namespace {

Eigen::Vector2d turned(const Eigen::Vector2d& v, double phi) { return Eigen::Rotation2Dd(phi) * v; }

/// J v: v turned by +90°.
Eigen::Vector2d perpendicular(const Eigen::Vector2d& v) { return {-v.y(), v.x()}; }

}  // namespace

SlewingPlane::SlewingPlane(const Vec3& axis_point, double plane_y, double side)
    : axis_point_(axis_point), plane_y_(plane_y), side_(side < 0.0 ? -1.0 : 1.0), turns_(true) {}

Vec3 SlewingPlane::place(double x, double z, double phi) const {
  const Eigen::Vector2d c = axis_point_.head<2>();
  const Eigen::Vector2d h = c + turned(Eigen::Vector2d(x, plane_y_) - c, phi);
  return {h.x(), h.y(), z};
}

Vec3 SlewingPlane::acceleration(double x, double dx, double ddx, double ddz, double phi, double dphi, double ddphi) const {
  const Eigen::Vector2d l = Eigen::Vector2d(x, plane_y_) - axis_point_.head<2>();
  const Eigen::Vector2d dl(dx, 0.0), ddl(ddx, 0.0);
  const Eigen::Vector2d h =
      turned(ddl + 2.0 * dphi * perpendicular(dl) + ddphi * perpendicular(l) - dphi * dphi * l, phi);
  return {h.x(), h.y(), ddz};
}

PlanePoint SlewingPlane::locate(const Vec3& P, double phi_near) const {
  if (!turns_) return {P.x(), P.z(), 0.0};
  const Eigen::Vector2d h = P.head<2>() - axis_point_.head<2>();
  const double offset = plane_y_ - axis_point_.y();
  const double radius_squared = h.squaredNorm() - offset * offset;
  if (!(radius_squared >= 0.0))
    throw std::domain_error("the point lies closer to the slewing axis than the crane's plane passes it");
  const Eigen::Vector2d l(side_ * std::sqrt(radius_squared), offset);
  const double raw = std::atan2(h.y(), h.x()) - std::atan2(l.y(), l.x());
  const double phi = phi_near + std::remainder(raw - phi_near, 2.0 * std::numbers::pi);
  return {axis_point_.x() + l.x(), P.z(), phi};
}

}  // namespace cranesim
