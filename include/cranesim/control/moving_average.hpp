#pragma once
// The mean of a signal over its last n samples: a speed command passed through it changes as a
// ramp over n samples, and a ramp whose duration is a mode's period leaves that mode still (the
// spectrum of a rectangular acceleration pulse is zero at the inverse of its duration).

#include <cstddef>
#include <deque>
#include <stdexcept>

namespace cranesim {

class MovingAverage {
 public:
  /// Over `samples` (≥ 1) samples, starting from `value` held before.
  MovingAverage(std::size_t samples, double value) : window_(samples, value), sum_(value * static_cast<double>(samples)) {
    if (samples == 0) throw std::invalid_argument("a moving average needs at least one sample");
  }

  /// Takes this sample's value and returns the mean of the last n.
  double operator()(double value) {
    sum_ += value - window_.front();
    window_.pop_front();
    window_.push_back(value);
    return sum_ / static_cast<double>(window_.size());
  }

 private:
  std::deque<double> window_;
  double sum_;
};

}  // namespace cranesim
