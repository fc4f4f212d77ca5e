#include "cranesim/math/input_signal.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cranesim {
namespace {

/// A chain of `order` lags driven by a ramp w(t) = r + s·(t − t₀), from lag outputs z at t₀.
/// Each output tracks the ramp i·s·τ behind it; its distance from that, eᵢ, decays as
/// eᵢ(σ) = e^{−σ} Σ_{j≤i} eⱼ(0) σ^{i−j}/(i−j)!, σ = (t − t₀)/τ.
struct LagChain {
  int order;
  double tau;

  /// e₁ … e_order at σ (e[0] = 0: the ramp itself).
  std::array<double, 3> errors(const std::array<double, 3>& e0, double sigma) const {
    std::array<double, 3> e{0.0, 0.0, 0.0};
    const double decay = std::exp(-sigma);
    for (int i = 1; i <= order; ++i) {
      double sum = 0.0, power = 1.0;
      for (int j = i; j >= 1; --j) {  // power = σ^{i−j}/(i−j)!
        sum += e0[j] * power;
        power *= sigma / static_cast<double>(i - j + 1);
      }
      e[i] = decay * sum;
    }
    return e;
  }

  /// Dᵐ e_n = τ^{−m} Σ_r C(m, r) (−1)^r e_{n−m+r} (e_k = 0 for k ≤ 0): the m-th time derivative
  /// of the last lag's distance from its track.
  double derivative(const std::array<double, 3>& e, int m) const {
    static constexpr int kBinomial[4][4] = {{1, 0, 0, 0}, {1, 1, 0, 0}, {1, 2, 1, 0}, {1, 3, 3, 1}};
    double sum = 0.0;
    for (int r = 0; r <= m; ++r) {
      const int k = order - m + r;
      if (k >= 1) sum += (r % 2 == 0 ? 1.0 : -1.0) * kBinomial[m][r] * e[k];
    }
    return sum / std::pow(tau, m);
  }
};

/// 1 − e^{−σ} Σ_{l<k} σ^l/l! = ∫₀^σ s^{k−1}/(k−1)! e^{−s} ds.
double incompleteGamma(int k, double sigma) {
  double sum = 0.0, power = 1.0;
  for (int l = 0; l < k; ++l) {
    sum += power;
    power *= sigma / static_cast<double>(l + 1);
  }
  return -std::expm1(-sigma) - std::exp(-sigma) * (sum - 1.0);
}

/// The lags' distances from the track of a ramp at r with slope s.
std::array<double, 3> distances(const InputState& st, int order, double tau, double s) {
  std::array<double, 3> e{0.0, 0.0, 0.0};
  for (int i = 1; i <= order; ++i) e[i] = st.z[i - 1] - (st.r - i * s * tau);
  return e;
}

}  // namespace

InputSignal::InputSignal(const InputSpec& spec, double t0) : spec_(spec) {
  if (spec.order < 1 || spec.order > 2) throw std::invalid_argument(fmt::format("an input's order is 1 or 2, not {}", spec.order));
  if (!(spec.time_constant > 0.0)) throw std::invalid_argument("an input's time constant must be positive");
  const double rest = spec.command == InputCommand::Speed ? 0.0 : spec.value;
  now_ = {t0, rest, rest, spec.value, {rest, rest}};
  before_ = now_;
}

double InputSignal::rampRate(const InputState& s) const {
  const double limit = spec_.command == InputCommand::Speed ? spec_.max_acceleration : spec_.max_speed;
  if (s.u == s.r) return 0.0;
  return s.u > s.r ? limit : -limit;  // infinite: the reference jumps (handled by command)
}

InputState InputSignal::advanced(const InputState& start, double t) const {
  const int n = spec_.order;
  const double tau = spec_.time_constant;
  const LagChain chain{n, tau};
  InputState s = start;
  // At most two pieces: the ramp until the reference reaches the command, then the hold.
  while (s.t < t) {
    const double slope = rampRate(s);
    const bool reaches = slope != 0.0 && s.t + (s.u - s.r) / slope <= t;
    const double piece_end = reaches ? s.t + (s.u - s.r) / slope : t;
    const double dt = piece_end - s.t, sigma = dt / tau;
    const std::array<double, 3> e0 = distances(s, n, tau, slope), e = chain.errors(e0, sigma);
    const double r = reaches ? s.u : s.r + slope * dt;
    if (spec_.command == InputCommand::Value) {
      s.x = r - n * slope * tau + e[n];
    } else {  // x = x₀ + ∫ z_n: the track r₀ + s·t − n·s·τ integrated, and the decaying distances
      double decaying = 0.0;
      for (int j = 1; j <= n; ++j) decaying += e0[j] * incompleteGamma(n - j + 1, sigma);
      s.x += (s.r - n * slope * tau) * dt + 0.5 * slope * dt * dt + tau * decaying;
    }
    for (int i = 1; i <= n; ++i) s.z[i - 1] = r - i * slope * tau + e[i];
    s.r = r;
    s.t = piece_end;
  }
  return s;
}

std::array<double, 4> InputSignal::derivativesOf(const InputState& start, double t) const {
  const int n = spec_.order;
  const double tau = spec_.time_constant;
  const LagChain chain{n, tau};
  const InputState s = advanced(start, t);
  const double slope = rampRate(s);
  const std::array<double, 3> e = distances(s, n, tau, slope);
  // z_n = r − n·s·τ + e_n: its rate s + D e_n, then Dᵐ e_n (the ramp's slope is constant).
  const double rate = slope + chain.derivative(e, 1);
  if (spec_.command == InputCommand::Value) return {s.x, rate, chain.derivative(e, 2), chain.derivative(e, 3)};
  return {s.x, s.z[n - 1], rate, chain.derivative(e, 2)};
}

std::array<double, 4> InputSignal::derivatives(double t, bool before_command) const {
  const bool before = t < now_.t || (before_command && t == now_.t);
  return derivativesOf(before ? before_ : now_, t);
}

double InputSignal::command(double t, double u) {
  if (!std::isfinite(u)) throw std::invalid_argument(fmt::format("the command is {}, not a finite number", u));
  if (t < now_.t) throw std::invalid_argument(fmt::format("a command at t = {} s comes before the last one ({} s)", t, now_.t));
  InputState s = now_;
  if (t > now_.t) {
    before_ = now_;
    s = advanced(now_, t);
  }
  if (spec_.command == InputCommand::Value) {
    u = std::clamp(u, spec_.min, spec_.max);
  } else {
    u = std::clamp(u, -spec_.max_speed, spec_.max_speed);
    if ((s.x >= spec_.max && u > 0.0) || (s.x <= spec_.min && u < 0.0)) u = 0.0;
  }
  s.u = u;
  if (!std::isfinite(rampRate(s))) s.r = u;  // no ramp: the reference follows the command at once
  now_ = s;
  return u;
}

void InputSignal::restore(const InputState& state) {
  now_ = state;
  before_ = state;
}

}  // namespace cranesim
