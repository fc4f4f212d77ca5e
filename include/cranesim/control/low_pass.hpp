#pragma once
// A second-order Butterworth low-pass filter for sampled measurements: the analog prototype
// ω_c² / (s² + √2 ω_c s + ω_c²) mapped by the bilinear transform with the cutoff prewarped, so
// that the sampled filter passes exactly 1/√2 of a sinusoid at the cutoff and all of a constant.

namespace cranesim {

class LowPassFilter {
 public:
  /// `cutoff` (Hz) below the Nyquist frequency 1 / (2 `sample_time`); std::invalid_argument otherwise.
  LowPassFilter(double cutoff, double sample_time);

  /// The filtered value after the sample `x`. The first sample starts the filter at rest at `x`.
  double operator()(double x);

  /// y_k = b0 x_k + b1 x_{k−1} + b2 x_{k−2} − a1 y_{k−1} − a2 y_{k−2}.
  double b0, b1, b2, a1, a2;

 private:
  bool started_ = false;
  double x1_ = 0.0, x2_ = 0.0, y1_ = 0.0, y2_ = 0.0;
};

}  // namespace cranesim
