#include "cranesim/control/sway_sensor.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace cranesim {
namespace {

double nonNegative(double value, const char* what) {
  if (!(value >= 0.0 && std::isfinite(value)))
    throw std::invalid_argument(fmt::format("the sway sensor's {} must be 0 or positive, not {}", what, value));
  return value;
}

}  // namespace

SwaySensor::SwaySensor(const SwaySensorSpec& spec, double sample_time)
    : spec_(spec), delayed_(nonNegative(spec.delay, "delay"), sample_time), random_(spec.seed) {
  nonNegative(spec.angle_noise, "angle noise");
  nonNegative(spec.rate_noise, "rate noise");
}

Session::Sway SwaySensor::read(const Session::Sway& truth) {
  const Eigen::Vector4d late = delayed_(Eigen::Vector4d(truth.radial, truth.across, truth.radial_rate, truth.across_rate));
  Session::Sway measured{late(0), late(1), late(2), late(3)};
  if (spec_.angle_noise > 0.0) {
    measured.radial += spec_.angle_noise * normal_(random_);
    measured.across += spec_.angle_noise * normal_(random_);
  }
  if (spec_.rate_noise > 0.0) {
    measured.radial_rate += spec_.rate_noise * normal_(random_);
    measured.across_rate += spec_.rate_noise * normal_(random_);
  }
  return measured;
}

Session::Sway predictOverDelay(const Session::Sway& late, double delay, double gravity, double rope_length,
                               const Eigen::Vector2d& head_speed_change) {
  const double d = delay, g_over_l = gravity / rope_length;
  return {late.radial + d * late.radial_rate, late.across + d * late.across_rate,
          late.radial_rate - d * g_over_l * late.radial - head_speed_change(0) / rope_length,
          late.across_rate - d * g_over_l * late.across - head_speed_change(1) / rope_length};
}

}  // namespace cranesim
