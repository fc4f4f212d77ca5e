#include "cranesim/planning/rest_to_rest_path.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace cranesim {
namespace {

/// Σ c_i τ^(lowest + i), differentiated k times.
template <std::size_t n>
double polynomial(std::array<double, n> c, int lowest, double tau, int k) {
  std::array<int, n> power{};
  for (std::size_t i = 0; i < n; ++i) power[i] = lowest + static_cast<int>(i);
  for (int d = 0; d < k; ++d)
    for (std::size_t i = 0; i < n; ++i) c[i] *= power[i]--;
  double value = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    if (c[i] != 0.0) value += c[i] * std::pow(tau, power[i]);
  return value;
}

/// The k-th derivative of I(τ) = ∫₀^τ S, S the smooth step 35τ⁴ − 84τ⁵ + 70τ⁶ − 20τ⁷:
/// 0 before 0, 7τ⁵ − 14τ⁶ + 10τ⁷ − 5τ⁸/2 on [0, 1], τ − 1/2 after 1 (∫₀¹ S = 1/2).
double rampIntegral(double tau, int k) {
  if (tau <= 0.0) return 0.0;
  if (tau >= 1.0) return k == 0 ? tau - 0.5 : k == 1 ? 1.0 : 0.0;
  return polynomial<4>({7.0, -14.0, 10.0, -2.5}, 5, tau, k);
}

constexpr double kPeakStep = 35.0 / 16.0;  // max S' = S'(1/2)
constexpr const char* kAxes[] = {"x", "z"};

/// The longest ramp for `duration` within the speed bounds (≤ 0: none fits) and the largest
/// ratio of the path's peak acceleration to its bound over the axes.
struct RampFit {
  double ramp = 0.0, acceleration_ratio = 0.0;
  int axis = 0;
};

RampFit fitRamp(const Eigen::Vector2d& distance, double duration, const Eigen::Vector2d& v_limit, const Eigen::Vector2d& a_limit) {
  RampFit fit;
  fit.ramp = duration / 2.0;
  for (int i = 0; i < 2; ++i)
    if (distance(i) != 0.0) fit.ramp = std::min(fit.ramp, duration - distance(i) / v_limit(i));
  if (!(fit.ramp > 0.0)) return fit;
  for (int i = 0; i < 2; ++i) {
    const double ratio = kPeakStep * distance(i) / ((duration - fit.ramp) * fit.ramp) / a_limit(i);
    if (ratio > fit.acceleration_ratio) fit = {fit.ramp, ratio, i};
  }
  return fit;
}

}  // namespace

double restToRest(double tau, int derivative) {
  if (derivative < 0 || derivative > 4) throw std::invalid_argument("restToRest: derivatives 0 … 4");
  if (tau <= 0.0 || tau >= 1.0) return derivative == 0 && tau >= 1.0 ? 1.0 : 0.0;
  return polynomial<5>({126.0, -420.0, 540.0, -315.0, 70.0}, 5, tau, derivative);
}

RestToRestPath::RestToRestPath(const Eigen::Vector2d& start, const Eigen::Vector2d& end, double duration, double ramp)
    : start_(start), end_(end), duration_(duration), ramp_(ramp) {
  if (!(duration > 0.0) || !std::isfinite(duration)) throw std::invalid_argument("rest-to-rest path: the duration must be positive");
  if (!(ramp > 0.0) || ramp > duration / 2.0)
    throw std::invalid_argument("rest-to-rest path: the ramps must be positive and at most half the duration");
}

RestToRestPath RestToRestPath::fitting(const Eigen::Vector2d& start, const Eigen::Vector2d& end, double duration,
                                       const Eigen::Vector2d& v_min, const Eigen::Vector2d& v_max,
                                       const Eigen::Vector2d& a_min, const Eigen::Vector2d& a_max) {
  const Eigen::Vector2d distance = (end - start).cwiseAbs();
  Eigen::Vector2d v_limit, a_limit;
  for (int i = 0; i < 2; ++i) {
    v_limit(i) = end(i) > start(i) ? v_max(i) : -v_min(i);
    a_limit(i) = std::min(a_max(i), -a_min(i));  // the path accelerates and brakes on every axis it moves
    if (distance(i) != 0.0 && !(v_limit(i) > 0.0 && a_limit(i) > 0.0))
      throw std::invalid_argument(fmt::format("infeasible horizon: {} cannot move with a speed or acceleration bound of 0",
                                              kAxes[i]));
  }
  const auto feasible = [&](double t) {
    const RampFit f = fitRamp(distance, t, v_limit, a_limit);
    return f.ramp > 0.0 && f.acceleration_ratio <= 1.0;
  };
  const RampFit fit = fitRamp(distance, duration, v_limit, a_limit);
  if (fit.ramp > 0.0 && fit.acceleration_ratio <= 1.0)
    return distance.isZero() ? RestToRestPath(start, end, duration, duration / 2.0) : RestToRestPath(start, end, duration, fit.ramp);
  double low = duration, high = 2.0 * duration;
  while (!feasible(high)) high *= 2.0;
  while (high - low > 1e-3 * high) (feasible(0.5 * (low + high)) ? high : low) = 0.5 * (low + high);
  const std::string why =
      fit.ramp > 0.0 ? fmt::format("its acceleration in {} would reach {:.3g} times the bound", kAxes[fit.axis], fit.acceleration_ratio)
                     : std::string("it cannot cruise within the speed bounds");
  throw std::invalid_argument(fmt::format("infeasible horizon: the rest-to-rest path (flatness) needs at least {:.3g} s, "
                                          "not {:.3g} s: {}",
                                          high, duration, why));
}

double RestToRestPath::progress(double t, int k) const {
  if (k < 0 || k > 4) throw std::invalid_argument("rest-to-rest path: derivatives 0 … 4");
  const double speed = 1.0 / (duration_ - ramp_);
  return speed * std::pow(ramp_, 1 - k) * (rampIntegral(t / ramp_, k) - rampIntegral((t - duration_ + ramp_) / ramp_, k));
}

Eigen::Vector2d RestToRestPath::derivative(double t, int k) const {
  return (k == 0 ? start_ : Eigen::Vector2d::Zero()) + progress(t, k) * (end_ - start_);
}

RestToRestPath restToRestPath(const QrProblem& problem) { return restToRestPath(problem, problem.steps * problem.sample_time); }

RestToRestPath restToRestPath(const QrProblem& problem, double duration) {
  return RestToRestPath::fitting(problem.start.head<2>(), problem.target.head<2>(), duration, problem.state_min.tail<2>(),
                                 problem.state_max.tail<2>(), problem.control_min, problem.control_max);
}

QrTrajectory sampleTrajectory(const RestToRestPath& path, double sample_time) {
  const auto n = static_cast<long>(std::ceil(path.duration() / sample_time - 1e-9));
  QrTrajectory sampled;
  for (long k = 0; k <= n; ++k) {
    const double t = std::min(static_cast<double>(k) * sample_time, path.duration());
    EndState state;
    state << path.derivative(t, 0), path.derivative(t, 1);
    sampled.t.push_back(t);
    sampled.states.push_back(state);
  }
  for (long k = 0; k < n; ++k)
    sampled.controls.push_back((sampled.states[k + 1].tail<2>() - sampled.states[k].tail<2>()) /
                               (sampled.t[k + 1] - sampled.t[k]));
  return sampled;
}

}  // namespace cranesim
