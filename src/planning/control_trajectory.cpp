#include "cranesim/planning/control_trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace cranesim {

TableProfile smoothControlTrajectory(const std::vector<double>& t, const std::vector<double>& y, int points,
                                     int steady_points) {
  if (points < 2) throw std::invalid_argument("control trajectory: at least 2 resampling points are needed");
  if (steady_points < 0) throw std::invalid_argument("control trajectory: steady_points must not be negative");
  if (t.size() != y.size()) throw std::invalid_argument("control trajectory: t and y differ in size");
  if (t.size() < 2) throw std::invalid_argument("control trajectory: at least 2 samples are needed");
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (!std::isfinite(t[k]) || !std::isfinite(y[k]))
      throw std::invalid_argument("control trajectory: non-finite sample at index " + std::to_string(k));
    if (k > 0 && !(t[k] > t[k - 1]))
      throw std::invalid_argument("control trajectory: t must be strictly increasing (index " + std::to_string(k) + ")");
  }

  const double spacing = (t.back() - t.front()) / (points - 1);
  const int knots = points + 2 * steady_points;
  TableProfile profile;
  profile.t.reserve(knots);
  profile.y.reserve(knots);
  std::size_t segment = 1;  // samples t[segment − 1] ≤ time ≤ t[segment]
  for (int k = 0; k < knots; ++k) {
    profile.t.push_back(k * spacing);
    const int m = k - steady_points;  // the resampled point, or a steady knot outside 0 … points − 1
    if (m < 0 || m >= points) {
      profile.y.push_back(m < 0 ? y.front() : y.back());
      continue;
    }
    const double time = m + 1 == points ? t.back() : t.front() + m * spacing;
    while (segment + 1 < t.size() && t[segment] < time) ++segment;
    const double w = (time - t[segment - 1]) / (t[segment] - t[segment - 1]);
    profile.y.push_back((1.0 - w) * y[segment - 1] + w * y[segment]);
  }
  profile.slopes = splineSlopes(profile.t, profile.y, true);
  return profile;
}

RatePeaks ratePeaks(const TableProfile& spline) {
  RatePeaks peaks;
  for (std::size_t i = 0; i + 1 < spline.t.size(); ++i) {
    // On s = (t − t_i)/h the Hermite cubic's rate is (a s² + b s + c)/h, its derivative
    // (2a s + b)/h² and the jerk 2a/h³.
    const double h = spline.t[i + 1] - spline.t[i], dy = spline.y[i + 1] - spline.y[i];
    const double m0 = h * spline.slopes[i], m1 = h * spline.slopes[i + 1];
    const double a = -6.0 * dy + 3.0 * (m0 + m1), b = 6.0 * dy - 4.0 * m0 - 2.0 * m1, c = m0;
    const auto rate = [&](double s) { return std::abs((a * s + b) * s + c) / h; };
    peaks.speed = std::max({peaks.speed, rate(0.0), rate(1.0)});
    if (a != 0.0 && -b / (2.0 * a) > 0.0 && -b / (2.0 * a) < 1.0) peaks.speed = std::max(peaks.speed, rate(-b / (2.0 * a)));
    peaks.acceleration = std::max({peaks.acceleration, std::abs(b) / (h * h), std::abs(2.0 * a + b) / (h * h)});
    peaks.jerk = std::max(peaks.jerk, std::abs(2.0 * a) / (h * h * h));
  }
  return peaks;
}

}  // namespace cranesim
