#pragma once
// The wind on the parts a scene exposes to it, as elements without mass whose force is the
// aerodynamic drag (elements/wind_drag.hpp) of the wind field (model/wind_field.hpp) relative to
// the part's own motion. They sit on the nodes of the part they load, so the Jacobian's pattern
// does not change, and provide their velocity derivative in closed form: drag is not a
// polynomial in the velocities, which KernelElement's polarization assumes.
//   residual   r = −Q(q, dq, t) · load factor  (the generalized wind force Q on the right-hand side)
//   Jacobian   ∂r/∂q by forward AD of the same code, ∂r/∂dq in closed form; no mass.

#include <memory>
#include <vector>

#include "cranesim/math/gauss_legendre.hpp"
#include "cranesim/model/element.hpp"
#include "cranesim/model/rope_path.hpp"
#include "cranesim/model/wind_field.hpp"

namespace cranesim {

class WindElement : public Element {
 public:
  /// Local coordinates or velocities: at most two nodes of kMaxNodeSize values, on the stack.
  using Local = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, 14, 1>;

  WindElement(std::shared_ptr<const WindField> wind, std::vector<int> nodes, std::vector<int> q_indices,
              std::vector<int> v_indices);

  const std::vector<int>& nodes() const override { return nodes_; }
  int size() const override { return static_cast<int>(v_.size()); }
  const std::vector<int>& velocityIndices() const override { return v_; }
  const std::vector<int>& coordinateIndices() const override { return q_; }
  void residual(const ElementInput& in, double* r) const override;
  void jacobian(const ElementInput& in, double cj, double* J) const override;
  void coordinateJacobian(const ElementInput& in, double* J) const override;
  void mass(const ElementInput& in, double* M) const override;
  double kineticEnergy(const ElementInput&) const override { return 0.0; }
  double potentialEnergy(const ElementInput&) const override { return 0.0; }

  /// The resultant of the wind's forces on the part at (q, dq, t), N, inertial.
  virtual Vec3 resultantForce(const ElementInput& in) const = 0;
  /// The wind's power on the part, Q · dq, W.
  double power(const ElementInput& in) const;

 protected:
  /// The generalized wind force Q (size() values) at the element's local q, dq.
  virtual void force(const Local& q, const Local& v, double t, double* Q) const = 0;
  /// ∂Q/∂q and ∂Q/∂dq, column-major, size() × size() each.
  virtual void tangents(const Local& q, const Local& v, double t, double* Qq, double* Qv) const = 0;

  Local gather(const double* x, const std::vector<int>& at) const;

  std::shared_ptr<const WindField> wind_;

 private:
  std::vector<int> nodes_, q_, v_;
};

/// The wind on a bluff rigid body at a point fixed on it: F = ½ ρ c A |u| u with the full
/// relative velocity u = w(r_P) − ṙ_P of the point P = r + R p, and its moment about the origin,
/// Q = [F, p × Rᵀ F] on the body's [ṙ, ω].
class BodyWindElement final : public WindElement {
 public:
  /// `drag_area` c A, m²; `point` p in body axes.
  BodyWindElement(std::shared_ptr<const WindField> wind, double drag_area, const Vec3& point, int node,
                  std::vector<int> q_indices, std::vector<int> v_indices);
  Vec3 resultantForce(const ElementInput& in) const override;

 private:
  template <class S> Eigen::Matrix<S, 6, 1> generalizedForce(const Eigen::Matrix<S, 6, 1>& q, const Eigen::Matrix<double, 6, 1>& v,
                                                             double t) const;
  void force(const Local& q, const Local& v, double t, double* Q) const override;
  void tangents(const Local& q, const Local& v, double t, double* Qq, double* Qv) const override;

  double coefficient_;  // ½ ρ c A
  Vec3 point_;
};

/// The wind on a cylinder along the chord between two nodes (a rope or beam element, a tube):
/// f = ½ ρ c d |u⊥| u⊥ per unit length at the Gauss points of the chord, u⊥ the relative
/// velocity normal to it, and w and ṙ interpolated linearly between the nodes' positions, to
/// which the forces go with the same weights. Only the nodes' positions and their velocities
/// (the first three coordinates of every kind of node) enter.
class LineWindElement final : public WindElement {
 public:
  /// `drag_diameter` c d, m.
  LineWindElement(std::shared_ptr<const WindField> wind, double drag_diameter, int points, int node1, int node2,
                  int second_node_offset, std::vector<int> q_indices, std::vector<int> v_indices);
  Vec3 resultantForce(const ElementInput& in) const override;

 private:
  template <class S> Eigen::Matrix<S, 6, 1> endForces(const Vec3T<S>& r1, const Vec3T<S>& r2, const Vec3& v1, const Vec3& v2,
                                                      double t) const;
  void force(const Local& q, const Local& v, double t, double* Q) const override;
  void tangents(const Local& q, const Local& v, double t, double* Qq, double* Qv) const override;

  double coefficient_;  // ½ ρ c d
  GaussRule rule_;
  int second_;  // local offset of the second node
};

/// The wind on one cable of a massive reeved rope's part (model/massive_reeved_rope_element.hpp):
/// the cylinder of LineWindElement between two points that may sit on turning bodies (a sheave's
/// centre, the winch, the dead end) or be the part's inner nodes, placed and loaded through the
/// rope's path mapping (model/rope_path.hpp). Both tangents by forward AD.
class PathLineWindElement final : public WindElement {
 public:
  /// `drag_diameter` c d, m; `ends` the two points on the element's nodes.
  PathLineWindElement(std::shared_ptr<const WindField> wind, double drag_diameter, int points, RopePath ends,
                      std::vector<int> nodes, std::vector<int> q_indices, std::vector<int> v_indices);
  Vec3 resultantForce(const ElementInput& in) const override;

 private:
  template <class S> Eigen::Matrix<S, Eigen::Dynamic, 1, Eigen::ColMajor, 14, 1> generalizedForce(
      const Eigen::Matrix<S, Eigen::Dynamic, 1, Eigen::ColMajor, 14, 1>& q,
      const Eigen::Matrix<S, Eigen::Dynamic, 1, Eigen::ColMajor, 14, 1>& v, double t, Vec3T<S>* resultant = nullptr) const;
  void force(const Local& q, const Local& v, double t, double* Q) const override;
  void tangents(const Local& q, const Local& v, double t, double* Qq, double* Qv) const override;

  double coefficient_;  // ½ ρ c d
  GaussRule rule_;
  RopePath ends_;
};

/// A tube of a lattice section between two of its nodes (LatticeWindElement's points), with its
/// c d (m) times the shielding weight.
struct WindTube {
  int from = 0, to = 0;
  double drag_diameter = 0.0;
};

/// The wind on a lattice section's tubes, placed by its two end-section frames. A node p of the
/// truss (truss frame: x along the axis from end section 1 at x = 0 to end section 2 at
/// x = length) moves as (1 − s)(r₁ + R₁ p₁) + s (r₂ + R₂ p₂), s = p_x/length, p₁ and p₂ its
/// offsets from the two end sections: the nodes follow the sections rigidly and linearly in
/// between, the same for every fidelity of the section. Each tube is a cylinder on the chord
/// between its nodes as in LineWindElement, with the wind taken at the nodes and interpolated
/// linearly (a tube is a few metres long); its forces go to its nodes and from them to the end
/// sections' [ṙ, ω] with the same weights.
class LatticeWindElement final : public WindElement {
 public:
  LatticeWindElement(std::shared_ptr<const WindField> wind, std::vector<Vec3> points, std::vector<WindTube> tubes,
                     double length, int gauss_points, int section1, int section2, std::vector<int> q_indices,
                     std::vector<int> v_indices);
  Vec3 resultantForce(const ElementInput& in) const override;

 private:
  using Q12 = Eigen::Matrix<double, 12, 1>;
  template <class S> Eigen::Matrix<S, 12, 1> generalizedForce(const Eigen::Matrix<S, 12, 1>& q, const Q12& v, double t) const;
  /// The 3 × 12 map from the sections' [ṙ₁, ω₁, ṙ₂, ω₂] to the velocity of node n.
  Eigen::Matrix<double, 3, 12> nodeVelocityMap(const Mat3& R1, const Mat3& R2, int n) const;
  void force(const Local& q, const Local& v, double t, double* Q) const override;
  void tangents(const Local& q, const Local& v, double t, double* Qq, double* Qv) const override;

  std::vector<Vec3> points_;
  std::vector<WindTube> tubes_;
  double length_;
  GaussRule rule_;
  double half_density_;  // ½ ρ
};

}  // namespace cranesim
