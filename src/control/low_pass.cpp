#include "cranesim/control/low_pass.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace cranesim {

LowPassFilter::LowPassFilter(double cutoff, double sample_time) {
  if (!(sample_time > 0.0 && cutoff > 0.0 && cutoff < 0.5 / sample_time))
    throw std::invalid_argument(fmt::format(
        "a low-pass filter's cutoff must lie between 0 and the Nyquist frequency {} Hz, not {} Hz", 0.5 / sample_time, cutoff));
  const double w = std::tan(std::numbers::pi * cutoff * sample_time);  // prewarped ω_c h / 2
  const double norm = 1.0 / (1.0 + std::numbers::sqrt2 * w + w * w);
  b0 = w * w * norm;
  b1 = 2.0 * b0;
  b2 = b0;
  a1 = 2.0 * (w * w - 1.0) * norm;
  a2 = (1.0 - std::numbers::sqrt2 * w + w * w) * norm;
}

double LowPassFilter::operator()(double x) {
  if (!started_) {
    x1_ = x2_ = y1_ = y2_ = x;
    started_ = true;
  }
  const double y = b0 * x + b1 * x1_ + b2 * x2_ - a1 * y1_ - a2 * y2_;
  x2_ = x1_;
  x1_ = x;
  y2_ = y1_;
  y1_ = y;
  return y;
}

}  // namespace cranesim
