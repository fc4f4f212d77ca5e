#include "cranesim/planning/control_trajectory.hpp"

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

}  // namespace cranesim
