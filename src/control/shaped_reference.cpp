#include "cranesim/control/shaped_reference.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace cranesim {
namespace {

// Substeps per sample of the reference's ramp and pendulum (semi-implicit Euler): ω h ≤ 4e-4 at
// the sample times and periods of a crane, far below what the feedback could see.
constexpr int kSubsteps = 20;

}  // namespace

ShapedReference::ShapedReference(double period, double acceleration_limit, double sample_time, double start,
                                 double gravity)
    : period_(period), acceleration_limit_(acceleration_limit), sample_time_(sample_time), gravity_(gravity) {
  if (!(period > 0.0 && std::isfinite(period)))
    throw std::invalid_argument(fmt::format("the shaping period must be positive, not {}", period));
  if (!(acceleration_limit > 0.0))
    throw std::invalid_argument(fmt::format("the acceleration limit must be positive, not {}", acceleration_limit));
  if (!(sample_time > 0.0 && std::isfinite(sample_time)))
    throw std::invalid_argument(fmt::format("the sample time must be positive, not {}", sample_time));
  length_ = gravity * std::pow(period / (2.0 * std::numbers::pi), 2);
  delay_samples_ = static_cast<std::size_t>(std::lround(0.5 * period / sample_time));
  commands_.assign(delay_samples_, 0.0);
  now_.position = start;
}

ShapedReference::Sample ShapedReference::advance(double command, double metres_per_unit) {
  const Sample at_start = now_;
  commands_.push_back(command);
  const double shaped = 0.5 * command + 0.5 * commands_.front();
  commands_.pop_front();
  const double h = sample_time_ / kSubsteps, step = acceleration_limit_ * h;
  for (int k = 0; k < kSubsteps; ++k) {
    const double change = std::clamp(shaped - now_.speed, -step, step);
    const double acceleration = metres_per_unit * change / h;  // m/s² of the head along the axis
    now_.speed += change;
    now_.position += now_.speed * h;
    now_.angle_rate += (-(gravity_ / length_) * now_.angle - acceleration / length_) * h;
    now_.angle += now_.angle_rate * h;
  }
  return at_start;
}

}  // namespace cranesim
