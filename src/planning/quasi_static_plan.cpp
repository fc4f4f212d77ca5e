#include "cranesim/planning/quasi_static_plan.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

#include "cranesim/io/results_writer.hpp"
#include "cranesim/model/compile.hpp"
#include "cranesim/planning/control_trajectory.hpp"
#include "cranesim/planning/flat_pendulum.hpp"
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

/// The load's pendulum for the flat map: the simple pendulum of the crane's sway period, its
/// length affine in the hoist rope's length between the path's start and end equilibria (as
/// the hanging length is, for a rope of fixed reeving).
struct EffectivePendulum {
  double hoist_start = 0.0, hoist_end = 0.0, length_start = 0.0, length_end = 0.0;

  double length(double hoist) const {
    if (std::abs(hoist_end - hoist_start) < 1e-9) return 0.5 * (length_start + length_end);
    return length_start + (length_end - length_start) * (hoist - hoist_start) / (hoist_end - hoist_start);
  }
};

/// The controls that carry the load along the flat path at time t: the map's controls at the
/// point where the load would hang at rest from the suspension that carries it
/// (planning/flat_pendulum.hpp: restingPoint), whose pendulum length depends on the hoist rope
/// those controls set: a fixed point, contracting by about ℓ'·‖e − ẑ‖ ≈ 1e-2 per iteration.
ControlPoint flatControls(const TargetSpec& target, const QuasiStaticPlan& plan, const EffectivePendulum& pendulum, double t) {
  const Eigen::Vector2d p = plan.load_path.derivative(t, 0), a = plan.load_path.derivative(t, 2);
  const double gravity = -target.scene.gravity.z();
  EndState resting = EndState::Zero();
  resting.head<2>() = p;
  ControlPoint c = pathControls(target, plan, resting);
  for (int iteration = 0; iteration < 50; ++iteration) {
    const Eigen::Vector2d next = restingPoint(p, a, pendulum.length(c.hoist_length), gravity);
    const double change = (next - resting.head<2>()).norm();
    resting.head<2>() = next;
    c = pathControls(target, plan, resting);
    if (change < 1e-10) return c;
  }
  throw std::runtime_error(fmt::format("flatness: the resting point at t = {:.4g} s does not converge", t));
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
    if (k != 0 && k != n - 1) continue;
    (k == 0 ? plan.hanging_length_start : plan.hanging_length_end) = hangingLength(model, eq.q, target.controls);
    (k == 0 ? pendulum.hoist_start : pendulum.hoist_end) = c.hoist_length;
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

  // 5. The path: the QR trajectory, it input-shaped for the sway period, or the load's
  // rest-to-rest path.
  plan.path = plan.trajectory;
  if (target.method == PlanMethod::Flatness) {
    const double gravity = -target.scene.gravity.z();
    for (auto [period, length] : {std::pair{plan.sway_period_start, &pendulum.length_start},
                                  std::pair{plan.sway_period_end, &pendulum.length_end}})
      *length = gravity * std::pow(period / (2.0 * std::numbers::pi), 2);
    plan.pendulum_length_start = pendulum.length_start;
    plan.pendulum_length_end = pendulum.length_end;
    plan.load_path = restToRestPath(problem);
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

  // 6. Control trajectory (6.4).
  t0 = Clock::now();
  std::vector<double> luffing, hoist;
  for (std::size_t k = 0; k < plan.path.states.size(); ++k) {
    const ControlPoint c = target.method == PlanMethod::Flatness ? flatControls(target, plan, pendulum, plan.path.t[k])
                                                                 : pathControls(target, plan, plan.path.states[k]);
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
