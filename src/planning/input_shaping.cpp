#include "cranesim/planning/input_shaping.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cranesim {
namespace {

/// The QR trajectory's state at any time: exact between samples for the double integrator
/// under the step's constant control, held outside [t_0, t_N].
EndState stateAt(const QrTrajectory& trajectory, double t) {
  const std::vector<double>& ts = trajectory.t;
  if (t <= ts.front()) return trajectory.states.front();
  if (t >= ts.back()) return trajectory.states.back();
  const std::size_t k = std::upper_bound(ts.begin(), ts.end(), t) - ts.begin() - 1;
  const double s = t - ts[k];
  const EndState& x = trajectory.states[k];
  const EndControl& a = trajectory.controls[k];
  EndState at;
  at << x.head<2>() + s * x.tail<2>() + 0.5 * s * s * a, x.tail<2>() + s * a;
  return at;
}

}  // namespace

InputShaper makeShaper(ShaperKind kind, double period) {
  if (!(period > 0.0) || !std::isfinite(period)) throw std::invalid_argument("input shaper: the period must be positive");
  if (kind == ShaperKind::ZV) return {{0.0, 0.5 * period}, {0.5, 0.5}};
  return {{0.0, 0.5 * period, period}, {0.25, 0.5, 0.25}};
}

QrTrajectory shapeTrajectory(const QrTrajectory& trajectory, const InputShaper& shaper) {
  if (trajectory.t.size() < 2) throw std::invalid_argument("input shaping: the trajectory needs at least two samples");
  const double t0 = trajectory.t.front();
  const double ts = trajectory.t[1] - t0;
  const auto n = static_cast<long>(trajectory.t.size() - 1 + std::ceil(shaper.duration() / ts - 1e-9));
  QrTrajectory shaped;
  shaped.cost = trajectory.cost;
  shaped.iterations = trajectory.iterations;
  shaped.solve_time_s = trajectory.solve_time_s;
  for (long j = 0; j <= n; ++j) {
    const double t = t0 + static_cast<double>(j) * ts;
    EndState state = EndState::Zero();
    for (std::size_t i = 0; i < shaper.times.size(); ++i) state += shaper.amplitudes[i] * stateAt(trajectory, t - shaper.times[i]);
    shaped.t.push_back(t);
    shaped.states.push_back(state);
  }
  for (long j = 0; j < n; ++j)
    shaped.controls.push_back((shaped.states[j + 1].tail<2>() - shaped.states[j].tail<2>()) / ts);
  return shaped;
}

}  // namespace cranesim
