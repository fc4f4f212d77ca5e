#include "cranesim/control/sway_axis.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace cranesim {

PendulumAxisModel pendulumAxisModel(double rope_length, double gravity, double drive_lag) {
  const double L = rope_length, T = drive_lag;
  PendulumAxisModel m;
  m.A << 0, 1, 0, 0,                //
      0, -1 / T, 0, 0,              //
      0, 0, 0, 1,                   //
      0, 1 / (T * L), -gravity / L, 0;  // θ̈ = −(g/L) θ − (u − v)/(T L)
  m.B << 0, 1 / T, 0, -1 / (T * L);
  return m;
}

SwayAxisController::SwayAxisController(const SwayAxisSpec& spec) : spec_(spec) {
  const auto positive = [](double value, const char* what) {
    if (!(value > 0.0 && std::isfinite(value)))
      throw std::invalid_argument(fmt::format("the sway controller's {} must be positive, not {}", what, value));
  };
  positive(spec.sample_time, "sample time");
  positive(spec.drive_lag, "drive lag");
  positive(spec.gravity, "gravity");
  positive(spec.position, "position deviation");
  positive(spec.speed, "speed deviation");
  positive(spec.angle, "angle deviation");
  positive(spec.angle_rate, "angular rate deviation");
  positive(spec.command, "command deviation");
  if (!(spec.steady_angle_time >= 0.0 && std::isfinite(spec.steady_angle_time)))
    throw std::invalid_argument(fmt::format("the steady angle's time constant must be 0 or positive, not {}",
                                            spec.steady_angle_time));
  if (spec.measurement_cutoff != 0.0) {
    angle_filter_.emplace(spec.measurement_cutoff, spec.sample_time);
    rate_filter_.emplace(spec.measurement_cutoff, spec.sample_time);
  }
}

void SwayAxisController::design(double rope_length) {
  if (!(rope_length > 0.0 && std::isfinite(rope_length)))
    throw std::invalid_argument(fmt::format("the rope's length must be positive, not {}", rope_length));
  const PendulumAxisModel model = pendulumAxisModel(rope_length, spec_.gravity, spec_.drive_lag);
  system_ = zeroOrderHold(model.A, model.B, spec_.sample_time);
  const Eigen::Vector4d deviations(spec_.position, spec_.speed, spec_.angle, spec_.angle_rate);
  const Eigen::Matrix4d Q = deviations.cwiseInverse().cwiseAbs2().asDiagonal();
  const Eigen::Matrix<double, 1, 1> R(1.0 / (spec_.command * spec_.command));
  gain_ = discreteLqr(system_, Q, R).K;
  design_length_ = rope_length;
}

double SwayAxisController::command(double rope_length, double position_error, double speed, double reference_speed,
                                   double angle, double angle_rate) {
  if (design_length_ == 0.0 || std::abs(rope_length - design_length_) > spec_.reschedule * design_length_)
    design(rope_length);
  if (angle_filter_) {
    angle = (*angle_filter_)(angle);
    angle_rate = (*rate_filter_)(angle_rate);
  }
  if (spec_.steady_angle_time > 0.0) {
    steady_angle_ += -std::expm1(-spec_.sample_time / spec_.steady_angle_time) * (angle - steady_angle_);
    angle -= steady_angle_;
  }
  const Eigen::Vector4d error(position_error, speed - reference_speed, angle, angle_rate);
  return reference_speed - gain_.dot(error);
}

}  // namespace cranesim
