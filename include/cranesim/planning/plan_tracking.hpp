#pragma once
// A plan tracked by anti-sway feedback on a crane that differs from the one it was planned on
// (a target's `feedback:`, docs/control.md#tracking-a-plan). The plan's control splines are the
// feed-forward; the reference the feedback holds the crane to is the plan simulated on the
// nominal crane, sampled at the controller's rate: the drives' values and speeds and the swing
// the plan gives the load on its way. On the nominal crane the feedback has nothing to correct;
// on a crane with a heavier load, a longer rope, a load that starts swinging or a gust it acts on
// the difference. Each case runs twice, the plan alone (open loop) and tracked (closed loop).

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cranesim/model/scene.hpp"
#include "cranesim/model/source_location.hpp"
#include "cranesim/model/sway_sensor_spec.hpp"
#include "cranesim/solvers/dynamics.hpp"

namespace cranesim {

struct TargetSpec;
struct QuasiStaticPlan;

/// A force on the load rising and falling as 1 − cos over `duration` (a gust), across the boom
/// or along it (radial, outwards), from `start` s after the motion's start.
struct TrackingGust {
  double force = 0.0, start = 0.0, duration = 3.0;  // N, s, s
  bool across = true;
};

/// How the crane differs from the planned one.
struct TrackingCase {
  std::string name;
  double load_mass = 1.0;    // factor on the load body's mass and inertia
  double hoist_rope = 0.0;   // the hoist rope is this fraction longer than its encoder (and the plan) says
  double initial_sway = 0.0;  // m: the load starts displaced this far radially (outwards), at rest, and is let go
  std::optional<TrackingGust> gust;
  /// Wind on the crane (a scene's `wind:`), its gust's start counted from the motion's start.
  std::optional<WindSpec> wind;
  SwaySensorSpec sensor;  // how the rope's angles reach the feedback
  SourceLocation where;
};

struct TrackingSpec {
  double sample_time = 0.02;  // s
  std::string slewing;        // the driven constraint that slews the crane
  std::string sheave;         // the joint the hoist rope hangs from (its upper end's joint when empty)
  double settle_band = 0.05;  // m: "at rest" for the settling time
  /// The runs' tolerances, when the feedback sets them (the verification's otherwise).
  std::optional<double> rtol;
  std::optional<AbsoluteTolerance> atol;
  std::vector<TrackingCase> cases;
  SourceLocation where;
};

/// One run of a case, open or closed loop. Sway: the end point's horizontal distance from the
/// point it hangs from (zero when the rope hangs plumb).
struct TrackingRun {
  std::string name;
  bool closed_loop = false;
  double sway_after_5_s = 0.0;  // the largest sway from 5 s after the planned arrival to the end, m
  double sway_at_arrival = 0.0;  // the largest sway in the 5 s after arrival, m
  double settling_time = -1.0;  // s after arrival until the sway stays within the band (−1: never)
  double peak_tension = 0.0, dynamic_factor = 0.0;  // the hoist rope's largest tension (N), over its static tension
  /// The drives' largest speeds and accelerations along the run (m/s, m/s², the slewing drive's
  /// unit per s and s²), in the order luffing, hoist, slewing (0 without slewing).
  double peaks[3][2] = {};
  /// J: the work each drive delivered to the crane along the run, in the same order: the
  /// positive part of its power only (a drive that brakes or lowers is taken to regenerate
  /// nothing).
  double energy[3] = {};
  double wall_s = 0.0, controller_s = 0.0;  // the run's wall time; the controller's share of it
  long samples = 0;
  SimulationOutcome outcome;
};

/// Runs every case of `target.feedback` open and closed loop (after the plan's own
/// verification) into plan.tracking and plan.tracking_s. Throws std::runtime_error when a run
/// fails.
void verifyTracking(const TargetSpec& target, QuasiStaticPlan& plan, const std::function<void(const std::string&)>& log = {});

}  // namespace cranesim
