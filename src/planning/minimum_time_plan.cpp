#include "cranesim/planning/minimum_time_plan.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>


namespace cranesim {
namespace {

/// The lift keeps its drives' limits at its nodes; the control splines through the nodes
/// overshoot them between nodes by a fraction of h² (measured 0.16 % on Table 8-2 with 200
/// intervals), so the nodes keep 99 % of them.
constexpr double kNodeMargin = 0.99;
/// A cubic spline's jerk is constant on each interval, the difference of its second derivatives
/// at the ends: it meets the nodes' jerks only to O(h) (+3 % measured on Table 8-2's luffing rope
/// at 200 intervals), so the nodes keep 95 % of a jerk limit.
constexpr double kJerkNodeMargin = 0.95;

/// Central differences of samples y at times t (one-sided zero at the ends: the plan is at rest there).
template <class V> std::vector<V> rates(const std::vector<double>& t, const std::vector<V>& y) {
  std::vector<V> r(y.size(), V::Zero());
  for (std::size_t k = 1; k + 1 < y.size(); ++k) r[k] = (y[k + 1] - y[k - 1]) / (t[k + 1] - t[k - 1]);
  return r;
}

/// The height of an obstacle's top, m.
double topOf(const ObstacleShape& shape) {
  struct Top {
    double operator()(const BoxShape& b) const { return b.centre.z() + 0.5 * b.size.z(); }
    double operator()(const CylinderShape& c) const { return c.base.z() + c.height; }
    double operator()(const PrismShape& p) const { return p.top; }
  };
  return std::visit(Top{}, shape);
}

/// The node at rest at q.
LiftNode restingAt(const Eigen::Vector3d& q) {
  LiftNode node;
  node.q = q;
  return node;
}

/// The map's controls q of the load at (x, z) (map coordinates) and slewing angle φ; none outside the map.
std::optional<Eigen::Vector3d> mapControlsAt(const QuasiStaticPlan& plan, double x, double z, double phi) {
  try {
    const ControlPoint c = controlsAt(plan.fit, plan.map, x, z);
    return Eigen::Vector3d(c.boom_angle_deg, c.hoist_change, phi);
  } catch (const std::domain_error&) {
    return std::nullopt;
  }
}

}  // namespace

LiftBody liftBody(const TargetSpec& target, const StaticMap& map, const Scene& scene, const Model& model, const VecX& q) {
  const auto at = [&](int joint) { return model.jointFrame(q.data(), joint).r; };
  LiftBody body;
  body.boom_foot = at(model.findJoint(target.controls.boom_foot));
  const Vec3 head = at(model.findJoint(target.controls.boom_head));
  const Vec3 chord = head - body.boom_foot;
  body.boom_length = chord.norm();
  body.boom_out = Vec3(chord.x(), chord.y(), 0.0).normalized();
  const Vec3 along = chord / body.boom_length;
  const Vec3 up = (Vec3::UnitZ() - along.z() * along).normalized();
  const auto offChord = [&](const Vec3& x) {
    const double s = std::clamp((x - body.boom_foot).dot(along), 0.0, body.boom_length);
    return (x - body.boom_foot - s * along).norm();
  };
  constexpr double kOnChord = 0.5;  // m: a lattice section's ends lie on the boom's chord (bent by centimetres)
  for (const CranePart& part : craneParts(scene, model, target.controls.end_point, target.load_radius)) {
    if (part.name == target.controls.hoist_rope) {
      body.rope_radius = part.radius;
      const Vec3 first = at(part.joints.front()), last = at(part.joints.back());
      const Vec3 sheave = (first - head).norm() < (last - head).norm() ? first : last;
      body.sheave_along = (sheave - head).dot(along);
      body.sheave_up = (sheave - head).dot(up);
      continue;
    }
    const auto member = std::find_if(scene.members.begin(), scene.members.end(), [&](const MemberSpec& m) { return m.name == part.name; });
    if (member == scene.members.end() || member->type != MemberType::Truss) continue;
    if (std::all_of(part.joints.begin(), part.joints.end(), [&](int j) { return offChord(at(j)) < kOnChord; }))
      body.boom_radius = std::max(body.boom_radius, part.radius);
  }
  body.load_radius = target.load_radius;
  body.rope_longest = 1.05 * (map.hoist_length - map.hoist_changes.front());
  return body;
}

void checkLiftEndsClear(const TargetSpec& target, const LiftProblem& problem) {
  for (const auto& [q, where, what] :
       {std::tuple{problem.start, target.where_start, "start"}, std::tuple{problem.end, target.where_target, "target"}}) {
    const NodeClearance c = clearanceAt(problem, restingAt(q));
    if (c.clearance >= problem.clearance_margin) continue;
    const Obstacle& o = problem.obstacles[c.obstacle];
    throw SceneError(where, fmt::format("the {} at the {} is too close to obstacle '{}' (line {}) for the minimum-time lift: "
                                        "{:.3g} m, where it needs {:.3g} m (the clearance margin {:.3g} m and its allowance {:.3g} m)",
                                        liftPartName(c.part), what, o.name, o.where.line, c.clearance, problem.clearance_margin,
                                        target.clearance_margin, target.minimum_time.clearance_allowance));
  }
}

LiftProblem liftProblem(const TargetSpec& target, const QuasiStaticPlan& plan) {
  LiftProblem p;
  LiftKinematics& k = p.crane;
  k.end_x = plan.fit.fx;
  k.end_z = plan.fit.fz;
  k.luffing = plan.fit.fluffing;
  k.hoist_length = plan.map.hoist_length;
  k.slewing_start = target.slewing ? target.slewing->start : 0.0;
  k.plane = plan.plane;
  k.along_length = plan.pendulum_map->along_fit;
  k.across_length = plan.pendulum_map->across_fit;
  k.gravity = -target.scene.gravity.z();

  const double turn = target.slewing ? target.slewing->turn : 0.0;
  const ControlPoint &a = plan.controls.front(), &b = plan.controls.back();
  p.start = Eigen::Vector3d(a.boom_angle_deg, a.hoist_change, 0.0);
  p.end = Eigen::Vector3d(b.boom_angle_deg, b.hoist_change, turn);
  const double slew_range = target.slewing ? 2.0 * std::numbers::pi : 0.0;
  // The hoist rope between its lengths at the ends (liftStart widens this to its start's): the
  // pendulum is measured there and affine in the hoist rope between them, not beyond.
  p.q_min = Eigen::Vector3d(plan.map.boom_angles_deg.front(), std::min(p.start(1), p.end(1)), std::min(0.0, turn) - slew_range);
  p.q_max = Eigen::Vector3d(plan.map.boom_angles_deg.back(), std::max(p.start(1), p.end(1)), std::max(0.0, turn) + slew_range);

  const ControlLimits& limits = target.drive_limits;
  const double rise = target.minimum_time.rise_time;
  for (const auto& [drive, d] :
       {std::pair{kLuffingDrive, &limits.luffing}, std::pair{kHoistDrive, &limits.hoist}, std::pair{kSlewingDrive, &limits.slewing}}) {
    if (!d->speed) continue;  // a drive the lift does not move (readTarget requires the others' speeds)
    DriveBounds& bounds = p.drives[drive];
    bounds.speed = kNodeMargin * *d->speed;
    bounds.acceleration = kNodeMargin * d->acceleration.value_or(*d->speed / rise);
    const double jerk = d->jerk ? kJerkNodeMargin * *d->jerk : kNodeMargin * bounds.acceleration / rise;
    // The hoist rope's and the slewing drive's jerks are their coordinates' (−v⃛, φ⃛); the luffing
    // rope's is d³fl(u, v)/dt³ through the map, a constraint of its own at every node.
    (drive == kLuffingDrive ? p.luffing_jerk_limit : p.jerk_limit(drive)) = jerk;
  }
  p.intervals = target.minimum_time.intervals;
  p.tolerance = target.minimum_time.tolerance;
  if (!target.obstacles.empty()) {
    k.body = plan.lift_body;
    p.obstacles = target.obstacles;
    p.clearance_margin = target.clearance_margin + target.minimum_time.clearance_allowance;
  }
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
    const double along = k.along(c.boom_angle_deg, c.hoist_change), across = k.across(c.boom_angle_deg, c.hoist_change);
    const Vec3 offset = Eigen::AngleAxisd(-phi, Vec3::UnitZ()) * (load - resting - along * Vec3::UnitZ());
    const Vec3 n = Vec3(offset.x() / along, offset.y() / across, offset.z() / along).normalized();
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

LiftStart liftStart(const TargetSpec& target, const QuasiStaticPlan& plan, LiftProblem& problem) {
  const auto holdHoist = [&](const LiftGuess& guess) {
    for (const LiftNode& node : guess.nodes) {
      problem.q_min(1) = std::min(problem.q_min(1), node.q(1));
      problem.q_max(1) = std::max(problem.q_max(1), node.q(1));
    }
  };
  LiftGuess flat = flatnessGuess(target, plan, problem);
  const auto clears = [&](const LiftGuess& guess) {
    return std::all_of(guess.nodes.begin(), guess.nodes.end(),
                       [&](const LiftNode& n) { return clearanceAt(problem, n).clearance >= problem.clearance_margin; });
  };
  if (problem.obstacles.empty() || clears(flat)) {
    holdHoist(flat);
    return {std::move(flat), "the flatness plan"};
  }

  const Eigen::Vector2d from = target.origin + target.trajectory.start.head<2>(), to = target.origin + target.trajectory.target.head<2>();
  const double turn = problem.end(2);
  const double axis = plan.plane.axisPoint().x();
  const double in = std::abs(from.x() - axis) <= std::abs(to.x() - axis) ? from.x() : to.x();
  const auto reachable = [&](double z) {
    return mapControlsAt(plan, from.x(), z, 0.0) && mapControlsAt(plan, to.x(), z, 0.0) && mapControlsAt(plan, in, z, 0.0);
  };
  // Over the obstacles the load can clear by lifting it; around the others.
  double over = std::max(from.y(), to.y());
  for (const Obstacle& o : problem.obstacles) {
    const double above = topOf(o.shape) + problem.clearance_margin + problem.crane.body.load_radius + 1.0;
    if (above > over && reachable(above)) over = above;
  }
  std::vector<Eigen::Vector3d> waypoints = {problem.start};
  for (const auto& [x, z, phi] : {std::tuple{from.x(), over, 0.0}, std::tuple{in, over, 0.0}, std::tuple{in, over, turn},
                                  std::tuple{to.x(), over, turn}}) {
    const std::optional<Eigen::Vector3d> q = mapControlsAt(plan, x, z, phi);
    if (q && (*q - waypoints.back()).norm() > 1e-9) waypoints.push_back(*q);
  }
  waypoints.push_back(problem.end);
  LiftGuess guess = waypointGuess(problem, waypoints);
  holdHoist(guess);
  return {std::move(guess), "a lift over and around the obstacles"};
}

}  // namespace cranesim
