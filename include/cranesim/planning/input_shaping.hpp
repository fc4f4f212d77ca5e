#pragma once
// Input shaping of a planned end-point path (docs/planning.md): the path convolved with a
// few impulses spaced by fractions of the load's sway period, so that the sway each part of the
// motion excites is cancelled by the next (Singer & Seering 1990; Singhose, Seering & Singer
// 1994 for ZVD). For an undamped pendulum of period T:
//   ZV:  amplitudes ½, ½ at 0, T/2;          residual sway |cos(π r / 2)| of an unshaped move,
//   ZVD: amplitudes ¼, ½, ¼ at 0, T/2, T;    residual sway cos²(π r / 2),
// r = T / (the true period): ZVD keeps the residual below 5 % for r within ±14 %, ZV within ±3 %.

#include <vector>

#include "cranesim/planning/qr_trajectory.hpp"

namespace cranesim {

enum class ShaperKind { ZV, ZVD };

struct InputShaper {
  std::vector<double> times;       // s, from 0, increasing
  std::vector<double> amplitudes;  // sum to 1
  double duration() const { return times.back(); }
};

/// The ZV or ZVD shaper for an undamped oscillation of `period` s (> 0).
InputShaper makeShaper(ShaperKind kind, double period);

/// The trajectory's path convolved with the shaper: state(t) = Σ a_i state_QR(t − t_i), with
/// the QR states between samples exact for its double integrator (x + v s + a s²/2) and held at
/// the first and last state outside the trajectory. Sampled at the trajectory's sample time
/// from its first time until every impulse's copy has arrived (⌈duration / ts⌉ samples more);
/// the controls are the mean accelerations over each sample interval. Cost and iterations are
/// the QR solution's.
QrTrajectory shapeTrajectory(const QrTrajectory& trajectory, const InputShaper& shaper);

}  // namespace cranesim
