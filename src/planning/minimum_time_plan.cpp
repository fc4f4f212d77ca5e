#include "cranesim/planning/minimum_time_plan.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace cranesim {
namespace {

/// The lift keeps its drives' limits at its nodes; the control splines through the nodes
/// overshoot them between nodes by a fraction of h² (measured 0.16 % on Table 8-2 with 200
/// intervals), so the nodes keep 99 % of them.
constexpr double kNodeMargin = 0.99;

/// Central differences of samples y at times t (one-sided zero at the ends: the plan is at rest there).
template <class V> std::vector<V> rates(const std::vector<double>& t, const std::vector<V>& y) {
  std::vector<V> r(y.size(), V::Zero());
  for (std::size_t k = 1; k + 1 < y.size(); ++k) r[k] = (y[k + 1] - y[k - 1]) / (t[k + 1] - t[k - 1]);
  return r;
}

}  // namespace

LiftProblem liftProblem(const TargetSpec& target, const QuasiStaticPlan& plan) {
  LiftProblem p;
  LiftKinematics& k = p.crane;
  k.end_x = plan.fit.fx;
  k.end_z = plan.fit.fz;
  k.luffing = plan.fit.fluffing;
  k.hoist_length = plan.map.hoist_length;
  k.slewing_start = target.slewing ? target.slewing->start : 0.0;
  k.plane = plan.plane;
  k.hoist_start = plan.controls.front().hoist_length;
  k.hoist_end = plan.controls.back().hoist_length;
  k.along_start = plan.pendulum_length_start;
  k.along_end = plan.pendulum_length_end;
  k.across_start = plan.pendulum_across_start;
  k.across_end = plan.pendulum_across_end;
  k.gravity = -target.scene.gravity.z();

  const double turn = target.slewing ? target.slewing->turn : 0.0;
  const ControlPoint &a = plan.controls.front(), &b = plan.controls.back();
  p.start = Eigen::Vector3d(a.boom_angle_deg, a.hoist_change, 0.0);
  p.end = Eigen::Vector3d(b.boom_angle_deg, b.hoist_change, turn);
  const double slew_range = target.slewing ? 2.0 * std::numbers::pi : 0.0;
  p.q_min = Eigen::Vector3d(plan.map.boom_angles_deg.front(), plan.map.hoist_changes.front(), std::min(0.0, turn) - slew_range);
  p.q_max = Eigen::Vector3d(plan.map.boom_angles_deg.back(), plan.map.hoist_changes.back(), std::max(0.0, turn) + slew_range);

  const ControlLimits& limits = target.drive_limits;
  const double rise = target.minimum_time.rise_time;
  // The luffing rope's jerk through the boom angle's: its steepest slope in u at the ends.
  const double luffing_slope =
      std::max(std::abs(k.luffing.gradient(a.boom_angle_deg, a.hoist_change)(0)), std::abs(k.luffing.gradient(b.boom_angle_deg, b.hoist_change)(0)));
  const double slopes[3] = {luffing_slope, 1.0, 1.0};  // drive per coordinate: m/°, m/m, rad/rad
  for (const auto& [drive, d] :
       {std::pair{kLuffingDrive, &limits.luffing}, std::pair{kHoistDrive, &limits.hoist}, std::pair{kSlewingDrive, &limits.slewing}}) {
    if (!d->speed) continue;  // a drive the lift does not move (readTarget requires the others' speeds)
    DriveBounds& bounds = p.drives[drive];
    bounds.speed = kNodeMargin * *d->speed;
    bounds.acceleration = kNodeMargin * d->acceleration.value_or(*d->speed / rise);
    p.jerk_limit(drive) = kNodeMargin * d->jerk.value_or(bounds.acceleration / rise) / slopes[drive];
  }
  p.intervals = target.minimum_time.intervals;
  p.tolerance = target.minimum_time.tolerance;
  return p;
}

LiftGuess flatnessGuess(const TargetSpec& target, const QuasiStaticPlan& plan, const LiftProblem& problem) {
  const std::vector<double>& t = plan.path.t;
  const LiftKinematics& k = problem.crane;
  std::vector<Eigen::Vector3d> q;
  std::vector<Eigen::Vector2d> swing;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const ControlPoint& c = plan.controls[i];
    const double phi = target.slewing ? plan.slewing_angles[i] : 0.0;
    q.emplace_back(c.boom_angle_deg, c.hoist_change, phi);
    // p = r + ℓ_a ẑ + R_z(φ) D n: n from the load's offset below the suspension, in the plane's axes.
    const Eigen::Vector2d point = target.origin + plan.path.states[i].head<2>();
    const Vec3 load = k.plane.place(point.x(), point.y(), phi);
    const Vec3 resting = k.plane.place(k.end_x(c.boom_angle_deg, c.hoist_change), k.end_z(c.boom_angle_deg, c.hoist_change), phi);
    const double hoist = k.hoist_length - c.hoist_change;
    const Vec3 offset = Eigen::AngleAxisd(-phi, Vec3::UnitZ()) * (load - resting - k.along(hoist) * Vec3::UnitZ());
    const Vec3 n = Vec3(offset.x() / k.along(hoist), offset.y() / k.across(hoist), offset.z() / k.along(hoist)).normalized();
    swing.emplace_back(std::atan2(n.x(), -n.z()), std::asin(n.y()));
  }
  const std::vector<Eigen::Vector3d> rate = rates(t, q), acceleration = rates(t, rate), jerk = rates(t, acceleration);
  const std::vector<Eigen::Vector2d> swing_rate = rates(t, swing);
  LiftGuess guess{t.back() - t.front(), {}};
  for (std::size_t i = 0; i < t.size(); ++i) {
    LiftNode node;
    node.q = q[i];
    node.rate = rate[i];
    node.acceleration = acceleration[i];
    node.jerk = jerk[i];
    node.swing << swing[i], swing_rate[i];
    guess.nodes.push_back(node);
  }
  return guess;
}

}  // namespace cranesim
