#pragma once
// The planning target of crane-opt (thesis chapter 6, 8.4, Table 8-2): which scene and which of
// its parts are the crane's controls, the static map's grid, the surface fit, the QR end-point
// problem, the smoothing of the control trajectory and the verification run.

#include <optional>
#include <string>

#include "cranesim/model/scene.hpp"
#include "cranesim/planning/obstacle.hpp"
#include "cranesim/planning/plan_tracking.hpp"
#include "cranesim/planning/qr_trajectory.hpp"
#include "cranesim/planning/slewing_axis.hpp"
#include "cranesim/planning/static_map.hpp"
#include "cranesim/planning/surface_fit.hpp"

namespace cranesim {

/// How the end-point path is planned: the thesis' quasi-static QR trajectory (6.3), that
/// trajectory input-shaped for the load's sway period (planning/input_shaping.hpp), or a
/// rest-to-rest path of the load carried by the flat map of its pendulum, or the minimum-time
/// lift of that pendulum within the drive limits, started from the flatness plan
/// (docs/planning.md).
enum class PlanMethod { QuasiStatic, ZV, ZVD, Flatness, MinimumTime };

/// Whether the method starts from the flatness path (the minimum-time lift is warm-started from it).
inline bool startsFromFlatness(PlanMethod method) { return method == PlanMethod::Flatness || method == PlanMethod::MinimumTime; }

/// The method's name in a target file.
inline std::string methodName(PlanMethod method) {
  switch (method) {
    case PlanMethod::ZV: return "zv";
    case PlanMethod::ZVD: return "zvd";
    case PlanMethod::Flatness: return "flatness";
    case PlanMethod::MinimumTime: return "minimum_time";
    case PlanMethod::QuasiStatic: break;
  }
  return "quasi_static";
}

/// A slewing motion planned with the path (docs/planning.md): the revolute constraint about the vertical
/// that turns the crane, and the angle it turns by from its value at the scene's start.
struct SlewingSpec {
  std::string constraint;
  double turn = 0.0;   // rad
  double start = 0.0;  // the drive's value at the scene's t_start (the map's slewing angle), rad
  SourceLocation where;
};

/// Limits on what a control's drive may be asked (winch or slewing motor): the peaks of its
/// control spline's rate, acceleration and jerk (m/s, m/s², m/s³; rad/s, … for the slewing).
/// Unset: unbounded.
struct DriveLimits {
  std::optional<double> speed, acceleration, jerk;
  bool any() const { return speed || acceleration || jerk; }
};

struct ControlLimits {
  DriveLimits luffing, hoist, slewing;
  SourceLocation where;
  bool any() const { return luffing.any() || hoist.any() || slewing.any(); }
};

/// The minimum-time lift's collocation (planning/minimum_time_lift.hpp) and smoothness: a drive
/// without an acceleration limit is held to speed / rise_time, a drive without a jerk limit to
/// acceleration / rise_time. With obstacles the lift plans for the clearance margin plus
/// `clearance_allowance`: what its rigid crane and pendulum miss of the verified flexible crane.
struct MinimumTimeSpec {
  int intervals = 200;
  double rise_time = 2.0;   // s
  double tolerance = 1e-6;  // Ipopt's
  double clearance_allowance = 0.2;  // m
  SourceLocation where;
};

struct TargetSpec {
  std::string path, text;
  Scene scene;
  CraneControls controls;
  SourceLocation where_controls;
  StaticMapSpec map;
  SurfaceSpec fit;
  /// The QR problem in trajectory coordinates: (x, z) of the end point relative to `origin`
  /// (crane frame: x horizontal in the boom's plane, z up), and their rates.
  QrProblem trajectory;
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  SourceLocation where_start, where_target, where_trajectory;
  /// The slewing axis the end point's radius is measured from (`pick`, `set`, /controls/radius),
  /// when the target slews or the scene's crane block names its slewing constraint.
  std::optional<SlewingAxis> slewing_axis;
  PlanMethod method = PlanMethod::QuasiStatic;
  std::optional<SlewingSpec> slewing;
  /// Flatness stretches its path's duration until every control spline keeps these, minimum_time
  /// plans within them; the other methods report whether theirs do.
  ControlLimits drive_limits;
  MinimumTimeSpec minimum_time;
  int resample_points = 20;  // 6.4: knots taken at equal times from the discrete controls
  int steady_points = 5;     // 6.4: steady-state knots added before and after
  double settle_time = 20.0;  // verification: simulated time after the motion, s
  /// The verification run's tolerances, when the target sets them (the scene's otherwise).
  std::optional<double> verification_rtol;
  std::optional<AbsoluteTolerance> verification_atol;
  /// The plan tracked by anti-sway feedback on cranes that differ from the planned one.
  std::optional<TrackingSpec> feedback;
  /// Obstacles the verified motion must clear by `clearance_margin` (docs/planning.md); the load
  /// counts as a sphere of `load_radius` about the end point.
  std::vector<Obstacle> obstacles;
  double clearance_margin = 0.5;  // m
  double load_radius = 1.0;       // m
};

/// Reads and validates a target file (the scene path in it is relative to the file). Throws
/// SceneError naming the YAML path and line of the first problem.
TargetSpec readTarget(const std::string& path);

}  // namespace cranesim
