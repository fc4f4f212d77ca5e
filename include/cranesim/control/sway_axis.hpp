#pragma once
// Anti-sway feedback along one horizontal axis of a crane: the load as a pendulum under a
// suspension point (the boom head's sheave) whose speed follows a command through the drive's
// lag; an LQR that moves the suspension point to its reference while it damps the swing,
// redesigned as the rope's length changes (gain scheduling).
//
// Along the axis, for small angles θ of the rope from the vertical (the load's offset from the
// suspension point over the rope's length), with v the suspension point's speed and u its command:
//   ẋ = v,   v̇ = (u − v) / T,   θ̈ = −(g/L) θ − v̇ / L.

#include <Eigen/Dense>

#include <optional>

#include "cranesim/control/low_pass.hpp"
#include "cranesim/control/lqr.hpp"

namespace cranesim {

struct SwayAxisSpec {
  double sample_time = 0.02;  // s: the controller's period; commands are held over it
  double drive_lag = 0.1;     // s: T, how the suspension point's speed follows its command
  double gravity = 9.81;      // m/s²
  // The largest deviations the design accepts of [position (m), speed (m/s), angle (rad),
  // angular rate (rad/s)] and of the command (m/s): Bryson's weights 1/deviation².
  double position = 1.0, speed = 1.0, angle = 0.01, angle_rate = 0.01, command = 0.5;
  /// The rope's length changes by more than this fraction before the gain is designed anew.
  double reschedule = 0.005;
  /// Hz: a second-order low-pass filter on the measured angle and its rate, to keep a flexible
  /// boom's sideways and luffing modes (near 1 Hz on the thesis crane) out of the feedback; 0:
  /// none, the loop is the design's.
  double measurement_cutoff = 0.0;
  /// s: the angle's steady part — the offset at which a steady wind holds the load — is the
  /// angle through a first-order low-pass of this time constant, and the feedback acts on the
  /// angle less it: on the swing about where the load hangs, not on where it hangs (fed back,
  /// a steady offset θ₀ would hold the head off its reference by K_θ θ₀ / K_x, 0.8 m in 10 m/s
  /// of wind on the thesis crane). 0: none, the feedback acts on the angle from the vertical.
  double steady_angle_time = 0.0;
};

/// The model above, continuous: state [x, v, θ, θ̇], input u.
struct PendulumAxisModel {
  Eigen::Matrix4d A;
  Eigen::Vector4d B;
};
PendulumAxisModel pendulumAxisModel(double rope_length, double gravity, double drive_lag);

class SwayAxisController {
 public:
  explicit SwayAxisController(const SwayAxisSpec& spec);

  /// The suspension point's speed command for the next sample: its reference speed, less the
  /// LQR feedback on [position − reference position, speed − reference speed, θ, θ̇]. Designs the
  /// gain for `rope_length` when it is the first call or the length has moved (spec.reschedule).
  /// The angle and its rate pass the measurement filter first when the spec has one.
  double command(double rope_length, double position_error, double speed, double reference_speed, double angle,
                 double angle_rate);

  /// The gain in use, and the rope length it was designed for.
  const Eigen::RowVector4d& gain() const { return gain_; }
  double designLength() const { return design_length_; }
  /// The discrete closed loop of the model at the design length (A − B K), to check the design.
  Eigen::Matrix4d closedLoop() const { return system_.A - system_.B * gain_; }
  const SwayAxisSpec& spec() const { return spec_; }

 private:
  void design(double rope_length);

  SwayAxisSpec spec_;
  DiscreteSystem system_;
  Eigen::RowVector4d gain_ = Eigen::RowVector4d::Zero();
  double design_length_ = 0.0;
  std::optional<LowPassFilter> angle_filter_, rate_filter_;
  double steady_angle_ = 0.0;  // rad: the angle's steady part (spec.steady_angle_time)
};

}  // namespace cranesim
