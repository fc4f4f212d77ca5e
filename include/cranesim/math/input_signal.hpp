#pragma once
// A drive whose command is set while the model runs (docs/session.md#inputs): a winch, a
// slewing drive or a load's force follows its caller's command as a real drive follows its
// lever. The command u passes a ramp (rate limiter: the reference r moves towards u no faster
// than the limit) and then a chain of `order` first-order lags with time constant τ:
//
//   speed command:  |r'| ≤ max_acceleration,  z₁' = (r − z₁)/τ,  zᵢ' = (zᵢ₋₁ − zᵢ)/τ,  x' = z_order
//   value command:  |r'| ≤ max_speed,          the same chain with x = z_order
//
// (x: the drive's value; without the limit r jumps to u). Between commands r is a ramp and a
// hold, and the chain is solved in closed form on each, so the value and its first three time
// derivatives are exact at any time after the last command. A new command only changes where
// the ramp heads: r stays continuous and so does everything the lags integrate from it. A speed
// drive with an acceleration limit keeps its acceleration continuous (its jerk jumps); without
// one, its speed stays continuous (its acceleration jumps). The integrator need not restart.

#include <array>
#include <limits>

namespace cranesim {

enum class InputCommand { Speed, Value };

struct InputSpec {
  InputCommand command = InputCommand::Speed;
  double value = 0.0;           // the drive's value at the start
  int order = 1;                // lags in series: 1 or 2
  double time_constant = 0.05;  // τ, s
  /// What the drive can do, in the scene's units (see InputSignal::command).
  double max_speed = std::numeric_limits<double>::infinity();
  double max_acceleration = std::numeric_limits<double>::infinity();
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
};

/// Where a drive is at time t: its command, ramp, lags and value. All a restore needs.
struct InputState {
  double t = 0.0;             // the time it describes
  double u = 0.0;             // the command held since the last command
  double r = 0.0;             // the ramp's reference
  double x = 0.0;             // the drive's value
  std::array<double, 2> z{};  // the lags' outputs
};

class InputSignal {
 public:
  /// At rest at spec.value from t0: speed 0 (a speed command 0, or a value command spec.value).
  InputSignal(const InputSpec& spec, double t0);

  /// The value and its first three time derivatives at t (not before the last command but one);
  /// at the last command's time itself, `before_command` asks for them as the command before it
  /// left them (the integrator's left limit at a stop).
  std::array<double, 4> derivatives(double t, bool before_command = false) const;

  /// Holds command u from time t (not before the last command) on. A value command is clipped
  /// to [min, max]; a speed command to ±max_speed, and to zero towards a value limit the drive
  /// has reached (a limit switch: the drive then stops within its lag). The ramp keeps the
  /// speed within max_speed for a value command and the acceleration within max_acceleration for
  /// a speed command. Returns the command as held; std::invalid_argument for one not finite.
  double command(double t, double u);

  const InputSpec& spec() const { return spec_; }
  /// The command held now (after its clipping).
  double held() const { return now_.u; }
  /// The drive at its last command: what save and restore keep.
  InputState state() const { return now_; }
  void restore(const InputState& state);

 private:
  /// The state at t ≥ s.t under the command s.u held since s.t.
  InputState advanced(const InputState& s, double t) const;
  std::array<double, 4> derivativesOf(const InputState& s, double t) const;
  /// The ramp's slope from s towards its command s.u (0 once there).
  double rampRate(const InputState& s) const;

  InputSpec spec_;
  InputState now_;     // from the last command on
  InputState before_;  // from the command before it (for the left limit at the last command)
};

}  // namespace cranesim
