#include "cranesim/planning/flat_pendulum.hpp"

#include <cmath>
#include <stdexcept>

namespace cranesim {
namespace {

/// The rope's direction from the load towards its suspension: e = (p̈ + g ẑ) / ‖p̈ + g ẑ‖.
Eigen::Vector2d ropeDirection(const Eigen::Vector2d& a, double gravity) {
  const Eigen::Vector2d lift = a + Eigen::Vector2d(0.0, gravity);
  if (!(lift.y() > 0.0)) throw std::domain_error("flat pendulum: the load falls faster than gravity: the rope goes slack");
  return lift.normalized();
}

}  // namespace

PendulumControls flatPendulumControls(const LuffingPendulum& crane, const Eigen::Vector2d& p, const Eigen::Vector2d& a) {
  const Eigen::Vector2d e = ropeDirection(a, crane.gravity);
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

Eigen::Vector2d restingPoint(const Eigen::Vector2d& p, const Eigen::Vector2d& a, double length, double gravity) {
  return p + length * (ropeDirection(a, gravity) - Eigen::Vector2d::UnitY());
}

}  // namespace cranesim
