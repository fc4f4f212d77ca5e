#include "cranesim/control/shaped_head_path.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace cranesim {
namespace {

double halfPeriodSamples(double period, double sample_time) {
  if (!(period > 0.0 && std::isfinite(period)))
    throw std::invalid_argument(fmt::format("the shaping period must be positive, not {}", period));
  return std::max(1.0, 0.5 * period / sample_time);
}

/// The drive's ramp: `speed` moves towards `command` by at most `acceleration` × dt.
void ramp(double& speed, double command, double acceleration, double dt) {
  const double step = acceleration * dt;
  speed += std::clamp(command - speed, -step, step);
}

}  // namespace

ShapedHeadPath::ShapedHeadPath(const Eigen::Vector2d& head, double period, const Limits& limits, double sample_time,
                               double gravity)
    : limits_(limits), sample_time_(sample_time), gravity_(gravity), azimuth_(std::atan2(head.y(), head.x())),
      lever_radius_(head.norm()), shaped_(head) {
  if (!(sample_time > 0.0 && std::isfinite(sample_time)))
    throw std::invalid_argument(fmt::format("the sample time must be positive, not {}", sample_time));
  if (!(limits.slewing_acceleration > 0.0) || !(limits.radial_acceleration > 0.0))
    throw std::invalid_argument("the shaped path's acceleration limits must be positive");
  if (!(head.norm() > 0.0))
    throw std::invalid_argument("the boom head must be off the slewing axis to shape its path");
  delay_samples_ = halfPeriodSamples(period, sample_time);
  lever_history_.push_back(head);
}

Eigen::Vector2d ShapedHeadPath::leverPosition() const {
  const double azimuth = azimuth_ + lever_slewing_;
  return lever_radius_ * Eigen::Vector2d(std::cos(azimuth), std::sin(azimuth));
}

Eigen::Vector2d ShapedHeadPath::delayedLeverPosition() const {
  // p_L(t − T/2), linear between the samples about it; before the lever has moved for T/2 the
  // delayed half is where the head started.
  const double back = std::floor(delay_samples_), between = delay_samples_ - back;
  const std::size_t newest = lever_history_.size() - 1, k = static_cast<std::size_t>(back);
  if (k + 1 > newest) return lever_history_.front();
  return (1.0 - between) * lever_history_[newest - k] + between * lever_history_[newest - k - 1];
}

ShapedHeadPath::Sample ShapedHeadPath::advance(double slewing_speed, double radius_speed, double period) {
  const double dt = sample_time_;
  delay_samples_ = halfPeriodSamples(period, dt);
  ramp(lever_slewing_speed_, slewing_speed, limits_.slewing_acceleration, dt);
  ramp(lever_radius_speed_, radius_speed, limits_.radial_acceleration, dt);
  lever_slewing_ += lever_slewing_speed_ * dt;
  lever_radius_ += lever_radius_speed_ * dt;
  lever_history_.push_back(leverPosition());
  // Room for the delay to double as the hoist pays out; the oldest position stands in beyond.
  while (static_cast<double>(lever_history_.size()) > 2.0 * delay_samples_ + 2.0) lever_history_.pop_front();

  const Eigen::Vector2d next = 0.5 * (lever_history_.back() + delayedLeverPosition());
  const Eigen::Vector2d velocity = (next - shaped_) / dt;
  const Eigen::Vector2d acceleration = (velocity - shaped_velocity_) / dt;
  const double turn = std::atan2(shaped_.x() * next.y() - shaped_.y() * next.x(), shaped_.dot(next));

  Sample now;
  const Eigen::Vector2d radial = shaped_.normalized(), across(-radial.y(), radial.x());
  now.slewing = slewing_;
  now.slewing_speed = turn / dt;
  now.radius = shaped_.norm();
  now.radius_speed = (next.norm() - shaped_.norm()) / dt;
  now.radial = radial.dot(angle_);
  now.across = across.dot(angle_);
  now.radial_rate = radial.dot(angle_rate_);
  now.across_rate = across.dot(angle_rate_);

  // The pendulum over the sample under the held acceleration, exactly: about its offset −a/g it
  // swings at ω = 2π/T.
  const double omega = 2.0 * std::numbers::pi / period, c = std::cos(omega * dt), s = std::sin(omega * dt);
  const Eigen::Vector2d offset = -acceleration / gravity_, from = angle_ - offset;
  angle_ = offset + from * c + angle_rate_ * (s / omega);
  angle_rate_ = -from * (omega * s) + angle_rate_ * c;

  shaped_ = next;
  shaped_velocity_ = velocity;
  slewing_ += turn;
  return now;
}

}  // namespace cranesim
