#include "cranesim/planning/flat_pendulum.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

namespace cranesim {

PendulumControls flatPendulumControls(const LuffingPendulum& crane, const Eigen::Vector2d& p, const Eigen::Vector2d& a) {
  const Eigen::Vector2d lift = a + Eigen::Vector2d(0.0, crane.gravity);
  if (!(lift.y() > 0.0)) throw std::domain_error("flat pendulum: the load falls faster than gravity: the rope goes slack");
  const Eigen::Vector2d e = lift.normalized();
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

double restToRest(double tau, int derivative) {
  if (derivative < 0 || derivative > 4) throw std::invalid_argument("restToRest: derivatives 0 … 4");
  if (tau <= 0.0 || tau >= 1.0) return derivative == 0 && tau >= 1.0 ? 1.0 : 0.0;
  // Coefficients of τ^5 … τ^9, differentiated `derivative` times.
  std::array<double, 5> c{126.0, -420.0, 540.0, -315.0, 70.0};
  std::array<int, 5> power{5, 6, 7, 8, 9};
  for (int k = 0; k < derivative; ++k)
    for (int i = 0; i < 5; ++i) c[i] *= power[i]--;
  double value = 0.0;
  for (int i = 0; i < 5; ++i) value += c[i] * std::pow(tau, power[i]);
  return value;
}

}  // namespace cranesim
