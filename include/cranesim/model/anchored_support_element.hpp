#pragma once
// A support's shear springs tied to one anchor that slides in the bed's plane: friction with
// memory. A pad, or a crawler track's stretches, are points of one rigid body, so their bed
// slides as one rigid plate under them: the anchor's coordinates s = (d₁, d₂, θ) move the points'
// drawn places X_i by d = d₁ t₁ + d₂ t₂ (t₁, t₂ across `up`) and turn them by θ about `up`
// round the support's drawn centre C:
//   A_i = C + d + Rot(θ)(X_i − C),   e_i = across(P_i − A_i),   F_i = −k_i e_i − c_i ė_i
// on the point P_i of the body. The springs pull the anchor with the resultant F = Σ k_i e_i
// and the moment M = Σ up · (r_i × k_i e_i) about the centre of friction c (the points'
// friction-weighted centre, r_i = A_i − c), which slide together within the ellipse
//   |F|² + (M/ρ)² ≤ (μN)²,   μN = Σ μ_i N_i,   ρ = Σ μ_i N_i √(|r_i|² + r₀ᵢ²) / μN
// (ρ the friction's lever about c when the plate turns about it; r₀ᵢ a point's own footprint's
// lever). It is exact for a pure slide and a pure turn about c and overestimates combined
// ones: a rigid strip pushed across at its end slides at μN/√5 where Coulomb's law per point
// gives (√2 − 1) μN (+8 %). In the scaled space g = (F·t₁, F·t₂, M/ρ) the anchor follows the
// slip law of a single point:
//   ε ṡ_v + ṡ − w = 0,   ν = ĝ (α(|g|/μN) s₊(Ẇ·ĝ) + r(|g| − μN) / (Σk τ)),
// Ẇ = (the body's velocity at c across up, ρ × its turn rate about up), ν the anchor's velocity
// at c and ρ θ̇ (w is ν in the coordinates s), α a smoothstep from 0 at 0.9 μN to 1 at μN + b
// (exact stick below), s₊ a smoothed positive part, r a C¹ ramp by which an anchor whose bound
// fell (a support unloading) catches up, ε a lag that gives every coordinate a mass.
// Statics and modes hold the anchor where it was drawn (on a spring that rings at 1 kHz on the
// lag's mass) and bound each point's spring force smoothly by μ_i N_i beyond its stick's onset:
// a statics pushed past μN has no equilibrium, a lifted point carries nothing.

#include "cranesim/model/element.hpp"
#include "cranesim/model/support_elements.hpp"

namespace cranesim {

class AnchoredSupportElement final : public Element {
 public:
  static constexpr double kAnchorLag = 1e-6;        // ε, s
  static constexpr double kStickFraction = 0.9;     // exact stick below this fraction of μN
  static constexpr double kSlipBandFloor = 100.0;   // N: the slip band's least width b; full slip at μN + b
  static constexpr double kCatchUpTime = 1e-2;      // τ, s
  static constexpr double kCatchUpFraction = 0.05;  // r's quadratic start spans this fraction of μN (+ b)
  static constexpr double kHeldAnchorFrequency = 1e3;  // Hz: the held anchor's modes (statics, modes)

  /// `footprints`: each point's bed area (its own lever r₀ = ⅔ √(A/π), a disc's). The body's
  /// [r, φ] and the anchor's s are the coordinates, in this order.
  AnchoredSupportElement(std::vector<SupportPoint> points, const std::vector<double>& footprints, int body, int anchor,
                         std::vector<int> q_indices, std::vector<int> v_indices);
  const std::vector<int>& nodes() const override { return nodes_; }
  int size() const override { return 9; }
  const std::vector<int>& velocityIndices() const override { return v_; }
  const std::vector<int>& coordinateIndices() const override { return q_; }
  void residual(const ElementInput& in, double* r) const override;
  void jacobian(const ElementInput& in, double cj, double* J) const override;
  void coordinateJacobian(const ElementInput& in, double* J) const override;
  void mass(const ElementInput& in, double* M) const override;
  double kineticEnergy(const ElementInput&) const override { return 0.0; }
  double potentialEnergy(const ElementInput& in) const override;
  double dissipatedPower(const ElementInput& in) const override;

 private:
  using Local = Eigen::Matrix<double, 9, 1>;
  template <class S> Eigen::Matrix<S, 9, 1> rows(const Eigen::Matrix<S, 9, 1>& q, const Eigen::Matrix<S, 9, 1>& v, bool held) const;
  template <class S> Eigen::Matrix<S, 9, 1> heldRows(const Eigen::Matrix<S, 9, 1>& q, const Eigen::Matrix<S, 9, 1>& v) const;
  Local gather(const double* x, const std::vector<int>& at) const;
  /// Per point: its offset e_i from its anchor, its velocity Ṗ_i and its anchor's Ȧ_i, across up.
  struct PointSlip {
    Vec3 offset, moving, anchor_moving;
  };
  std::vector<PointSlip> slips(const Local& q, const Local& v) const;

  std::vector<SupportPoint> points_;
  std::vector<double> levers_;        // r₀ᵢ
  std::vector<Vec3> drawn_arms_;      // across(X_i − C)
  Vec3 up_, across1_, across2_, centre_;
  double stiffness_ = 0.0;            // Σ k_i
  std::vector<int> nodes_, q_, v_;
};

}  // namespace cranesim
