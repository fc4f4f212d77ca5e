#pragma once
// Smooth drives from planned control trajectories (6.4): the planner produces the controls
// (boom angle, rope lengths) at discrete times; the simulator needs them as smooth functions
// that start and end at rest.

#include <vector>

#include "cranesim/math/profile.hpp"

namespace cranesim {

/// The discrete control trajectory (t_k, y_k), k = 0..n (increasing t, any spacing) resampled
/// by linear interpolation at `points` equally spaced times over [t_0, t_n], padded with
/// `steady_points` knots of value y_0 before t_0 and y_n after t_n at the same spacing, and
/// interpolated by the cubic spline with zero slope at both ends. The knots lie on the
/// simulation's time axis: knot j at j · spacing, so the first steady knot is at 0 and t_0 falls
/// on knot `steady_points`. (A spline shifted in time afterwards would keep slopes rounded
/// differently from those of the same knots read from a scene file.)
/// Throws std::invalid_argument on points < 2, steady_points < 0, sizes mismatching or below 2,
/// or t not strictly increasing.
TableProfile smoothControlTrajectory(const std::vector<double>& t, const std::vector<double>& y, int points,
                                     int steady_points);

/// The largest |dy/dt|, |d²y/dt²| and |d³y/dt³| of a cubic table (what a drive following it asks
/// of its winch or motor): per interval exact, the rate being quadratic, its derivative linear
/// and the jerk constant in t.
struct RatePeaks {
  double speed = 0.0, acceleration = 0.0, jerk = 0.0;
};
RatePeaks ratePeaks(const TableProfile& spline);

}  // namespace cranesim
