#pragma once
// A signal sampled every h, read d = (n + f)·h late: the value at t − d interpolated linearly
// between the samples around it; before the first sample, the first sample.

#include <cmath>
#include <cstddef>
#include <deque>
#include <stdexcept>

namespace cranesim {

template <class Value>
class DelayLine {
 public:
  /// `delay` ≥ 0 and `sample_time` > 0 (std::invalid_argument otherwise).
  DelayLine(double delay, double sample_time) {
    if (!(delay >= 0.0 && std::isfinite(delay) && sample_time > 0.0 && std::isfinite(sample_time)))
      throw std::invalid_argument("a delay line needs a delay ≥ 0 and a positive sample time");
    const double samples = delay / sample_time;
    whole_ = static_cast<std::size_t>(std::floor(samples));
    fraction_ = samples - static_cast<double>(whole_);
  }

  /// Takes this sample's value and returns the value `delay` ago.
  Value operator()(const Value& now) {
    if (history_.empty()) history_.assign(whole_ + 2, now);
    history_.pop_front();
    history_.push_back(now);
    const Value& later = history_[history_.size() - 1 - whole_];
    const Value& earlier = history_[history_.size() - 2 - whole_];
    return (1.0 - fraction_) * later + fraction_ * earlier;
  }

 private:
  std::size_t whole_;
  double fraction_;
  std::deque<Value> history_;  // the last whole_ + 2 values, the newest last
};

}  // namespace cranesim
