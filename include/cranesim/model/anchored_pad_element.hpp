#pragma once
// A support point's shear spring tied to an anchor that slides: friction with memory.
// The anchor a (a Point node: how far the pad's bed has slid from where it was drawn) follows a first-order slip law,
// regularised by a lag ε on its velocity so that every coordinate keeps a mass:
//   ε ȧ_v + v_a − w(q, v, a) = 0,   w = ê (α(k|e|/μN) s₊(Ṗ·ê) + r(k|e| − μN) / (k τ)),
// e the pad's horizontal offset from its anchor, α a smoothstep from 0 at 0.9 μN to 1 at μN
// (exact stick below 0.9 μN), s₊ a smoothed positive part, r a C¹ ramp that lets an anchor
// whose bound fell (a pad unloading) catch up. The pad feels F = −k e − c ė. Statics and modes
// hold the anchor where it was drawn and bound the same force smoothly by μN beyond the stick's
// onset: a statics pushed past μN has no equilibrium, a lifted point carries nothing.

#include "cranesim/model/element.hpp"
#include "cranesim/model/support_elements.hpp"

namespace cranesim {

class AnchoredPadElement final : public Element {
 public:
  static constexpr double kAnchorLag = 1e-6;      // ε, s
  static constexpr double kStickFraction = 0.9;   // exact stick below this fraction of μN
  static constexpr double kSlipBandFloor = 100.0;  // N: the slip band's least width; full slip at μN + this
  static constexpr double kCatchUpTime = 1e-2;     // τ, s
  static constexpr double kCatchUpFraction = 0.05;  // r's quadratic start spans this fraction of μN (+ the floor)

  AnchoredPadElement(const SupportPoint& pad, int body, int anchor, std::vector<int> q_indices, std::vector<int> v_indices);
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
  Local gather(const double* x, const std::vector<int>& at) const;

  SupportPoint pad_;
  std::vector<int> nodes_, q_, v_;
};

}  // namespace cranesim
