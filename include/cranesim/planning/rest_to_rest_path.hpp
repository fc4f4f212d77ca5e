#pragma once
// Rest-to-rest paths for flatness-based planning (docs/planning.md): a path whose derivatives up to
// the fourth vanish at both ends starts and ends with a load on a rope hanging plumb and its
// suspension at rest, so a suspension that follows the path's flat map leaves no sway.

#include <Eigen/Dense>

#include "cranesim/planning/qr_trajectory.hpp"

namespace cranesim {

/// The rest-to-rest transition s(τ) = 126τ⁵ − 420τ⁶ + 540τ⁷ − 315τ⁸ + 70τ⁹ on [0, 1] and its
/// derivatives d^k s / dτ^k, k = 0 … 4 (clamped to 0 and 1 outside): s' … s'''' vanish at both ends.
double restToRest(double tau, int derivative = 0);

/// A straight line from `start` to `end` (x, z) traversed in `duration` s with a speed that rises
/// from rest in a ramp of `ramp` s, cruises, and falls back to rest in a ramp as long:
///   σ'(t) = V [S((t) / T_r) − S((t − T + T_r) / T_r)],   V = 1 / (T − T_r),   σ(0) = 0, σ(T) = 1,
/// with the smooth step S(τ) = 35τ⁴ − 84τ⁵ + 70τ⁶ − 20τ⁷ (S' … S''' vanish at 0 and 1). The
/// path's derivatives 1 … 4 vanish at both ends; the fifth jumps at the ramps' ends. Its peak
/// speed is V·‖end − start‖ and its peak acceleration max S' · V / T_r = (35/16) V / T_r per unit length.
class RestToRestPath {
 public:
  RestToRestPath() = default;
  /// Throws std::invalid_argument unless duration > 0 and 0 < ramp ≤ duration / 2.
  RestToRestPath(const Eigen::Vector2d& start, const Eigen::Vector2d& end, double duration, double ramp);

  /// The path through the box of speeds [v_min, v_max] and accelerations [a_min, a_max] per axis
  /// with the longest ramps (the lowest accelerations) that keep the speeds within it: T_r = T/2
  /// unless a speed bound asks for a cruise. Throws std::invalid_argument ("infeasible horizon: …",
  /// naming the axis, the bound and the shortest duration that meets it) when no ramp fits.
  static RestToRestPath fitting(const Eigen::Vector2d& start, const Eigen::Vector2d& end, double duration,
                                const Eigen::Vector2d& v_min, const Eigen::Vector2d& v_max,
                                const Eigen::Vector2d& a_min, const Eigen::Vector2d& a_max);

  /// d^k σ / dt^k at t, k = 0 … 4: the fraction σ of the way covered (0 before, 1 after).
  double progress(double t, int k) const;
  /// d^k p / dt^k at t, k = 0 … 4; held at start and end outside [0, duration].
  Eigen::Vector2d derivative(double t, int k) const;
  double duration() const { return duration_; }
  double ramp() const { return ramp_; }

 private:
  Eigen::Vector2d start_ = Eigen::Vector2d::Zero(), end_ = Eigen::Vector2d::Zero();
  double duration_ = 0.0, ramp_ = 0.0;
};

/// The QR problem's start and target joined by RestToRestPath::fitting over its horizon
/// (steps · sample_time), or over `duration`, within its speed and acceleration bounds
/// (positions: the straight line between two points inside the state box stays inside it).
RestToRestPath restToRestPath(const QrProblem& problem);
RestToRestPath restToRestPath(const QrProblem& problem, double duration);

/// The path sampled every sample_time over its duration (the last sample at its end) as an
/// end-point trajectory: exact states; controls the mean accelerations over each interval.
QrTrajectory sampleTrajectory(const RestToRestPath& path, double sample_time);

}  // namespace cranesim
