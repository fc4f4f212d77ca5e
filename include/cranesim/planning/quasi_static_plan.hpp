#pragma once
// Quasi-static optimal control (thesis chapter 6, 8.4): static map → fitted surfaces → QR
// end-point trajectory → control trajectory → verification by simulating the crane.

#include <functional>
#include <string>
#include <vector>

#include "cranesim/math/profile.hpp"
#include "cranesim/planning/clearance.hpp"
#include "cranesim/planning/control_trajectory.hpp"
#include "cranesim/planning/input_shaping.hpp"
#include "cranesim/planning/minimum_time_lift.hpp"
#include "cranesim/planning/pendulum_map.hpp"
#include "cranesim/planning/rest_to_rest_path.hpp"
#include "cranesim/planning/slewing_plane.hpp"
#include "cranesim/planning/target.hpp"
#include "cranesim/solvers/dynamics.hpp"

namespace cranesim {

/// The map's surfaces over (boom angle °, hoist change m) (6.2).
struct MapFit {
  GridData x, z, luffing;  // end point x, z and the luffing rope's unstretched length
  FittedSurface fx, fz, fluffing;
};

MapFit fitStaticMap(const StaticMap& map, const SurfaceSpec& spec);

/// One point of the control trajectory: where the map puts an end point.
struct ControlPoint {
  double boom_angle_deg = 0.0, hoist_change = 0.0;
  double luffing_length = 0.0, hoist_length = 0.0;
};

/// The map inverted at an end point (absolute crane coordinates x, z); throws std::domain_error
/// outside the map.
ControlPoint controlsAt(const MapFit& fit, const StaticMap& map, double x, double z);

/// map(inverse(p)) − p: the crane's equilibrium under the controls that the fitted map gives for p.
struct InversionCheck {
  double t = 0.0;                     // trajectory time of p
  Eigen::Vector2d planned, reached;   // absolute end point (x, z)
  double error = 0.0;                 // ‖reached − planned‖, m
};

struct Verification {
  std::vector<double> t;                        // simulation time (the motion starts at lead_time)
  std::vector<Eigen::Vector3d> planned;         // planned end point (world x, y, z) at t
  std::vector<Eigen::Vector3d> simulated;       // simulated end point (world x, y, z)
  double max_error = 0.0, rms_error = 0.0;      // tracking error during the motion, m
  /// Half the peak-to-peak horizontal motion after the motion (half the largest horizontal
  /// distance between two samples: the sway's amplitude in whichever direction it swings), m.
  double residual_sway = 0.0;
  /// The largest horizontal distance from the target within 10 s after the planned arrival, m.
  double arrival_sway = 0.0;
  double final_error = 0.0;                     // mean end point after the motion − target, m
  SimulationOutcome outcome;
};

struct QuasiStaticPlan {
  StaticMap map;
  MapFit fit;
  QrTrajectory trajectory;                 // relative to the target's origin
  /// The end-point path the controls follow (relative to the origin): the QR trajectory
  /// (method quasi_static), the trajectory shaped by `shaper` (zv, zvd), or `load_path` sampled
  /// at the QR problem's sample time (flatness).
  QrTrajectory path;
  InputShaper shaper;                      // no impulses for quasi_static
  RestToRestPath load_path;                // flatness only
  /// The pendulum at the path's start and end equilibria: from the hoist rope's end at the boom
  /// head to the end point, m.
  double hanging_length_start = 0.0, hanging_length_end = 0.0;
  /// Shaped and flatness methods: the crane's sway period in its plane at the start and end
  /// equilibria (its lowest mode in which the end point moves mostly along x), s; the shaper's
  /// period is their mean.
  double sway_period_start = 0.0, sway_period_end = 0.0, sway_period = 0.0;
  /// The same across the plane (its lowest mode swaying along y) for a slewing target, along it
  /// otherwise, s.
  double sway_period_across_start = 0.0, sway_period_across_end = 0.0;
  /// Flatness only: the simple pendulums of those periods, g (T / 2π)², m; between them the
  /// pendulum's length is interpolated linearly in the hoist rope's length.
  double pendulum_length_start = 0.0, pendulum_length_end = 0.0;
  /// The same across the plane (flatness and minimum_time).
  double pendulum_across_start = 0.0, pendulum_across_end = 0.0;
  /// minimum_time only: the load's pendulum over the map, which the lift carries it on.
  std::optional<PendulumMap> pendulum_map;
  /// minimum_time only: the lift the controls follow (planning/minimum_time_lift.hpp), started
  /// from the flatness path of `load_path`'s duration.
  std::optional<LiftTrajectory> lift;
  /// minimum_time: the crane's parts the lift keeps clear of obstacles, at the start's equilibrium.
  LiftBody lift_body;
  /// minimum_time with slewing: the slewing angle that turns the map's plane onto the load at
  /// each path point (the load sways across the plane, so it differs from the drive's), rad.
  std::vector<double> path_turns;
  std::vector<ControlPoint> controls;      // per path point
  TableProfile luffing_spline, hoist_spline;
  /// The map's plane and how it turns (a plane that does not turn without a slewing target).
  SlewingPlane plane;
  /// Slewing targets: the slewing angle per path point relative to the scene's (rad) and the
  /// drive's control spline (absolute, rad).
  std::vector<double> slewing_angles;
  TableProfile slewing_spline;
  /// What the control splines ask of the drives (planning/control_trajectory.hpp), and the factor
  /// by which the motion would have to last longer to keep the target's drive limits (≤ 1: kept;
  /// 0 without limits). Flatness stretches its path to keep them: its duration before, s (0 when
  /// not stretched).
  RatePeaks luffing_peaks, hoist_peaks, slewing_peaks;
  double drive_limit_factor = 0.0;
  double stretched_from = 0.0;
  double lead_time = 0.0;                  // steady time before the motion in the splines and the simulation
  std::vector<InversionCheck> inversion_checks;
  Verification verification;
  /// The verified motion's clearance from the target's obstacles (none without obstacles).
  std::optional<ClearanceRecord> clearance;
  /// The target's feedback cases, each open and closed loop (planning/plan_tracking.hpp).
  std::vector<TrackingRun> tracking;
  double tracking_s = 0.0;
  double map_s = 0.0, fit_s = 0.0, trajectory_s = 0.0, controls_s = 0.0, inversion_s = 0.0, verification_s = 0.0;
};

using PlanLog = std::function<void(const std::string&)>;

/// Fit, trajectory, control trajectory and the inversion checks on the target's static map
/// (computeStaticMap). Throws SceneError (bad input: a start or target outside the map) or
/// std::runtime_error (a solver failure, failed map points).
QuasiStaticPlan planQuasiStatic(const TargetSpec& target, StaticMap map, const PlanLog& log = {});

/// Simulates the crane driven by the plan's control splines (8.4.3) and fills
/// plan.verification and, with obstacles, plan.clearance; writes the run as a crane-sim results file when `results_path` is given.
void verifyPlan(const TargetSpec& target, QuasiStaticPlan& plan, const std::string& results_path, const PlanLog& log = {});

/// The verification scene: the target's scene with its ropes driven by the control splines,
/// from t = 0 to the end of the splines plus the settle time.
Scene verificationScene(const TargetSpec& target, const QuasiStaticPlan& plan);

/// The end point's radius from the target's slewing axis and its height, m, where it rests under
/// the controls c (the fitted map); the target must have a slewing axis.
Eigen::Vector2d radiusAndHeight(const TargetSpec& target, const QuasiStaticPlan& plan, const ControlPoint& c);

}  // namespace cranesim
