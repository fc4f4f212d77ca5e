#include "cranesim/planning/flat_pendulum.hpp"

#include <cmath>
#include <stdexcept>

namespace cranesim {
namespace {

/// The rope's direction from the load towards its suspension: e = (p̈ + g ẑ) / ‖p̈ + g ẑ‖, ẑ the
/// last axis (up) of the plane (x, z) or the space (x, y, z).
template <int N> Eigen::Matrix<double, N, 1> ropeDirection(const Eigen::Matrix<double, N, 1>& a, double gravity) {
  Eigen::Matrix<double, N, 1> lift = a;
  lift(N - 1) += gravity;
  if (!(lift(N - 1) > 0.0)) throw std::domain_error("flat pendulum: the load falls faster than gravity: the rope goes slack");
  return lift.normalized();
}

}  // namespace

PendulumControls flatPendulumControls(const LuffingPendulum& crane, const Eigen::Vector2d& p, const Eigen::Vector2d& a) {
  const Eigen::Vector2d e = ropeDirection<2>(a, crane.gravity);
  const Eigen::Vector2d d = p - crane.foot;
  const double de = d.dot(e), discriminant = de * de - d.squaredNorm() + crane.boom_length * crane.boom_length;
  if (discriminant < 0.0) throw std::domain_error("flat pendulum: the rope's line misses the boom's reach");
  PendulumControls c;
  c.rope_length = -de + std::sqrt(discriminant);
  if (!(c.rope_length > 0.0)) throw std::domain_error("flat pendulum: the boom tip would lie below the load");
  c.tip = p + c.rope_length * e;
  c.boom_angle = std::asin((c.tip.y() - crane.foot.y()) / crane.boom_length);
  return c;
}

Vec3 restingPoint(const Vec3& p, const Vec3& a, double length_along, double length_across, const Vec3& along, double gravity) {
  const Vec3 tilt = ropeDirection<3>(a, gravity) - Vec3::UnitZ();
  const Vec3 across = Vec3::UnitZ().cross(along);
  return p + length_along * (tilt.dot(along) * along + tilt.z() * Vec3::UnitZ()) + length_across * tilt.dot(across) * across;
}

}  // namespace cranesim
