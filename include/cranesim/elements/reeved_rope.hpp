#pragma once
// Massless reeved rope (docs/scene-format.md#reeved-ropes): one rope from its winch over a
// sequence of sheaves to its dead end, each part between consecutive path points a straight,
// tension-only spring, the whole path sharing one unstretched length L(t) (the winch).
//
// Path points x_0 (winch) … x_m (dead end); part k runs from x_k to x_{k+1}, chord ℓ_k,
// direction u_k, rate ℓ̇_k = u_k·(ẋ_{k+1} − ẋ_k). A sheave sits at each inner point
// x_1 … x_{m−1}, the rope's line of action through its centre (the geometric model and its
// error: docs/scene-format.md#reeved-ropes).
// - Strain of the whole path ε = Σℓ/L − 1, rate ε̇ = Σℓ̇/L − Σℓ L̇/L² (the material's, as the
//   cable's); the lead part's tension T_0 = EA max(ε + η ε̇, 0) (Kelvin–Voigt η).
// - Material speed over sheave i towards the dead end, for rigid parts: w_i = Σ_{k≥i} ℓ̇_k (the
//   rope beyond the sheave lengthens), the rope's travel over it s_i = Σ_{k≥i} ℓ_k. The sheave's
//   friction holds the rope back: T_i = T_{i−1} e^(λ_i φ_i), with λ_i = −ln η_i for a turning
//   sheave of bearing efficiency η_i and λ_i = μ_i θ_i for a capstan (the rope sliding over a
//   sheave that does not turn, wrap θ_i, Euler–Eytelwein T_tight/T_slack = e^(μθ)).
// - φ_i ∈ [−1, 1], the sheave's grip, follows the rope's travel by Dahl's pre-sliding law
//   dφ/ds = (1 − φ sgn ds)/δ_i: at rest it stays (the ratio is held: stick), running one way
//   for a few δ_i it reaches ±1 (hoisting w < 0 drops the tension by e^(−λ_i) at each sheave
//   away from the winch, lowering raises it by e^(λ_i)). Along a travel of one direction from
//   where the grip was held, (s₀, φ₀), the law integrates in closed form:
//   φ = σ + (φ₀ − σ) e^(−|s − s₀|/δ), σ = sgn(s − s₀); the memory (s₀, φ₀) is moved to the
//   state each accepted step ends at (`hold`), so a step's φ is a function of its coordinates.
// - δ_i, the pre-sliding distance: the rope's travel over which the elasticity of the two parts
//   beside the sheave builds the tension difference λ_i T: moving u of rope over the sheave
//   with the parts' ends held changes T_i − T_{i−1} by EA u (1/ℓ_{i−1} + 1/ℓ_i), so
//   δ_i = λ_i T_{i−1} / (EA (1/ℓ_{i−1} + 1/ℓ_i)), taken at each held state, unless the scene
//   gives every sheave its own (`pre_sliding`: the groove's and bearing's compliance on top).
// - Forces: part k pulls its ends together, F = Σ T_k ∂ℓ_k/∂x (−T_k u_k on x_k, +T_k u_k on
//   x_{k+1}); the rope has no mass and no weight.
// - Energy books (model/element.hpp): V = ½ EA L max(ε, 0)². Summation by parts gives
//   Σ T_k ℓ̇_k = T_0 Σℓ̇ + Σ_i (T_i − T_{i−1}) w_i, so with the lead part's law the books close
//   exactly: the winch's power L̇ ∂V/∂L at fixed state (plus the damping stress' power on the
//   stretch rate that L̇ causes, as the cable's), the dissipation
//   L EA (σ − σ₀) ε̇ + Σ_i (T_i − T_{i−1}) w_i. A sheave's term is ≥ 0 while it slips
//   (T_i/T_{i−1} − 1 has the sign of w_i); in pre-sliding back towards φ = 0 it is negative, by
//   at most λ_i T δ_i over the travel δ_i: the rope's elastic pre-sliding energy, which the
//   massless parts have no store for (docs/known-limits.md).

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "cranesim/elements/parts/reeled_length.hpp"
#include "cranesim/elements/section.hpp"

namespace cranesim {

/// The winch's pull while hoisting steadily (every sheave slipping towards the winch) the load
/// that parts 1 … m−1 (the falls) of a rope of m parts carry with the tensions `tension`, λ_i
/// the sheaves' friction exponents: the falls' sum over Σ_k Π_{i≤k} e^(−λ_i), the falls keeping
/// their directions. For n falls over sheaves of efficiency η: W (1 − η) / (η (1 − ηⁿ)),
/// DIN 15020-1's W / (n η_S η).
inline double hoistingLinePull(const double* tension, const double* friction_exponent, int parts) {
  double carried = 0.0, share = 0.0, ratio = 1.0;
  for (int k = 1; k < parts; ++k) {
    carried += tension[k];
    ratio *= std::exp(-friction_exponent[k - 1]);
    share += ratio;
  }
  return carried / share;
}

struct ReevedRopeKernel : ReeledLength {
  /// Path points a kernel call holds on the stack: a rope on 30 falls and its lead part.
  static constexpr int kMaxPoints = 34;

  Section section;
  Material material;
  double damping = 0.0;     // Kelvin–Voigt retardation time η, s
  int points = 2;           // path points, winch and dead end included
  double pre_sliding = 0.0;  // δ of every sheave, m; 0: from the parts' elasticity (file comment)
  /// λ_i of the sheave at inner point i (index i − 1): −ln η_i or μ_i θ_i, 0 for a frictionless sheave.
  std::array<double, kMaxPoints> friction_exponent{};

  /// A sheave's memory of its grip: the travel s₀ (the rope beyond it, m) and φ₀ when last held,
  /// and δ (m). Not yet held (s₀ NaN), and in statics and modes (rates held), φ = φ₀.
  struct Grip {
    double travel = std::numeric_limits<double>::quiet_NaN();
    double state = 0.0;
    double distance = 1.0;
  };
  std::array<Grip, kMaxPoints> grip{};

  template <class S> using Points = std::array<Vec3T<S>, kMaxPoints>;

  /// The tensions T_k of the m = points − 1 parts (N) at path positions x and velocities xd.
  template <class S>
  void partTensions(const Points<S>& x, const Points<S>& xd, double t, ParameterRates rates, S* tension) const {
    const Chords<S> c = chords(x, xd);
    const double L = segmentLength(t);
    S strain = c.total / L - 1.0;
    if (damping > 0.0) strain += damping * (c.total_rate / L - c.total * segmentRate(t, rates) / (L * L));
    tension[0] = strain > 0.0 ? S(axialStiffness() * strain) : S(0.0);
    S beyond = c.total;  // s_i = Σ_{k≥i} ℓ_k
    for (int i = 1; i < parts(); ++i) {
      beyond -= c.length[i - 1];
      tension[i] = tension[i - 1] * sheaveRatio(i, beyond, rates);
    }
  }

  /// Moves every sheave's memory to the path at x (a step accepted there): φ₀ the grip reached,
  /// s₀ the travel, δ from the tensions there.
  void hold(const Points<double>& x, const Points<double>& xd, double t) {
    std::array<double, kMaxPoints> tension;
    partTensions(x, xd, t, ParameterRates::Left, tension.data());
    const Chords<double> c = chords(x, xd);
    const double EA = axialStiffness();
    double beyond = c.total;
    for (int i = 1; i < parts(); ++i) {
      beyond -= c.length[i - 1];
      Grip& g = grip[i - 1];
      g.state = gripState(i, beyond, ParameterRates::Left);
      g.travel = beyond;
      const double pair = 1.0 / c.length[i - 1] + 1.0 / c.length[i];
      g.distance = pre_sliding > 0.0 ? pre_sliding
                                     : std::max(friction_exponent[i - 1] * tension[i - 1] / (EA * pair), kLeastPreSliding);
    }
  }

  /// φ_i at the travel s over sheave i (file comment).
  template <class S> S gripState(int i, const S& travel, ParameterRates rates) const {
    const Grip& g = grip[i - 1];
    if (rates == ParameterRates::Held || std::isnan(g.travel)) return S(g.state);
    using std::exp;
    const S moved = travel - g.travel;
    if (moved >= 0.0) return 1.0 - (1.0 - g.state) * exp(-moved / g.distance);
    return -1.0 + (1.0 + g.state) * exp(moved / g.distance);
  }

  /// Forces F on the path points (the left side's: the rope's resistance, −(force on the body)).
  template <class S>
  void pointForces(const Points<S>& x, const Points<S>& xd, double t, ParameterRates rates, Points<S>& force) const {
    std::array<S, kMaxPoints> tension;
    partTensions(x, xd, t, rates, tension.data());
    for (int p = 0; p < points; ++p) force[p].setZero();
    for (int k = 0; k < parts(); ++k) {
      const Vec3T<S> d = x[k + 1] - x[k];
      using std::sqrt;
      const Vec3T<S> pull = (tension[k] / sqrt(d.squaredNorm())) * d;
      force[k] -= pull;
      force[k + 1] += pull;
    }
  }

  /// ½ EA L max(ε, 0)².
  double potentialEnergy(const Points<double>& x, double t) const {
    double length = 0.0;
    for (int k = 0; k < parts(); ++k) length += (x[k + 1] - x[k]).norm();
    const double strain = std::max(length / segmentLength(t) - 1.0, 0.0);
    return 0.5 * axialStiffness() * segmentLength(t) * strain * strain;
  }

  /// The winch's power: L̇ ∂V/∂L at fixed state, ∂ε/∂L = −Σℓ/L², plus the damping stress' power
  /// on the stretch rate that L̇ causes (file comment).
  double explicitTimePower(const Points<double>& x, const Points<double>& xd, double t) const {
    const double rate = segmentRate(t);
    if (rate == 0.0) return 0.0;
    const Chords<double> c = chords(x, xd);
    const double L = segmentLength(t), EA = axialStiffness();
    const double strain = std::max(c.total / L - 1.0, 0.0), strain_L = -c.total / (L * L);
    return rate * (0.5 * EA * strain * strain + EA * L * strain * strain_L +
                   L * EA * dampingStress(c, t) * strain_L);
  }

  /// Kelvin–Voigt power plus every sheave's (T_i − T_{i−1}) w_i ≥ 0.
  double dissipatedPower(const Points<double>& x, const Points<double>& xd, double t) const {
    const Chords<double> c = chords(x, xd);
    const double L = segmentLength(t);
    double power = L * axialStiffness() * dampingStress(c, t) * (c.total_rate / L - c.total * segmentRate(t) / (L * L));
    std::array<double, kMaxPoints> tension;
    partTensions(x, xd, t, ParameterRates::Left, tension.data());
    double beyond = c.total_rate;
    for (int i = 1; i < parts(); ++i) {
      beyond -= c.rate[i - 1];
      power += (tension[i] - tension[i - 1]) * beyond;
    }
    return power;
  }

  int parts() const { return points - 1; }
  double axialStiffness() const { return material.youngs_modulus * section.area; }

 private:
  /// δ of a slack rope, m: the grip turns within a micrometre of travel.
  static constexpr double kLeastPreSliding = 1e-6;

  template <class S> struct Chords {
    std::array<S, kMaxPoints> length, rate;  // ℓ_k, ℓ̇_k
    S total, total_rate;            // Σℓ, Σℓ̇
  };

  template <class S> Chords<S> chords(const Points<S>& x, const Points<S>& xd) const {
    using std::sqrt;
    Chords<S> c;
    c.total = S(0.0), c.total_rate = S(0.0);
    for (int k = 0; k < parts(); ++k) {
      const Vec3T<S> d = x[k + 1] - x[k];
      const S length = sqrt(d.squaredNorm());
      c.length[k] = length;
      c.rate[k] = d.dot(Vec3T<S>(xd[k + 1] - xd[k])) / length;
      c.total += length;
      c.total_rate += c.rate[k];
    }
    return c;
  }

  /// T_i / T_{i−1} = e^(λ_i φ_i) across the sheave at inner point i, s its travel.
  template <class S> S sheaveRatio(int i, const S& travel, ParameterRates rates) const {
    const double exponent = friction_exponent[i - 1];
    if (exponent == 0.0) return S(1.0);
    using std::exp;
    return exp(exponent * gripState(i, travel, rates));
  }

  /// (σ − σ₀)/E: the damped law's stress less the elastic one.
  double dampingStress(const Chords<double>& c, double t) const {
    if (damping == 0.0) return 0.0;
    const double L = segmentLength(t), strain = c.total / L - 1.0;
    const double rate = c.total_rate / L - c.total * segmentRate(t) / (L * L);
    return std::max(strain + damping * rate, 0.0) - std::max(strain, 0.0);
  }
};

}  // namespace cranesim
