#pragma once
// Anti-sway feedback on a crane driven step by step: two SwayAxisControllers, across the boom by
// the slewing drive and along it by the luffing winch, in the loop of a Session. The operator's
// (or a plan's) speeds are the references the boom head follows; the feedback adds what damps
// the swing. It reads what a crane measures: the drives' encoders (the inputs' values and rates),
// the hoist rope's angles at the boom head and its length.

#include <optional>
#include <string>
#include <vector>

#include "cranesim/control/moving_average.hpp"
#include "cranesim/control/shaped_head_path.hpp"
#include "cranesim/control/sway_axis.hpp"
#include "cranesim/control/sway_sensor.hpp"
#include "cranesim/session/session.hpp"

namespace cranesim {

struct CraneSwaySpec {
  std::string slewing = "slewing";            // input: the slewing drive, speed commands in the scene's unit per s
  std::string luffing_rope = "luffing_rope";  // input: the luffing winch, m/s
  std::string hoist_rope = "hoist_rope";      // input: the hoist winch, m/s (passed through)
  std::string hook = "load.origin";           // joint at the rope's lower end
  std::string sheave = "head.sheave";         // joint at its upper end, on the boom head
  // The boom's sideways mode (0.86 Hz), the load's bounce (0.76 Hz) stay out of the feedback: 0.3 Hz.
  SwayAxisSpec across{.measurement_cutoff = 0.3}, along{.angle = 0.02, .angle_rate = 0.02, .measurement_cutoff = 0.3};
  /// 1/s: the hoist winch's speed command corrects its length towards the reference's at this
  /// rate (0: the hoist speed passes through, an operator's lever).
  double hoist_gain = 0.0;
  /// s: the crane's sway period with the hoist rope as it is at the start. The operator's slewing
  /// and luffing speeds then move the boom head along a path shaped for a pendulum of that period
  /// (control/shaped_head_path.hpp), and the swing that path gives the pendulum is the feedback's
  /// reference; the period follows the hoist (a pendulum longer than the rope by a constant).
  /// 0: not shaped, the reference swing is zero.
  double shaping_period = 0.0;
  /// s: the period of the boom's mode that the hoist's load changes excite (its luffing-plane
  /// bending). The operator's hoist speed is then averaged over it, so that each of its changes
  /// is a ramp of that duration and leaves the mode still; 0: the hoist speed passes through.
  double boom_period = 0.0;
  /// How the rope's angles reach the feedback: late and noisy (control/sway_sensor.hpp); exact by
  /// default. The controller knows the delay and predicts the angles over it from the boom
  /// head's motion since (the encoders').
  SwaySensorSpec sensor;
};

/// Where the crane should be at one sample: the drives' values (in the inputs' units) and
/// speeds, and the swing the load should have there (a plan's swing while it accelerates; zero
/// to hold it still).
struct CraneSwayReference {
  double slewing = 0.0, slewing_speed = 0.0;
  double luffing = 0.0, luffing_speed = 0.0;
  double hoist = 0.0, hoist_speed = 0.0;
  Session::Sway sway;
};

class CraneSwayController {
 public:
  /// Finds the inputs and joints (std::invalid_argument naming what is missing) and tabulates the
  /// boom head's radius per metre of luffing rope from the scene's equilibria over the luffing
  /// input's range (its limits, or ±2 m about its value). The head's reference is where it is now.
  CraneSwayController(Session& session, const CraneSwaySpec& spec);

  /// Sets the session's inputs for the next sample: the head follows the reference speeds (the
  /// slewing rate in the slewing input's unit per s, the luffing rope's speed in m/s; shaped when
  /// the spec says so) while the swing is damped; the hoist speed passes through. Returns the commands as held, in the order of
  /// the session's inputs (clipped to their limits).
  std::vector<double> apply(double slewing_speed, double luffing_speed, double hoist_speed);

  /// Sets the session's inputs for the next sample so that the crane tracks `reference`: the
  /// reference speeds plus the LQR feedback on the head's distance from where the reference puts
  /// it and on the swing's difference from the reference's (plan tracking).
  std::vector<double> apply(const CraneSwayReference& reference);

  /// The boom head's radius per metre of luffing rope at luffing rope length `length` (the table).
  double headPerLuff(double length) const;
  const SwayAxisController& across() const { return across_; }
  const SwayAxisController& along() const { return along_; }

 private:
  Session& session_;
  int slewing_, luffing_, hoist_, hook_, sheave_;
  double slewing_unit_;  // rad per unit of the slewing input (π/180 for degrees)
  SwayAxisController across_, along_;
  SwaySensor sensor_;
  std::optional<DelayLine<Eigen::Vector2d>> late_head_speeds_;  // [along, across] as they were sensor.delay ago
  std::vector<double> table_length_, table_ratio_;  // dR/dl at luffing rope lengths
  double slewing_reference_, luffing_reference_, hoist_reference_;  // where the speeds lead, in the inputs' values
  double hoist_gain_;
  std::optional<ShapedHeadPath> shaped_;
  std::optional<MovingAverage> smoothed_hoist_;
  double slewing_start_ = 0.0;       // the slewing input's value where the shaped path begins
  double shaped_luffing_ = 0.0;      // the luffing rope's length along the shaped path
  double pendulum_offset_ = 0.0;     // m: the sway pendulum's length less the rope's
  double shapingPeriod(double rope_length) const;
};

}  // namespace cranesim
