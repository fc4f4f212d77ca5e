#include "cranesim/planning/quasi_static_plan.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "cranesim/io/results_writer.hpp"
#include "cranesim/model/compile.hpp"
#include "cranesim/planning/control_trajectory.hpp"
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

/// The pendulum the load hangs on: from the hoist rope's end farther from the end point (where
/// the rope leaves the boom head) to the end point, at the configuration q.
double hangingLength(const Model& model, const VecX& q, const CraneControls& controls) {
  const Vec3 end = model.jointFrame(q.data(), model.findJoint(controls.end_point)).r;
  double length = 0.0;
  for (const char* side : {".start", ".end"})
    length = std::max(length, (model.jointFrame(q.data(), model.findJoint(controls.hoist_rope + side)).r - end).norm());
  return length;
}

/// The period of the load's sway in the crane's plane about the equilibrium q: the crane's
/// lowest elastic mode in which the end point's node moves mostly along x (the plane's
/// horizontal). It includes what the simple pendulum misses: the load's own inertia below the
/// hook, the rope's mass and stretch and the boom's compliance.
double swayPeriod(const Model& model, const VecX& q, double t, const CraneControls& controls) {
  const ModalResult modes = computeModes(model, q, t, 0);
  const Node& node = model.nodes[model.joints[model.findJoint(controls.end_point)].node];
  for (Eigen::Index k = 0; k < modes.frequencies.size(); ++k) {
    if (modes.rigid[k] || modes.omega_squared(k) <= 0.0) continue;
    const Eigen::Vector3d v = modes.shapes.col(k).segment<3>(node.v).cwiseAbs();
    if (v.x() > v.y() && v.x() > v.z()) return 1.0 / modes.frequencies(k);
  }
  throw std::runtime_error(fmt::format("input shaping: no mode of the crane sways '{}' in its plane", controls.end_point));
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
  const Eigen::Vector2d uv = invertSurfaces(fit.fx, fit.fz, fit.x, fit.z, x, z);
  ControlPoint c;
  c.boom_angle_deg = uv(0);
  c.hoist_change = uv(1);
  c.luffing_length = fit.fluffing(uv(0), uv(1));
  c.hoist_length = map.hoist_length - uv(1);  // exact: the hoist change is the map's own variable
  return c;
}

namespace {

/// The controls of a path state (relative to the origin); leaving the map is bad input.
ControlPoint pathControls(const TargetSpec& target, const QuasiStaticPlan& plan, const EndState& s) {
  try {
    return controlsAt(plan.fit, plan.map, target.origin(0) + s(0), target.origin(1) + s(1));
  } catch (const std::domain_error& e) {
    throw SceneError(target.where_trajectory, fmt::format("the planned trajectory leaves the static map: {}", e.what()));
  }
}

}  // namespace

QuasiStaticPlan planQuasiStatic(const TargetSpec& target, const PlanLog& log) {
  const auto say = [&](const std::string& line) {
    if (log) log(line);
  };
  QuasiStaticPlan plan;
  const QrProblem& problem = target.trajectory;
  const Eigen::Vector2d origin = target.origin;

  // 1. Static map (6.2).
  auto t0 = Clock::now();
  plan.map = computeStaticMap(target.scene, target.controls, target.map, log);
  plan.map_s = secondsSince(t0);
  if (!plan.map.failures.empty())
    throw std::runtime_error(fmt::format("{} static map points failed; the first: {}", plan.map.failures.size(),
                                         plan.map.failures.front()));
  say(fmt::format("static map: {} × {} equilibria in {:.1f} s ({} Jacobian factorisations, {} threads)",
                  plan.map.rows(), plan.map.columns(), plan.map_s, plan.map.jacobians, plan.map.threads));

  // 2. Fitted surfaces.
  t0 = Clock::now();
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
    if (k != 0 && k != n - 1) continue;
    (k == 0 ? plan.hanging_length_start : plan.hanging_length_end) = hangingLength(model, eq.q, target.controls);
    if (target.method != PlanMethod::QuasiStatic)
      (k == 0 ? plan.sway_period_start : plan.sway_period_end) = swayPeriod(model, eq.q, eq.t, target.controls);
  }
  // Between the path's ends the sway period changes with the rope (Table 8-2: 15.5 → 12.0 s); the
  // mean puts the shaper's period error at either end near half that range.
  plan.sway_period = 0.5 * (plan.sway_period_start + plan.sway_period_end);
  plan.inversion_s = secondsSince(t0);
  double worst = 0.0;
  for (const InversionCheck& c : plan.inversion_checks) worst = std::max(worst, c.error);
  say(fmt::format("inversion: map(inverse(p)) − p ≤ {:.3g} m at {} trajectory points", worst, plan.inversion_checks.size()));

  // 5. The path: the QR trajectory, or it input-shaped for the sway period.
  plan.path = plan.trajectory;
  if (target.method != PlanMethod::QuasiStatic) {
    plan.shaper = makeShaper(target.method == PlanMethod::ZV ? ShaperKind::ZV : ShaperKind::ZVD, plan.sway_period);
    plan.path = shapeTrajectory(plan.trajectory, plan.shaper);
    say(fmt::format("input shaping: {} impulses over {:.4g} s for the mean sway period {:.4g} s ({:.4g} s at the start, "
                    "{:.4g} s at the end; hanging length {:.4g} → {:.4g} m); motion {:.4g} s",
                    plan.shaper.times.size(), plan.shaper.duration(), plan.sway_period, plan.sway_period_start,
                    plan.sway_period_end, plan.hanging_length_start, plan.hanging_length_end,
                    plan.path.t.back() - plan.path.t.front()));
  }

  // 6. Control trajectory (6.4).
  t0 = Clock::now();
  std::vector<double> luffing, hoist;
  for (const EndState& s : plan.path.states) {
    const ControlPoint c = pathControls(target, plan, s);
    plan.controls.push_back(c);
    luffing.push_back(c.luffing_length);
    hoist.push_back(c.hoist_length);
  }
  plan.luffing_spline = smoothControlTrajectory(plan.path.t, luffing, target.resample_points, target.steady_points);
  plan.hoist_spline = smoothControlTrajectory(plan.path.t, hoist, target.resample_points, target.steady_points);
  plan.lead_time = plan.luffing_spline.t[target.steady_points] - plan.path.t.front();
  plan.controls_s = secondsSince(t0);
  return plan;
}

Scene verificationScene(const TargetSpec& target, const QuasiStaticPlan& plan) {
  Scene scene = withControls(target.scene, target.controls, Profile(plan.luffing_spline), Profile(plan.hoist_spline));
  scene.solver.t_start = 0.0;
  scene.solver.t_end = plan.luffing_spline.t.back() + target.settle_time;
  scene.solver.start_from_equilibrium = true;
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
  double sum = 0.0, x_min = std::numeric_limits<double>::infinity(), x_max = -x_min;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  int during = 0, after = 0;
  for (std::size_t k = 0; k < recorder.samples(); ++k) {
    const double t = recorder.time()[k];
    const Eigen::Vector3d p(end[3 * k], end[3 * k + 1], end[3 * k + 2]);
    const Eigen::Vector2d planned = origin + trajectoryAt(plan.path, t - plan.lead_time);
    v.t.push_back(t);
    v.planned.push_back(planned);
    v.simulated.push_back(p);
    const double error = (Eigen::Vector2d(p.x(), p.z()) - planned).norm();
    if (t >= plan.lead_time && t <= motion_end) {
      v.max_error = std::max(v.max_error, error);
      sum += error * error;
      ++during;
    }
    if (t >= settled) {
      x_min = std::min(x_min, p.x());
      x_max = std::max(x_max, p.x());
      mean += Eigen::Vector2d(p.x(), p.z());
      ++after;
    }
  }
  v.rms_error = during > 0 ? std::sqrt(sum / during) : 0.0;
  if (after > 0) {
    v.residual_sway = 0.5 * (x_max - x_min);
    v.final_error = (mean / after - (origin + target.trajectory.target.head<2>())).norm();
  }
  plan.verification_s = secondsSince(t0);
  if (log)
    log(fmt::format("verification: {:.1f} s simulated in {:.1f} s; tracking error max {:.3g} m, RMS {:.3g} m; "
                    "residual sway ±{:.3g} m, final error {:.3g} m",
                    v.outcome.t_reached, plan.verification_s, v.max_error, v.rms_error, v.residual_sway, v.final_error));
  if (!v.outcome.complete) throw std::runtime_error("verification run stopped: " + v.outcome.message);
}

}  // namespace cranesim
