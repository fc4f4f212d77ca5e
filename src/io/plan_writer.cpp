#include "cranesim/io/plan_writer.hpp"

#include <numbers>

#include "cranesim/version.hpp"
#include "hdf5_file.hpp"

namespace cranesim {
namespace {

void writeMatrix(Hdf5File& file, const std::string& path, const Eigen::MatrixXd& m) {
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows = m;
  file.writeDoubles(path, {hsize_t(m.rows()), hsize_t(m.cols())}, rows.data());
}

void writeVector(Hdf5File& file, const std::string& path, const std::vector<double>& v) {
  file.writeDoubles(path, {hsize_t(v.size())}, v.data());
}

template <int N, class Points> void writePoints(Hdf5File& file, const std::string& path, const Points& points) {
  std::vector<double> flat;
  for (const auto& p : points)
    for (int k = 0; k < N; ++k) flat.push_back(p(k));
  file.writeDoubles(path, {hsize_t(points.size()), hsize_t(N)}, flat.data());
}

void writeMap(Hdf5File& file, const StaticMap& map) {
  writeVector(file, "/map/boom_angle", map.boom_angles_deg);
  writeVector(file, "/map/hoist_change", map.hoist_changes);
  writeMatrix(file, "/map/luffing_length", map.luffing_length);
  writeMatrix(file, "/map/hoist_length", map.hoist_rope_length);
  writeMatrix(file, "/map/end_x", map.end_x);
  writeMatrix(file, "/map/end_y", map.end_y);
  writeMatrix(file, "/map/end_z", map.end_z);
  writeMatrix(file, "/map/iterations", map.iterations.cast<double>());
  if (!map.failures.empty())
    file.writeStrings("/map/failures", {hsize_t(map.failures.size())}, map.failures);
  file.attribute("/map", "hoist_length_reference", map.hoist_length);
  file.attribute("/map", "jacobians", static_cast<long>(map.jacobians));
  file.attribute("/map", "threads", static_cast<long>(map.threads));
  file.attribute("/map", "execution", map.execution);
  file.attribute("/map", "start_iterations", static_cast<long>(map.start_iterations));
  file.attribute("/map", "start_time_s", map.start_time_s);
  file.attribute("/map", "sweep_time_s", map.sweep_time_s);
  file.attribute("/map", "time_s", map.time_s);
}

void writeFit(Hdf5File& file, const MapFit& fit, const SurfaceSpec& spec) {
  file.ensureGroup("/fit");
  file.attribute("/fit", "type", std::string(spec.kind == SurfaceKind::Spline ? "spline" : "polynomial"));
  if (spec.kind == SurfaceKind::Polynomial) {
    file.attribute("/fit", "order_boom_angle", static_cast<long>(spec.order_u));
    file.attribute("/fit", "order_hoist_change", static_cast<long>(spec.order_v));
  }
  for (const auto& [name, data, surface] : {std::tuple{"end_x", &fit.x, &fit.fx}, std::tuple{"end_z", &fit.z, &fit.fz},
                                            std::tuple{"luffing_length", &fit.luffing, &fit.fluffing}}) {
    Eigen::MatrixXd values(data->u.size(), data->v.size());
    for (int i = 0; i < values.rows(); ++i)
      for (int j = 0; j < values.cols(); ++j) values(i, j) = (*surface)(data->u[i], data->v[j]);
    const std::string path = std::string("/fit/") + name;
    writeMatrix(file, path, values);
    file.attribute(path, "max_residual", surface->maxResidual());
    file.attribute(path, "rms_residual", surface->rmsResidual());
  }
}

void writeTrajectory(Hdf5File& file, const TargetSpec& target, const QuasiStaticPlan& plan) {
  const QrTrajectory& tr = plan.trajectory;
  writeVector(file, "/trajectory/t", tr.t);
  writePoints<4>(file, "/trajectory/state", tr.states);
  writePoints<2>(file, "/trajectory/control", tr.controls);
  file.writeDoubles("/trajectory/origin", {2}, target.origin.data());
  file.attribute("/trajectory", "cost", tr.cost);
  file.attribute("/trajectory", "iterations", static_cast<long>(tr.iterations));
  file.attribute("/trajectory", "solve_time_s", tr.solve_time_s);
  file.attribute("/trajectory", "receding_horizon", static_cast<long>(target.trajectory.receding_horizon));
  const QrProblem& p = target.trajectory;
  writePoints<4>(file, "/trajectory/start", std::vector{p.start});
  writePoints<4>(file, "/trajectory/target", std::vector{p.target});
  writePoints<4>(file, "/trajectory/state_bounds", std::vector{p.state_min, p.state_max});
  writePoints<2>(file, "/trajectory/control_bounds", std::vector{p.control_min, p.control_max});
}

void writeControls(Hdf5File& file, const TargetSpec& target, const QuasiStaticPlan& plan) {
  std::vector<double> angle, change, luffing, hoist;
  for (const ControlPoint& c : plan.controls) {
    angle.push_back(c.boom_angle_deg);
    change.push_back(c.hoist_change);
    luffing.push_back(c.luffing_length);
    hoist.push_back(c.hoist_length);
  }
  writeVector(file, "/controls/t", plan.path.t);
  writeVector(file, "/controls/boom_angle", angle);
  writeVector(file, "/controls/hoist_change", change);
  writeVector(file, "/controls/luffing_length", luffing);
  writeVector(file, "/controls/hoist_length", hoist);
  if (target.slewing_axis) {
    std::vector<double> radius, height;
    for (const ControlPoint& c : plan.controls) {
      const Eigen::Vector2d at = radiusAndHeight(target, plan, c);
      radius.push_back(at.x());
      height.push_back(at.y());
    }
    writeVector(file, "/controls/radius", radius);
    writeVector(file, "/controls/height", height);
  }
  for (const auto& [name, spline] : {std::pair{"luffing_length", &plan.luffing_spline}, std::pair{"hoist_length", &plan.hoist_spline}}) {
    const std::string g = std::string("/controls/spline/") + name;
    writeVector(file, g + "/t", spline->t);
    writeVector(file, g + "/y", spline->y);
    writeVector(file, g + "/slopes", spline->slopes);
  }
  if (!plan.slewing_angles.empty()) {
    std::vector<double> degrees;
    for (double phi : plan.slewing_angles) degrees.push_back(phi * 180.0 / std::numbers::pi);
    writeVector(file, "/controls/slewing_angle", degrees);
    writeVector(file, "/controls/spline/slewing_angle/t", plan.slewing_spline.t);
    writeVector(file, "/controls/spline/slewing_angle/y", plan.slewing_spline.y);
    writeVector(file, "/controls/spline/slewing_angle/slopes", plan.slewing_spline.slopes);
  }
  file.attribute("/controls", "lead_time", plan.lead_time);
  for (const auto& [name, peaks] : {std::pair{"luffing", &plan.luffing_peaks}, std::pair{"hoist", &plan.hoist_peaks},
                                    std::pair{"slewing", &plan.slewing_peaks}}) {
    if (std::string(name) == "slewing" && plan.slewing_angles.empty()) continue;
    const std::string prefix = std::string(name) + "_peak_";
    file.attribute("/controls", prefix + "speed", peaks->speed);
    file.attribute("/controls", prefix + "acceleration", peaks->acceleration);
    file.attribute("/controls", prefix + "jerk", peaks->jerk);
  }
  if (target.drive_limits.any()) file.attribute("/controls", "drive_limit_factor", plan.drive_limit_factor);
}

void writePath(Hdf5File& file, const TargetSpec& target, const QuasiStaticPlan& plan) {
  writeVector(file, "/path/t", plan.path.t);
  writePoints<4>(file, "/path/state", plan.path.states);
  file.attribute("/path", "method", methodName(target.method));
  file.attribute("/path", "motion_time", plan.path.t.back() - plan.path.t.front());
  file.attribute("/path", "hanging_length_start", plan.hanging_length_start);
  file.attribute("/path", "hanging_length_end", plan.hanging_length_end);
  if (target.method != PlanMethod::QuasiStatic) {
    file.attribute("/path", "sway_period_start", plan.sway_period_start);
    file.attribute("/path", "sway_period_end", plan.sway_period_end);
    if (target.slewing) {
      file.attribute("/path", "sway_period_across_start", plan.sway_period_across_start);
      file.attribute("/path", "sway_period_across_end", plan.sway_period_across_end);
    }
    file.attribute("/path", "sway_period", plan.sway_period);
  }
  if (startsFromFlatness(target.method)) {
    file.attribute("/path", "ramp_time", plan.load_path.ramp());
    file.attribute("/path", "pendulum_length_start", plan.pendulum_length_start);
    file.attribute("/path", "pendulum_length_end", plan.pendulum_length_end);
  }
  if (plan.lift) {
    file.attribute("/path", "pendulum_across_start", plan.pendulum_across_start);
    file.attribute("/path", "pendulum_across_end", plan.pendulum_across_end);
    file.attribute("/path", "flatness_duration", plan.load_path.duration());
    file.attribute("/path", "intervals", static_cast<long>(plan.lift->t.size()) - 1);
    file.attribute("/path", "nlp_iterations", static_cast<long>(plan.lift->iterations));
    file.attribute("/path", "nlp_time_s", plan.lift->solve_time_s);
  }
  if (const auto& m = plan.pendulum_map) {
    file.attribute("/path", "pendulum_map_points", static_cast<long>(m->modal_analyses));
    file.attribute("/path", "pendulum_map_s", m->time_s);
    file.attribute("/path", "pendulum_fit_residual", std::max(m->along_fit.maxResidual(), m->across_fit.maxResidual()));
  }
  if (plan.stretched_from > 0.0) file.attribute("/path", "stretched_from", plan.stretched_from);
  if (target.slewing) {
    file.attribute("/path", "slewing_constraint", target.slewing->constraint);
    file.attribute("/path", "slewing_turn_deg", target.slewing->turn * 180.0 / std::numbers::pi);
    file.attribute("/path", "slewing_start_deg", target.slewing->start * 180.0 / std::numbers::pi);
  }
  if (!plan.shaper.times.empty()) {
    writeVector(file, "/path/impulse_times", plan.shaper.times);
    writeVector(file, "/path/impulse_amplitudes", plan.shaper.amplitudes);
  }
}

void writeVerification(Hdf5File& file, const QuasiStaticPlan& plan) {
  std::vector<double> t, planned_error;
  for (const InversionCheck& c : plan.inversion_checks) {
    t.push_back(c.t);
    planned_error.push_back(c.error);
  }
  std::vector<Eigen::Vector2d> planned, reached;
  for (const InversionCheck& c : plan.inversion_checks) {
    planned.push_back(c.planned);
    reached.push_back(c.reached);
  }
  writeVector(file, "/inversion/t", t);
  writePoints<2>(file, "/inversion/planned", planned);
  writePoints<2>(file, "/inversion/reached", reached);
  writeVector(file, "/inversion/error", planned_error);

  const Verification& v = plan.verification;
  writeVector(file, "/verification/t", v.t);
  writePoints<3>(file, "/verification/planned", v.planned);
  writePoints<3>(file, "/verification/simulated", v.simulated);
  file.attribute("/verification", "max_error", v.max_error);
  file.attribute("/verification", "rms_error", v.rms_error);
  file.attribute("/verification", "residual_sway", v.residual_sway);
  file.attribute("/verification", "arrival_sway", v.arrival_sway);
  file.attribute("/verification", "final_error", v.final_error);
  file.attribute("/verification", "status", std::string(v.outcome.complete ? "complete" : "incomplete"));
  file.attribute("/verification", "message", v.outcome.message);
  file.attribute("/verification", "t_reached", v.outcome.t_reached);
  file.attribute("/verification", "wall_time_s", v.outcome.statistics.wall_time_s);
  file.attribute("/verification", "steps", v.outcome.statistics.steps);
}

/// The feedback cases as a table, one row per run (docs/plan-format.md).
void writeTracking(Hdf5File& file, const QuasiStaticPlan& plan) {
  const std::vector<TrackingRun>& runs = plan.tracking;
  const hsize_t n = runs.size();
  std::vector<std::string> names, loops;
  std::vector<double> arrival, after, settling, tension, factor, peaks, energy, controller, wall, simulated;
  for (const TrackingRun& r : runs) {
    names.push_back(r.name);
    loops.push_back(r.closed_loop ? "closed" : "open");
    arrival.push_back(r.sway_at_arrival);
    after.push_back(r.sway_after_5_s);
    settling.push_back(r.settling_time);
    tension.push_back(r.peak_tension);
    factor.push_back(r.dynamic_factor);
    for (const auto& drive : r.peaks) peaks.insert(peaks.end(), {drive[0], drive[1]});
    energy.insert(energy.end(), r.energy, r.energy + 3);
    controller.push_back(r.samples > 0 ? r.controller_s / static_cast<double>(r.samples) : 0.0);
    wall.push_back(r.wall_s);
    simulated.push_back(r.outcome.t_reached);
  }
  file.writeStrings("/feedback/case", {n}, names);
  file.writeStrings("/feedback/loop", {n}, loops);
  writeVector(file, "/feedback/sway_at_arrival", arrival);
  writeVector(file, "/feedback/sway_after_5_s", after);
  writeVector(file, "/feedback/settling_time", settling);
  writeVector(file, "/feedback/peak_tension", tension);
  writeVector(file, "/feedback/dynamic_factor", factor);
  file.writeDoubles("/feedback/drive_peaks", {n, 3, 2}, peaks.data());
  file.writeDoubles("/feedback/drive_energy", {n, 3}, energy.data());
  writeVector(file, "/feedback/controller_s_per_sample", controller);
  writeVector(file, "/feedback/wall_time_s", wall);
  writeVector(file, "/feedback/t_reached", simulated);
}

/// Per obstacle (rows) and part (columns) the smallest signed distance over the verification run
/// and when; the smallest of all as attributes (docs/plan-format.md).
void writeClearance(Hdf5File& file, const ClearanceRecord& c) {
  file.writeStrings("/clearance/obstacle", {hsize_t(c.obstacles.size())}, c.obstacles);
  file.writeStrings("/clearance/part", {hsize_t(c.parts.size())}, c.parts);
  writeMatrix(file, "/clearance/minimum", c.minimum);
  writeMatrix(file, "/clearance/time", c.time);
  file.attribute("/clearance", "status", std::string(c.failed() ? "failed" : "clear"));
  file.attribute("/clearance", "margin", c.margin);
  file.attribute("/clearance", "distance", c.distance);
  file.attribute("/clearance", "t", c.t);
  file.attribute("/clearance", "closest_part", c.part >= 0 ? c.parts[c.part] : std::string());
  file.attribute("/clearance", "closest_obstacle", c.obstacle >= 0 ? c.obstacles[c.obstacle] : std::string());
  file.attribute("/clearance", "samples", static_cast<long>(c.samples));
  file.attribute("/clearance", "largest_interval", c.largest_interval);
  file.attribute("/clearance", "compute_s", c.compute_s);
}

}  // namespace

void writePlan(const std::string& path, const TargetSpec& target, const QuasiStaticPlan& plan, bool map_only) {
  writeResultsFile(path, [&](Hdf5File& file) {
    file.attribute("/", "engine_version", std::string(kVersion));
    file.attribute("/", "target_path", target.path);
    file.attribute("/", "target_text", target.text);
    file.attribute("/", "contents", std::string(map_only ? "map" : "plan"));
    writeMap(file, plan.map);
    if (!map_only) {
      writeFit(file, plan.fit, target.fit);
      writeTrajectory(file, target, plan);
      writePath(file, target, plan);
      writeControls(file, target, plan);
      writeVerification(file, plan);
      if (!plan.tracking.empty()) writeTracking(file, plan);
      if (plan.clearance) writeClearance(file, *plan.clearance);
    }
    file.ensureGroup("/timing");
    for (const auto& [name, seconds] : {std::pair{"map_s", plan.map_s}, std::pair{"fit_s", plan.fit_s},
                                        std::pair{"trajectory_s", plan.trajectory_s}, std::pair{"controls_s", plan.controls_s},
                                        std::pair{"inversion_s", plan.inversion_s}, std::pair{"verification_s", plan.verification_s},
                                        std::pair{"feedback_s", plan.tracking_s}})
      file.attribute("/timing", name, seconds);
  });
}

}  // namespace cranesim
