#pragma once
// Massive reeved rope (docs/elements.md#massive-reeving): the path of the massless reeved rope
// (reeved_rope.hpp), each part a chain of `elements_per_part` two-node cables that carries the
// rope's mass and weight, the material running over the sheaves.
//
// Chain: the rope's nodes in order from the winch, part k from chain node k n to (k + 1) n
// (n = elements_per_part); chain node k n is path point k (a sheave's centre, the winch, the dead
// end), the others are the part's inner nodes.
// Material coordinates σ_k: the unstretched length from path point k to the dead end, σ_0 = L(t)
// (the winch), σ_m = 0 (the dead end), σ_1 … σ_{m−1} the sheaves' coordinates; σ̇_i is the
// rope's speed over sheave i towards the dead end (the massless kernel's w_i). Part k's
// unstretched length L_k = σ_k − σ_{k+1}, each element's L_e = L_k / n.
// - Element e of a part: chord ℓ, u its direction, ε = ℓ/L_e − 1, ε̇ = ℓ̇/L_e − ℓ L̇_e/L_e²
//   (the material's), tension T = EA max(ε + η ε̇, 0), the elastic T₀ = EA max(ε, 0).
// - Energies: V = Σ_e ½ EA L_e max(ε, 0)² − ρA L_e g·(x_a + x_b)/2; T = ½ Σ_j μ_j |ẋ_j|² +
//   ½ Σ_i m_i σ̇_i², the inner node's lumped mass μ_j = ρA L_e, the sheave's m_i (the rope's mass
//   on half its circumference, ρA π r, and the sheave's rotary inertia J/r²: sheaveMass).
// - Equations: inner node μ_j ẍ_j + ∂V/∂x_j = 0 (material enters with the node's velocity);
//   path point: ∂V/∂x_k on its body; sheave m_i σ̈_i + ∂V/∂σ_i − ½ Σ_j ∂μ_j/∂σ_i |ẋ_j|² + f_i = 0.
//   ∂V/∂L_e = −T₀ (1 + ε/2) − ΔT (1 + ε) − ρA g·(x_a + x_b)/2, ΔT = T − T₀ (the damping stress'
//   share, its power on ε̇'s part through L_e), so at rest m_i σ̈_i ≈ T_i − T_{i−1}: the tension
//   of the part beyond the sheave against the one before it.
// - Friction f_i = T_{i−1}^end (e^(λ_i tanh(σ̇_i / b)) − 1), T_{i−1}^end the tension of the part
//   before the sheave where it reaches it: at steady running T_i = T_{i−1} e^(λ_i σ(σ̇_i)), the
//   massless law; its power f_i σ̇_i ≥ 0.
// - Books (model/element.hpp): with E = T + V, dqᵀ r = dE/dt − P_time + P_diss, P_time =
//   L̇ ∂(T + V)/∂σ_0 at fixed state plus the damping stress' power on the stretch rate L̇ causes,
//   P_diss = Σ_e L_e ΔT ε̇ + Σ_i f_i σ̇_i.

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "cranesim/elements/parts/reeled_length.hpp"
#include "cranesim/elements/section.hpp"

namespace cranesim {

struct MassiveReevingKernel : ReeledLength {
  static constexpr int kMaxPoints = 34;

  Section section;
  Material material;
  double damping = 0.0;      // Kelvin–Voigt retardation time η, s
  double speed_band = 1e-3;  // b of the friction's smoothing tanh(σ̇/b), m/s
  int points = 2;            // path points, winch and dead end included
  int elements_per_part = 8;
  /// λ_i of the sheave at inner point i (index i − 1), as the massless kernel's.
  std::array<double, kMaxPoints> friction_exponent{};
  /// m_i of the sheave at inner point i (index i − 1), kg.
  std::array<double, kMaxPoints> sheave_mass{};

  /// The state the kernel reads: the chain's positions, velocities and accelerations (those of
  /// the path points are not read), the material coordinates σ_0 … σ_m with their rates and
  /// accelerations (σ_0's and σ_m's from the winch and the dead end).
  template <class S> struct State {
    std::vector<Vec3T<S>> x, v;
    std::vector<Vec3> a;
    std::vector<S> sigma, sigma_rate;
    std::vector<double> sigma_acceleration;
  };
  /// The residual M (a + α v) + F: on every chain node (a path point's: the rope's resistance,
  /// −(force on its body)) and on every σ_k (σ_0's and σ_m's are not equations).
  template <class S> struct Residual {
    std::vector<Vec3T<S>> chain;
    std::vector<S> sigma;
  };

  int parts() const { return points - 1; }
  int chainNodes() const { return parts() * elements_per_part + 1; }
  double lineDensity() const { return material.density * section.area; }
  double axialStiffness() const { return material.youngs_modulus * section.area; }
  /// The mass m_i on a sheave's material coordinate: the rope on half the circumference of a
  /// sheave of radius r, and the sheave's rotary inertia J about its axle turned without slip
  /// (½ J (σ̇/r)² = ½ (J/r²) σ̇²).
  double sheaveMass(double radius, double inertia) const {
    return lineDensity() * std::numbers::pi * radius + inertia / (radius * radius);
  }

  /// One cable's share of the state, element e of part k: its end nodes (chain nodes k n + e and
  /// k n + e + 1), the start node's acceleration (read where it is an inner node), σ_k and σ_{k+1}
  /// with their rates, σ̈_{k+1}.
  template <class S> struct Cable {
    std::array<Vec3T<S>, 2> x, v;
    Vec3 a = Vec3::Zero();
    std::array<S, 2> sigma, sigma_rate;
    double sigma_acceleration = 0.0;
  };
  /// A cable's share of the residual: on its end nodes and on σ_k, σ_{k+1}.
  template <class S> struct CableResidual {
    std::array<Vec3T<S>, 2> node;
    std::array<S, 2> sigma;
  };

  template <class S> Cable<S> cable(const State<S>& s, int k, int e) const {
    const int a = k * elements_per_part + e;
    return {{s.x[a], s.x[a + 1]}, {s.v[a], s.v[a + 1]}, s.a[a], {s.sigma[k], s.sigma[k + 1]},
            {s.sigma_rate[k], s.sigma_rate[k + 1]}, s.sigma_acceleration[k + 1]};
  }

  /// One element's axial state: chord, direction, strain, rate, elastic tension, tension.
  template <class S> struct Axial {
    Vec3T<S> u;
    S chord, strain, strain_rate, elastic, tension;
  };

  template <class S> Axial<S> axial(const Cable<S>& c) const {
    using std::sqrt;
    const Vec3T<S> d = c.x[1] - c.x[0];
    Axial<S> out;
    out.chord = sqrt(d.squaredNorm());
    out.u = d / out.chord;
    const S L = elementLength(c), L_rate = (c.sigma_rate[0] - c.sigma_rate[1]) / double(elements_per_part);
    out.strain = out.chord / L - 1.0;
    out.strain_rate = out.u.dot(Vec3T<S>(c.v[1] - c.v[0])) / L - out.chord * L_rate / (L * L);
    const double EA = axialStiffness();
    out.elastic = out.strain > 0.0 ? S(EA * out.strain) : S(0.0);
    const S damped = out.strain + damping * out.strain_rate;
    out.tension = damping > 0.0 ? (damped > 0.0 ? S(EA * damped) : S(0.0)) : out.elastic;
    return out;
  }
  /// Element `e` of part `k`.
  template <class S> Axial<S> axial(const State<S>& s, int k, int e) const { return axial(cable(s, k, e)); }

  template <class S> S elementLength(const Cable<S>& c) const { return (c.sigma[0] - c.sigma[1]) / double(elements_per_part); }
  template <class S> S elementLength(const State<S>& s, int k) const {
    return (s.sigma[k] - s.sigma[k + 1]) / double(elements_per_part);
  }

  /// Element e of part k's share of the residual (file comment), α = mass_damping: its pull and
  /// weight on its ends, its ∂V/∂L_e on σ_k and σ_{k+1}; the inertia of its start node where that
  /// is an inner node (and the node's kinetic term on σ); the last element before a sheave adds
  /// the sheave's inertia and friction, its own tension T_{i−1}^end.
  template <class S>
  CableResidual<S> cableResidual(const Cable<S>& c, int k, int e, const Vec3& gravity, double mass_damping) const {
    const int n = elements_per_part;
    const double rhoA = lineDensity();
    const S L = elementLength(c);
    const Axial<S> ax = axial(c);
    const Vec3T<S> pull = ax.tension * ax.u;
    const Vec3T<S> half_weight = (0.5 * rhoA * gravity).cast<S>() * L;
    CableResidual<S> r;
    r.node[0] = -pull - half_weight;
    r.node[1] = pull - half_weight;
    const S spent = ax.tension - ax.elastic;
    S length_force = -ax.elastic * (1.0 + 0.5 * ax.strain) - spent * (1.0 + ax.strain) -
                     (0.5 * rhoA) * Vec3T<S>(c.x[0] + c.x[1]).dot(gravity.cast<S>());
    if (e > 0) {
      r.node[0] += (rhoA * L) * (c.a + mass_damping * c.v[0]).template cast<S>();
      length_force -= 0.5 * rhoA * c.v[0].squaredNorm();
    }
    length_force /= double(n);
    r.sigma[0] = length_force;
    r.sigma[1] = -length_force;
    if (e == n - 1 && k + 1 < parts()) {  // the sheave at path point k + 1, between part k and part k + 1
      const int i = k + 1;
      r.sigma[1] += sheave_mass[i - 1] * (c.sigma_acceleration + mass_damping * c.sigma_rate[1]);
      r.sigma[1] += friction(i, ax.tension, c.sigma_rate[1]);
    }
    return r;
  }

  /// The residual at the state s (file comment), α = mass_damping: the cables' shares summed.
  template <class S> Residual<S> residual(const State<S>& s, const Vec3& gravity, double mass_damping) const {
    Residual<S> r;
    r.chain.assign(static_cast<std::size_t>(chainNodes()), Vec3T<S>::Zero());
    r.sigma.assign(static_cast<std::size_t>(parts() + 1), S(0.0));
    for (int k = 0; k < parts(); ++k)
      for (int e = 0; e < elements_per_part; ++e) {
        const CableResidual<S> c = cableResidual(cable(s, k, e), k, e, gravity, mass_damping);
        const int a = k * elements_per_part + e;
        r.chain[a] += c.node[0];
        r.chain[a + 1] += c.node[1];
        r.sigma[k] += c.sigma[0];
        r.sigma[k + 1] += c.sigma[1];
      }
    return r;
  }

  /// f_i = T_{i−1}^end (e^(λ_i tanh(σ̇_i / b)) − 1).
  template <class S> S friction(int i, const S& tension, const S& speed) const {
    const double exponent = friction_exponent[i - 1];
    if (exponent == 0.0) return S(0.0);
    using std::exp;
    using std::tanh;
    return tension * (exp(exponent * tanh(speed / speed_band)) - 1.0);
  }

  double kineticEnergy(const State<double>& s) const {
    double energy = 0.0;
    for (int k = 0; k < parts(); ++k)
      for (int e = 1; e < elements_per_part; ++e)
        energy += 0.5 * lineDensity() * elementLength(s, k) * s.v[k * elements_per_part + e].squaredNorm();
    for (int i = 1; i < parts(); ++i) energy += 0.5 * sheave_mass[i - 1] * s.sigma_rate[i] * s.sigma_rate[i];
    return energy;
  }

  double potentialEnergy(const State<double>& s, const Vec3& gravity) const {
    double energy = 0.0;
    for (int k = 0; k < parts(); ++k) {
      const double L = elementLength(s, k);
      for (int e = 0; e < elements_per_part; ++e) {
        const int a = k * elements_per_part + e;
        const double strain = std::max((s.x[a + 1] - s.x[a]).norm() / L - 1.0, 0.0);
        energy += 0.5 * axialStiffness() * L * strain * strain - 0.5 * lineDensity() * L * gravity.dot(s.x[a] + s.x[a + 1]);
      }
    }
    return energy;
  }

  /// L̇ ∂(T + V)/∂σ_0 at fixed state, plus the damping stress' power on the stretch rate that
  /// L̇ causes in the lead part's elements (file comment).
  double explicitTimePower(const State<double>& s, const Vec3& gravity) const {
    const double rate = s.sigma_rate[0];
    if (rate == 0.0) return 0.0;
    const int n = elements_per_part;
    const double L = elementLength(s, 0);
    double dV = 0.0, damper = 0.0;
    for (int e = 0; e < n; ++e) {
      const Axial<double> ax = axial(s, 0, e);
      dV += -ax.elastic * (1.0 + 0.5 * ax.strain) - 0.5 * lineDensity() * gravity.dot(s.x[e] + s.x[e + 1]);
      damper += (ax.tension - ax.elastic) * (-ax.chord / L);  // L_e ΔT ∂ε/∂L_e
    }
    double dT = 0.0;
    for (int e = 1; e < n; ++e) dT += 0.5 * lineDensity() * s.v[e].squaredNorm();
    return rate * (dV + dT + damper) / n;
  }

  /// Σ_e L_e ΔT ε̇ + Σ_i f_i σ̇_i ≥ 0.
  double dissipatedPower(const State<double>& s) const {
    double power = 0.0;
    for (int k = 0; k < parts(); ++k) {
      const double L = elementLength(s, k);
      for (int e = 0; e < elements_per_part; ++e) {
        const Axial<double> ax = axial(s, k, e);
        power += L * (ax.tension - ax.elastic) * ax.strain_rate;
      }
      if (k + 1 < parts())
        power += friction(k + 1, axial(s, k, elements_per_part - 1).tension, s.sigma_rate[k + 1]) * s.sigma_rate[k + 1];
    }
    return power;
  }
};

}  // namespace cranesim
