#include "cranesim/planning/quasi_static_plan.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

#include "cranesim/io/results_writer.hpp"
#include "cranesim/model/compile.hpp"
#include "cranesim/model/reeved_rope.hpp"
#include "cranesim/planning/control_trajectory.hpp"
#include "cranesim/planning/flat_pendulum.hpp"
#include "cranesim/planning/minimum_time_plan.hpp"
#include "cranesim/planning/pendulum_map.hpp"
#include "cranesim/solvers/equilibrium_path.hpp"
#include "cranesim/solvers/modes.hpp"

namespace cranesim {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

GridData grid(const StaticMap& map, const Eigen::MatrixXd& values) {
  return {map.boom_angles_deg, map.hoist_changes, values};
}

/// The crane's equilibrium under the scene's controls at t (solvers/equilibrium_path.hpp: the
/// same statics as crane-sim's).
StaticResult equilibriumUnder(const Scene& scene, const Model& model, double t, const ControlPoint& c) {
  StaticResult eq = solveEquilibrium(scene, model, t);
  if (!eq.converged)
    throw std::runtime_error(fmt::format("no equilibrium at boom angle {:.4g}°, hoist rope {:.6g} m (luffing rope {:.6g} m): {}",
                                         c.boom_angle_deg, c.hoist_length, c.luffing_length, eq.message));
  return eq;
}

/// The trajectory point (relative coordinates) at time t, interpolated linearly and held at the ends.
Eigen::Vector2d trajectoryAt(const QrTrajectory& trajectory, double t) {
  const auto& ts = trajectory.t;
  if (t <= ts.front()) return trajectory.states.front().head<2>();
  if (t >= ts.back()) return trajectory.states.back().head<2>();
  const std::size_t k = std::upper_bound(ts.begin(), ts.end(), t) - ts.begin();
  const double w = (t - ts[k - 1]) / (ts[k] - ts[k - 1]);
  return (1.0 - w) * trajectory.states[k - 1].head<2>() + w * trajectory.states[k].head<2>();
}

/// Half the largest extent of the points over the horizontal directions (every 0.5°; within
/// 1e-5 of half their diameter): the amplitude of a sway in whichever direction it swings.
double halfHorizontalExtent(const std::vector<Eigen::Vector2d>& points) {
  double extent = 0.0;
  for (int k = 0; k < 360; ++k) {
    const double angle = k * std::numbers::pi / 360.0;
    const Eigen::Vector2d direction(std::cos(angle), std::sin(angle));
    double low = std::numeric_limits<double>::infinity(), high = -low;
    for (const Eigen::Vector2d& p : points) {
      const double s = direction.dot(p);
      low = std::min(low, s), high = std::max(high, s);
    }
    extent = std::max(extent, high - low);
  }
  return 0.5 * extent;
}

/// The pendulum the load hangs on: from where the hoist rope leaves the boom head to the end
/// point, at the configuration q: the rope's end farther from the end point, or a reeved rope's
/// first sheave (where its lead line turns into the falls).
double hangingLength(const Model& model, const VecX& q, const CraneControls& controls) {
  const Vec3 end = model.jointFrame(q.data(), model.findJoint(controls.end_point)).r;
  if (const int reeved = findReevedRope(model, controls.hoist_rope); reeved >= 0) {
    const VecX at_rest = VecX::Zero(model.nv);
    const ElementInput in{q.data(), at_rest.data(), nullptr, 0.0, model.gravity};
    return (reevedRope(model, reeved).pathPositions(in)[1] - end).norm();
  }
  double length = 0.0;
  for (const char* side : {".start", ".end"})
    length = std::max(length, (model.jointFrame(q.data(), model.findJoint(controls.hoist_rope + side)).r - end).norm());
  return length;
}

/// The map's plane at the start equilibrium q: at the end point's y, turning about the slewing
/// constraint's axis (which must be vertical) for a slewing target, whose map must keep the end
/// point in that plane.
SlewingPlane mapPlane(const TargetSpec& target, const StaticMap& map, const Model& model, const VecX& q) {
  const Vec3 end = model.jointFrame(q.data(), model.findJoint(target.controls.end_point)).r;
  if (!target.slewing) return SlewingPlane(end.y());
  const SlewingSpec& slewing = *target.slewing;
  double leaves = 0.0;
  for (Eigen::Index k = 0; k < map.end_y.size(); ++k)
    if (std::isfinite(map.end_y(k))) leaves = std::max(leaves, std::abs(map.end_y(k) - end.y()));
  if (leaves > 1e-3)
    throw SceneError(slewing.where, fmt::format("the map's end points leave the vertical plane y = {:.4g} m by {:.3g} m: a slewing "
                                                "plan turns that plane, so the crane's plane must be the x–z plane at the "
                                                "scene's slewing angle",
                                                end.y(), leaves));
  const auto c = std::find_if(model.constraints.begin(), model.constraints.end(),
                              [&](const Constraint& k) { return k.name == slewing.constraint; });
  const Vec3 axis_point = model.jointFrame(q.data(), c->joint1).r;  // its axis is vertical (target_reader.cpp)
  return SlewingPlane(axis_point, end.y(), end.x() < axis_point.x() ? -1.0 : 1.0);
}

/// Refuses a start or target whose load (a sphere of the target's load radius) lies within the
/// clearance margin of an obstacle, or inside one.
void checkEndsClear(const TargetSpec& target, const SlewingPlane& plane) {
  const Eigen::Vector2d origin = target.origin;
  const double turn = target.slewing ? target.slewing->turn : 0.0;
  for (const auto& [point, where, what, phi] : {std::tuple{target.trajectory.start, target.where_start, "start", 0.0},
                                                std::tuple{target.trajectory.target, target.where_target, "target", turn}}) {
    const Vec3 load = plane.place(origin.x() + point(0), origin.y() + point(1), phi);
    for (const Obstacle& o : target.obstacles) {
      const double d = signedDistance(o.shape, Capsule{load, load, target.load_radius});
      if (d >= target.clearance_margin) continue;
      throw SceneError(where, fmt::format("the load at the {} ({:.4g}, {:.4g}, {:.4g}) m {} obstacle '{}' (line {}): {}", what,
                                          load.x(), load.y(), load.z(), d < 0.0 ? "is inside" : "is too close to", o.name,
                                          o.where.line,
                                          d < 0.0 ? fmt::format("it reaches {:.3g} m into it", -d)
                                                  : fmt::format("{:.3g} m away, within the clearance margin of {:.3g} m", d,
                                                                target.clearance_margin)));
    }
  }
}

}  // namespace

MapFit fitStaticMap(const StaticMap& map, const SurfaceSpec& spec) {
  MapFit fit{grid(map, map.end_x), grid(map, map.end_z), grid(map, map.luffing_length), {}, {}, {}};
  fit.fx = FittedSurface::fit(fit.x, spec);
  fit.fz = FittedSurface::fit(fit.z, spec);
  fit.fluffing = FittedSurface::fit(fit.luffing, spec);
  return fit;
}

ControlPoint controlsAt(const MapFit& fit, const StaticMap& map, double x, double z) {
  Eigen::Vector2d uv;
  try {
    uv = invertSurfaces(fit.fx, fit.fz, fit.x, fit.z, x, z);
  } catch (const OutsideMap& e) {  // in the crane's terms: where the load can go, and how far off this is
    throw OutsideMap(
        fmt::format("(x, z) = ({:.4g}, {:.4g}) m is beyond the map of boom angles {:g}…{:g}° and hoist rope taken in "
                    "by {:g}…{:g} m: the nearest end point is ({:.4g}, {:.4g}) m, {:.3g} m away, at boom angle {:.4g}° "
                    "with {:.4g} m taken in; move the point or widen the map",
                    x, z, fit.x.u.front(), fit.x.u.back(), fit.x.v.front(), fit.x.v.back(), e.xz.x(), e.xz.y(),
                    (e.xz - Eigen::Vector2d(x, z)).norm(), e.uv.x(), e.uv.y()),
        e.uv, e.xz);
  }
  ControlPoint c;
  c.boom_angle_deg = uv(0);
  c.hoist_change = uv(1);
  c.luffing_length = fit.fluffing(uv(0), uv(1));
  c.hoist_length = map.hoist_length - uv(1);  // exact: the hoist change is the map's own variable
  return c;
}

namespace {

/// The controls of a map point (absolute x, z); leaving the map is bad input.
ControlPoint mapControls(const TargetSpec& target, const QuasiStaticPlan& plan, double x, double z) {
  try {
    return controlsAt(plan.fit, plan.map, x, z);
  } catch (const std::domain_error& e) {
    throw SceneError(target.where_trajectory, fmt::format("the planned trajectory leaves the static map: {}", e.what()));
  }
}

/// The controls of a path state (relative to the origin).
ControlPoint pathControls(const TargetSpec& target, const QuasiStaticPlan& plan, const EndState& s) {
  return mapControls(target, plan, target.origin(0) + s(0), target.origin(1) + s(1));
}

/// The slewing angle φ of the path's point relative to the scene's and its rates (φ, φ̇, φ̈) at
/// path time t: the plane's angle onto the lift's load, linear between its nodes (minimum_time), along the rest-to-rest path's progress
/// (flatness, and minimum_time's start), or a rest-to-rest turn over the QR horizon convolved
/// with the shaper's impulses (quasi_static: one impulse); 0 without a slewing target.
Eigen::Vector3d slewingAt(const TargetSpec& target, const QuasiStaticPlan& plan, double t) {
  Eigen::Vector3d phi = Eigen::Vector3d::Zero();
  if (!target.slewing) return phi;
  const double turn = target.slewing->turn;
  if (plan.lift) {
    const std::vector<double>& ts = plan.path.t;
    const double clamped = std::clamp(t, ts.front(), ts.back());
    const std::size_t k = std::min<std::size_t>(std::upper_bound(ts.begin(), ts.end(), clamped) - ts.begin(), ts.size() - 1);
    const double h = ts[k] - ts[k - 1], w = (clamped - ts[k - 1]) / h;
    const double a = plan.path_turns[k - 1], b = plan.path_turns[k];
    return Eigen::Vector3d((1.0 - w) * a + w * b, t > ts.front() && t < ts.back() ? (b - a) / h : 0.0, 0.0);
  }
  if (startsFromFlatness(target.method)) {
    for (int k = 0; k < 3; ++k) phi(k) = turn * plan.load_path.progress(t, k);
    return phi;
  }
  const double horizon = target.trajectory.steps * target.trajectory.sample_time;
  const bool shaped = !plan.shaper.times.empty();
  const std::vector<double> times = shaped ? plan.shaper.times : std::vector<double>{0.0};
  const std::vector<double> amplitudes = shaped ? plan.shaper.amplitudes : std::vector<double>{1.0};
  for (std::size_t i = 0; i < times.size(); ++i)
    for (int k = 0; k < 3; ++k)
      phi(k) += amplitudes[i] * turn * restToRest((t - times[i]) / horizon, k) / std::pow(horizon, k);
  return phi;
}

/// The load's pendulum for the flat map: the simple pendulum of the crane's sway period, its
/// length affine in the hoist rope's length between the path's start and end equilibria (as
/// the hanging length is, for a rope of fixed reeving).
/// Across the crane's plane the pendulum of the sway period across it.
struct EffectivePendulum {
  double hoist_start = 0.0, hoist_end = 0.0, length_start = 0.0, length_end = 0.0, across_start = 0.0, across_end = 0.0;

  double length(double hoist) const { return between(hoist, length_start, length_end); }
  double acrossLength(double hoist) const { return between(hoist, across_start, across_end); }

 private:
  double between(double hoist, double start, double end) const {
    if (std::abs(hoist_end - hoist_start) < 1e-9) return 0.5 * (start + end);
    return start + (end - start) * (hoist - hoist_start) / (hoist_end - hoist_start);
  }
};

/// The controls that carry the load along the flat path at time t, and the slewing angle they
/// need: the map's controls at the point where the load would hang at rest from the suspension
/// that carries it (planning/flat_pendulum.hpp: restingPoint; the load's acceleration includes
/// the slewing plane's, planning/slewing_plane.hpp), that point's slewing angle, and the
/// pendulum's length from the hoist rope those controls set: a fixed point, contracting by about
/// ℓ'·‖e − ẑ‖ ≈ 1e-2 per iteration.
std::pair<ControlPoint, double> flatControls(const TargetSpec& target, const QuasiStaticPlan& plan,
                                             const EffectivePendulum& pendulum, double t) {
  const Eigen::Vector2d p = target.origin + plan.load_path.derivative(t, 0), v = plan.load_path.derivative(t, 1),
                        a = plan.load_path.derivative(t, 2);
  const Eigen::Vector3d phi = slewingAt(target, plan, t);
  const Vec3 load = plan.plane.place(p.x(), p.y(), phi(0));
  const Vec3 acceleration = plan.plane.acceleration(p.x(), v.x(), a.x(), a.y(), phi(0), phi(1), phi(2));
  const double gravity = -target.scene.gravity.z();
  PlanePoint resting{p.x(), p.y(), phi(0)};
  Vec3 resting_point = load;
  ControlPoint c = mapControls(target, plan, resting.x, resting.z);
  for (int iteration = 0; iteration < 50; ++iteration) {
    const Vec3 next = restingPoint(load, acceleration, pendulum.length(c.hoist_length), pendulum.acrossLength(c.hoist_length),
                                   plan.plane.along(phi(0)), gravity);
    const double change = (next - resting_point).norm();
    resting_point = next;
    try {
      resting = plan.plane.locate(resting_point, phi(0));
    } catch (const std::domain_error& e) {
      throw SceneError(target.where_trajectory, fmt::format("the planned path at t = {:.4g} s: {}", t, e.what()));
    }
    c = mapControls(target, plan, resting.x, resting.z);
    if (change < 1e-10) return {c, resting.phi};
  }
  throw std::runtime_error(fmt::format("flatness: the resting point at t = {:.4g} s does not converge", t));
}

/// The largest of (peak / limit)^(1/k) over the limited drives and their k-th derivatives (k = 1
/// speed, 2 acceleration, 3 jerk): the factor by which a motion's duration would have to grow for
/// its drives to keep their limits, were its shape kept (≤ 1: they keep them; 0 without limits).
double driveLimitFactor(const ControlLimits& limits, const QuasiStaticPlan& plan) {
  double factor = 0.0;
  for (const auto& [drive, peaks] : {std::pair{&limits.luffing, &plan.luffing_peaks}, std::pair{&limits.hoist, &plan.hoist_peaks},
                                     std::pair{&limits.slewing, &plan.slewing_peaks}}) {
    if (drive->speed) factor = std::max(factor, peaks->speed / *drive->speed);
    if (drive->acceleration) factor = std::max(factor, std::sqrt(peaks->acceleration / *drive->acceleration));
    if (drive->jerk) factor = std::max(factor, std::cbrt(peaks->jerk / *drive->jerk));
  }
  return factor;
}

/// The control splines through the controls at the path's points (6.4), resampled at `points`
/// equal times, and what the splines ask of the drives.
void setControlSplines(const TargetSpec& target, QuasiStaticPlan& plan, const std::vector<double>& luffing,
                       const std::vector<double>& hoist, const std::vector<double>& slewing, int points) {
  plan.luffing_spline = smoothControlTrajectory(plan.path.t, luffing, points, target.steady_points);
  plan.hoist_spline = smoothControlTrajectory(plan.path.t, hoist, points, target.steady_points);
  plan.luffing_peaks = ratePeaks(plan.luffing_spline);
  plan.hoist_peaks = ratePeaks(plan.hoist_spline);
  if (target.slewing) {
    plan.slewing_spline = smoothControlTrajectory(plan.path.t, slewing, points, target.steady_points);
    plan.slewing_peaks = ratePeaks(plan.slewing_spline);
  }
  plan.lead_time = plan.luffing_spline.t[target.steady_points] - plan.path.t.front();
  plan.drive_limit_factor = driveLimitFactor(target.drive_limits, plan);
}

/// The control trajectory of the plan's path (6.4): the controls at every path point, their
/// smoothed splines, and what the splines ask of the drives.
void computeControls(const TargetSpec& target, QuasiStaticPlan& plan, const EffectivePendulum& pendulum) {
  std::vector<double> luffing, hoist, slewing;
  plan.controls.clear();
  plan.slewing_angles.clear();
  for (std::size_t k = 0; k < plan.path.states.size(); ++k) {
    const double t = plan.path.t[k];
    const auto [c, phi] = startsFromFlatness(target.method)
                              ? flatControls(target, plan, pendulum, t)
                              : std::pair{pathControls(target, plan, plan.path.states[k]), slewingAt(target, plan, t)(0)};
    plan.controls.push_back(c);
    luffing.push_back(c.luffing_length);
    hoist.push_back(c.hoist_length);
    if (target.slewing) {
      plan.slewing_angles.push_back(phi);
      slewing.push_back(target.slewing->start + phi);
    }
  }
  setControlSplines(target, plan, luffing, hoist, slewing, target.resample_points);
}

/// The controls of the minimum-time lift at its nodes, and its load as the path (relative to
/// the origin; speeds by central differences).
void liftControls(const TargetSpec& target, QuasiStaticPlan& plan) {
  const LiftTrajectory& lift = *plan.lift;
  std::vector<double> luffing, hoist, slewing;
  plan.path = QrTrajectory{};
  plan.controls.clear();
  plan.slewing_angles.clear();
  plan.path_turns.clear();
  for (std::size_t k = 0; k < lift.t.size(); ++k) {
    const LiftNode& node = lift.nodes[k];
    const DriveState& drives = lift.drives[k];
    plan.controls.push_back({node.q(0), node.q(1), drives.value(kLuffingDrive), drives.value(kHoistDrive)});
    luffing.push_back(drives.value(kLuffingDrive));
    hoist.push_back(drives.value(kHoistDrive));
    if (target.slewing) {
      plan.slewing_angles.push_back(node.q(2));
      slewing.push_back(drives.value(kSlewingDrive));
    }
    const PlanePoint at = plan.plane.locate(lift.load[k], node.q(2));
    plan.path.t.push_back(lift.t[k]);
    plan.path_turns.push_back(at.phi);
    plan.path.states.push_back(EndState(at.x - target.origin.x(), at.z - target.origin.y(), 0.0, 0.0));
  }
  for (std::size_t k = 1; k + 1 < lift.t.size(); ++k)
    plan.path.states[k].tail<2>() = (plan.path.states[k + 1].head<2>() - plan.path.states[k - 1].head<2>()) / (lift.t[k + 1] - lift.t[k - 1]);
  // The nodes are equally spaced: the splines interpolate them.
  setControlSplines(target, plan, luffing, hoist, slewing, static_cast<int>(lift.t.size()));
}

}  // namespace

QuasiStaticPlan planQuasiStatic(const TargetSpec& target, StaticMap map, const PlanLog& log) {
  const auto say = [&](const std::string& line) {
    if (log) log(line);
  };
  QuasiStaticPlan plan;
  const QrProblem& problem = target.trajectory;
  const Eigen::Vector2d origin = target.origin;

  // 1. Static map (6.2).
  plan.map = std::move(map);
  plan.map_s = plan.map.time_s;
  if (!plan.map.failures.empty())
    throw std::runtime_error(fmt::format("{} static map points failed; the first: {}", plan.map.failures.size(),
                                         plan.map.failures.front()));
  say(fmt::format("static map: {} × {} equilibria in {:.1f} s ({} Jacobian factorisations, {})", plan.map.rows(),
                  plan.map.columns(), plan.map_s, plan.map.jacobians, plan.map.execution));

  // 2. Fitted surfaces.
  auto t0 = Clock::now();
  plan.fit = fitStaticMap(plan.map, target.fit);
  plan.fit_s = secondsSince(t0);
  say(fmt::format("fit: max residual x {:.3g} m, z {:.3g} m, luffing rope {:.3g} m", plan.fit.fx.maxResidual(),
                  plan.fit.fz.maxResidual(), plan.fit.fluffing.maxResidual()));
  for (const auto& [point, where, what] :
       {std::tuple{problem.start, target.where_start, "start"}, std::tuple{problem.target, target.where_target, "target"}}) {
    try {
      controlsAt(plan.fit, plan.map, origin(0) + point(0), origin(1) + point(1));
    } catch (const std::domain_error& e) {
      throw SceneError(where, fmt::format("the {} is not reachable within the static map: {}", what, e.what()));
    }
  }

  // 3. QR end-point trajectory (6.3).
  t0 = Clock::now();
  plan.trajectory = solveQrTrajectory(problem);
  plan.trajectory_s = secondsSince(t0);
  const EndState end = plan.trajectory.states.back();
  say(fmt::format("trajectory: {} steps, cost {:.6g}, {} Ipopt iterations in {:.3f} s; end at ({:.4f}, {:.4f}) m", problem.steps,
                  plan.trajectory.cost, plan.trajectory.iterations, plan.trajectory_s, end(0), end(1)));

  // 4. map(inverse(p)) − p at five points of the trajectory, against the crane's own equilibrium;
  // at its ends also the pendulum the load hangs on.
  t0 = Clock::now();
  EffectivePendulum pendulum;
  const int n = static_cast<int>(plan.trajectory.states.size());
  for (int k : {0, (n - 1) / 4, (n - 1) / 2, 3 * (n - 1) / 4, n - 1}) {
    InversionCheck check;
    check.t = plan.trajectory.t[k];
    check.planned = origin + plan.trajectory.states[k].head<2>();
    const ControlPoint c = pathControls(target, plan, plan.trajectory.states[k]);
    const Scene scene = withControls(target.scene, target.controls, Profile(ConstantProfile{c.luffing_length}),
                                     Profile(ConstantProfile{c.hoist_length}));
    const Model model = compileModel(scene);
    const StaticResult eq = equilibriumUnder(scene, model, scene.solver.t_start, c);
    const Vec3 reached = model.jointFrame(eq.q.data(), model.findJoint(target.controls.end_point)).r;
    check.reached = Eigen::Vector2d(reached.x(), reached.z());
    check.error = (check.reached - check.planned).norm();
    plan.inversion_checks.push_back(check);
    if (k == 0) plan.plane = mapPlane(target, plan.map, model, eq.q);
    if (k == 0 && target.method == PlanMethod::MinimumTime && !target.obstacles.empty())
      plan.lift_body = liftBody(target, plan.map, scene, model, eq.q);
    if (k != 0 && k != n - 1) continue;
    (k == 0 ? plan.hanging_length_start : plan.hanging_length_end) = hangingLength(model, eq.q, target.controls);
    (k == 0 ? pendulum.hoist_start : pendulum.hoist_end) = c.hoist_length;
    if (target.method != PlanMethod::QuasiStatic) {
      const SwayPeriods periods = swayPeriods(model, eq.q, eq.t, target.controls, target.slewing.has_value());
      (k == 0 ? plan.sway_period_start : plan.sway_period_end) = periods.along;
      (k == 0 ? plan.sway_period_across_start : plan.sway_period_across_end) = target.slewing ? periods.across : periods.along;
    }
  }
  checkEndsClear(target, plan.plane);
  // Between the path's ends the sway period changes with the rope (Table 8-2: 15.5 → 12.0 s); the
  // mean puts the shaper's period error at either end near half that range.
  plan.sway_period = 0.5 * (plan.sway_period_start + plan.sway_period_end);
  plan.inversion_s = secondsSince(t0);
  double worst = 0.0;
  for (const InversionCheck& c : plan.inversion_checks) worst = std::max(worst, c.error);
  say(fmt::format("inversion: map(inverse(p)) − p ≤ {:.3g} m at {} trajectory points", worst, plan.inversion_checks.size()));

  // 5. The path: the QR trajectory, it input-shaped for the sway period, or the load's
  // rest-to-rest path.
  plan.path = plan.trajectory;
  if (startsFromFlatness(target.method)) {
    const double gravity = -target.scene.gravity.z();
    for (auto [period, length] : {std::pair{plan.sway_period_start, &pendulum.length_start},
                                  std::pair{plan.sway_period_end, &pendulum.length_end},
                                  std::pair{plan.sway_period_across_start, &pendulum.across_start},
                                  std::pair{plan.sway_period_across_end, &pendulum.across_end}})
      *length = pendulumLength(period, gravity);
    plan.pendulum_length_start = pendulum.length_start;
    plan.pendulum_length_end = pendulum.length_end;
    plan.pendulum_across_start = pendulum.across_start;
    plan.pendulum_across_end = pendulum.across_end;
    plan.load_path = restToRestPath(problem, problem.steps * problem.sample_time);
    plan.path = sampleTrajectory(plan.load_path, problem.sample_time);
    say(fmt::format("flatness: rest-to-rest path over {:.4g} s with {:.4g} s ramps; the load's pendulum {:.4g} → {:.4g} m "
                    "(sway periods {:.4g} → {:.4g} s; hanging lengths {:.4g} → {:.4g} m)",
                    plan.load_path.duration(), plan.load_path.ramp(), pendulum.length_start, pendulum.length_end,
                    plan.sway_period_start, plan.sway_period_end, plan.hanging_length_start, plan.hanging_length_end));
  } else if (target.method != PlanMethod::QuasiStatic) {
    plan.shaper = makeShaper(target.method == PlanMethod::ZV ? ShaperKind::ZV : ShaperKind::ZVD, plan.sway_period);
    plan.path = shapeTrajectory(plan.trajectory, plan.shaper);
    say(fmt::format("input shaping: {} impulses over {:.4g} s for the mean sway period {:.4g} s ({:.4g} s at the start, "
                    "{:.4g} s at the end; hanging length {:.4g} → {:.4g} m); motion {:.4g} s",
                    plan.shaper.times.size(), plan.shaper.duration(), plan.sway_period, plan.sway_period_start,
                    plan.sway_period_end, plan.hanging_length_start, plan.hanging_length_end,
                    plan.path.t.back() - plan.path.t.front()));
  }

  // 6. Control trajectory (6.4), for flatness over a path stretched until its drives keep their
  // limits: rates scale as 1/T, accelerations 1/T², jerks 1/T³ (were the path's shape kept), so
  // the duration grows by the limits' factor until they hold, and is bisected back to 0.1 %.
  t0 = Clock::now();
  computeControls(target, plan, pendulum);
  if (startsFromFlatness(target.method) && plan.drive_limit_factor > 1.0) {
    const auto flatPath = [&](double duration) {
      plan.load_path = restToRestPath(problem, duration);
      plan.path = sampleTrajectory(plan.load_path, problem.sample_time);
      computeControls(target, plan, pendulum);
      return plan.drive_limit_factor;
    };
    const double horizon = plan.load_path.duration();
    double low = horizon, high = horizon * std::max(1.01, plan.drive_limit_factor);
    for (double factor = flatPath(high); factor > 1.0; factor = flatPath(high)) low = high, high *= std::max(1.01, factor);
    while (high - low > 1e-3 * high) {
      const double middle = 0.5 * (low + high);
      (flatPath(middle) > 1.0 ? low : high) = middle;
    }
    flatPath(high);
    plan.stretched_from = horizon;
    say(fmt::format("flatness: the path stretched from {:.4g} s to {:.4g} s to keep the drive limits", horizon, high));
  }
  plan.controls_s = secondsSince(t0);

  // 7. The minimum-time lift, started from the flatness plan.
  if (target.method == PlanMethod::MinimumTime) {
    plan.pendulum_map = measurePendulumMap(target.scene, target.controls, plan.map, target.slewing.has_value(),
                                           -target.scene.gravity.z(), {}, plan.map.threads);
    const PendulumMap& m = *plan.pendulum_map;
    say(fmt::format("pendulum: {} modal analyses over {} × {} map points in {:.3g} s; ℓ along {:.4g} … {:.4g} m, across "
                    "{:.4g} … {:.4g} m; fit residual ≤ {:.3g} m",
                    m.modal_analyses, m.along.u.size(), m.along.v.size(), m.time_s, m.along.values.minCoeff(),
                    m.along.values.maxCoeff(), m.across.values.minCoeff(), m.across.values.maxCoeff(),
                    std::max(m.along_fit.maxResidual(), m.across_fit.maxResidual())));
    const ControlPoint &first = plan.controls.front(), &last = plan.controls.back();
    say(fmt::format("pendulum: ℓ along at the start {:.4g} m, at the target {:.4g} m (their own modal analyses {:.4g}, {:.4g} m)",
                    m.along_fit(first.boom_angle_deg, first.hoist_change), m.along_fit(last.boom_angle_deg, last.hoist_change),
                    plan.pendulum_length_start, plan.pendulum_length_end));
    LiftProblem problem = liftProblem(target, plan);
    checkLiftEndsClear(target, problem);
    const LiftStart start = liftStart(target, plan, problem);
    try {
      plan.lift = solveMinimumTimeLift(problem, start.guess);
    } catch (const LiftBlocked& e) {
      const Obstacle& o = target.obstacles[e.closest.obstacle];
      throw SceneError(o.where, fmt::format("no lift within the map and the drive limits found that clears obstacle '{}' by {:.3g} m "
                                            "(the clearance margin {:.3g} m and the allowance {:.3g} m): the solver ({}) stopped "
                                            "with the {} {:.3g} m from it at t = {:.3g} s",
                                            o.name, problem.clearance_margin, target.clearance_margin,
                                            target.minimum_time.clearance_allowance, e.what(), liftPartName(e.closest.part),
                                            e.closest.clearance, e.t));
    }
    const double flat = plan.load_path.duration();
    liftControls(target, plan);
    say(fmt::format("minimum time: {:.4g} s instead of the flatness path's {:.4g} s ({} intervals, {} Ipopt iterations in {:.3g} s, "
                    "started from {} of {:.4g} s)",
                    plan.lift->final_time, flat, target.minimum_time.intervals, plan.lift->iterations, plan.lift->solve_time_s,
                    start.from, start.guess.final_time));
    if (!problem.obstacles.empty())
      say(fmt::format("minimum time: the lift's parts clear the obstacles by ≥ {:.3g} m at its nodes (asked {:.3g} m)",
                      *std::min_element(plan.lift->clearance.begin(), plan.lift->clearance.end()), problem.clearance_margin));
  }
  if (target.slewing_axis) {
    const Eigen::Vector2d pick = radiusAndHeight(target, plan, plan.controls.front()), set = radiusAndHeight(target, plan, plan.controls.back());
    say(fmt::format("lift: from a radius of {:.3f} m and a height of {:.3f} m (boom {:.2f}°) to {:.3f} m and {:.3f} m (boom {:.2f}°), "
                    "radii from the axis of '{}'",
                    pick.x(), pick.y(), plan.controls.front().boom_angle_deg, set.x(), set.y(), plan.controls.back().boom_angle_deg,
                    target.slewing_axis->constraint));
  }
  if (target.drive_limits.any())
    say(fmt::format("drive limits: {} (largest peak / limit, as duration factor: {:.3g})",
                    plan.drive_limit_factor <= 1.0 ? "kept" : "EXCEEDED by the " + methodName(target.method) + " path",
                    plan.drive_limit_factor));
  say(fmt::format("drive peaks (speed / acceleration / jerk): luffing rope {:.3g} m/s / {:.3g} m/s² / {:.3g} m/s³, hoist rope "
                  "{:.3g} / {:.3g} / {:.3g}",
                  plan.luffing_peaks.speed, plan.luffing_peaks.acceleration, plan.luffing_peaks.jerk, plan.hoist_peaks.speed,
                  plan.hoist_peaks.acceleration, plan.hoist_peaks.jerk));
  if (target.slewing) {
    constexpr double deg = 180.0 / std::numbers::pi;
    say(fmt::format("slewing: '{}' turns by {:.4g}° (peaks {:.3g}°/s, {:.3g}°/s², {:.3g}°/s³)", target.slewing->constraint,
                    target.slewing->turn * deg, plan.slewing_peaks.speed * deg, plan.slewing_peaks.acceleration * deg,
                    plan.slewing_peaks.jerk * deg));
  }
  return plan;
}

Eigen::Vector2d radiusAndHeight(const TargetSpec& target, const QuasiStaticPlan& plan, const ControlPoint& c) {
  const double x = plan.fit.fx(c.boom_angle_deg, c.hoist_change), z = plan.fit.fz(c.boom_angle_deg, c.hoist_change);
  return {target.slewing_axis->radiusAt(x), z};
}

Scene verificationScene(const TargetSpec& target, const QuasiStaticPlan& plan) {
  Scene scene = withControls(target.scene, target.controls, Profile(plan.luffing_spline), Profile(plan.hoist_spline));
  scene.solver.t_start = 0.0;
  scene.solver.t_end = plan.luffing_spline.t.back() + target.settle_time;
  scene.solver.start_from_equilibrium = true;
  if (target.slewing)
    for (ConstraintSpec& c : scene.constraints)
      if (c.name == target.slewing->constraint) c.drive = Profile(plan.slewing_spline);
  if (target.verification_rtol) scene.solver.rtol = *target.verification_rtol;
  if (target.verification_atol) scene.solver.atol = *target.verification_atol;
  scene.name += " — quasi-static plan verification";
  return scene;
}

void verifyPlan(const TargetSpec& target, QuasiStaticPlan& plan, const std::string& results_path, const PlanLog& log) {
  const auto t0 = Clock::now();
  const Scene scene = verificationScene(target, plan);
  const Model model = compileModel(scene);
  const Assembler assembler(model);
  const StaticResult eq = equilibriumUnder(scene, model, 0.0, plan.controls.front());
  const DynamicState initial =
      consistentInitialState(assembler, 0.0, eq.q, VecX::Zero(model.nv), model.solver.assembly_tolerance);
  ResultsRecorder recorder(assembler);
  Verification& v = plan.verification;
  v.outcome = simulate(assembler, initial, recorder);
  if (!results_path.empty())
    recorder.write(results_path, {target.path, scene.text, "ggl", scene.solver.t_end}, v.outcome);

  const Eigen::Vector2d origin = target.origin;
  const std::vector<double>& end = recorder.jointPositions(model.findJoint(target.controls.end_point));
  const double motion_end = plan.lead_time + plan.path.t.back();
  const double settled = plan.luffing_spline.t.back();
  double sum = 0.0;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector2d> settling;  // horizontal positions after the motion
  int during = 0;
  for (std::size_t k = 0; k < recorder.samples(); ++k) {
    const double t = recorder.time()[k];
    const Eigen::Vector3d p(end[3 * k], end[3 * k + 1], end[3 * k + 2]);
    const Eigen::Vector2d point = origin + trajectoryAt(plan.path, t - plan.lead_time);
    const Eigen::Vector3d planned = plan.plane.place(point.x(), point.y(), slewingAt(target, plan, t - plan.lead_time)(0));
    v.t.push_back(t);
    v.planned.push_back(planned);
    v.simulated.push_back(p);
    const double error = (p - planned).norm();
    if (t >= plan.lead_time && t <= motion_end) {
      v.max_error = std::max(v.max_error, error);
      sum += error * error;
      ++during;
    }
    if (t >= settled) {
      settling.push_back(p.head<2>());
      mean += p;
    }
  }
  v.rms_error = during > 0 ? std::sqrt(sum / during) : 0.0;
  const Eigen::Vector2d goal = origin + target.trajectory.target.head<2>();
  const Vec3 goal_point = plan.plane.place(goal.x(), goal.y(), target.slewing ? target.slewing->turn : 0.0);
  for (std::size_t k = 0; k < v.t.size(); ++k)
    if (v.t[k] >= motion_end && v.t[k] <= motion_end + 10.0)
      v.arrival_sway = std::max(v.arrival_sway, (v.simulated[k] - goal_point).head<2>().norm());
  if (!settling.empty()) {
    v.residual_sway = halfHorizontalExtent(settling);
    v.final_error = (mean / static_cast<double>(settling.size()) - goal_point).norm();
  }
  if (!target.obstacles.empty())
    plan.clearance = measureClearance(target.obstacles, craneParts(scene, model, target.controls.end_point, target.load_radius),
                                      recorder, target.clearance_margin);
  plan.verification_s = secondsSince(t0);
  if (log)
    log(fmt::format("verification: {:.1f} s simulated in {:.1f} s; tracking error max {:.3g} m, RMS {:.3g} m; "
                    "within 10 s of the arrival ≤ {:.3g} m from the target; residual sway ±{:.3g} m, final error {:.3g} m",
                    v.outcome.t_reached, plan.verification_s, v.max_error, v.rms_error, v.arrival_sway, v.residual_sway,
                    v.final_error));
  if (log && plan.clearance)
    log(fmt::format("clearance: {} parts × {} obstacles at {} samples (at most {:.3g} s apart) in {:.3g} s", plan.clearance->parts.size(),
                    plan.clearance->obstacles.size(), plan.clearance->samples, plan.clearance->largest_interval,
                    plan.clearance->compute_s));
  if (!v.outcome.complete) throw std::runtime_error("verification run stopped: " + v.outcome.message);
}

}  // namespace cranesim
