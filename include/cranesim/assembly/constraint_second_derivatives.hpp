#pragma once
// A constraint's equations, its velocity Jacobian G and the derivatives of G with respect to the
// node coordinates and time, which the DAE Jacobian needs (∂(Gᵀλ)/∂q, ∂(G dq + Φ_t)/∂q), in
// closed form through the equations' primitives (model/constraint_equations.hpp).
//
// Each joint frame moves with its node: r_J = r + R o, R_J = R R_rel. The twist δ = [δr, δθ] of
// G (constraint_evaluation.hpp) moves it to r + δr + R(I + δθ̃) o, R(I + δθ̃) R_rel, and a change
// of the node's coordinates dq = [dr, dφ] to the same with δ = [dr, T(φ) dφ] to first order
// (R(φ + dφ) = R(I + (T dφ)~), 2-10). Every vector x of the equations is therefore affine in δ,
//     x = x₀ + J_x δ,   J_x = [I, −R õ] for r_J,  [0, −R ũ] for e = R u (u = R_rel g_k),
// and the second derivative of G along dq comes from R(I + ã)(I + b̃) u alone:
//     ∂²(x·y)/∂b_j ∂a_l = (J_xᵀ J_y + J_yᵀ J_x)_jl + W_x(y)_jl + W_y(x)_jl,
//     W_x(y) = w uᵀ − (w·u) I   on x's rotation block, w = Rᵀ y   (w·(e_l × (e_j × u))).
// With Φ = h(p, t), h's first and second derivatives (forward AD over h alone, a handful of
// operations):  G = Σ h_a ∇p_a,  ∂G/∂a = Σ h_a ∇²p_a + Σ h_ac ∇p_a ∇p_cᵀ  (+ h's time terms),
// and ∂/∂φ = ∂/∂a T(φ). Checked against nested forward AD of the equations (tests).
//
// The DAE Jacobian needs ∂G_i/∂q only contracted — with the multipliers over the rows i
// (Σ λ_i ∂G_i/∂q), or with a velocity or acceleration over G's directions or q's — so the
// curvatures ∇²p_a are never formed: each contraction is taken primitive by primitive, on the
// 3 × 3 blocks of J_x and J_y that are not zero (a spherical joint's three primitives have no
// J_xᵀ J_y term at all, a fixed joint's rotation locks one block each).
//
// ∇²p_a is not symmetric (the twists of a rotation do not commute: W_x(y)), so contracting over
// G's directions (rows) and over the coordinates (columns) are different operations.

#include <array>

#include "cranesim/assembly/constraint_evaluation.hpp"
#include "cranesim/model/model.hpp"

namespace cranesim {

class ConstraintSecondDerivatives {
 public:
  using Mat13 = Eigen::Matrix<double, kConstraintDirections, kConstraintDirections>;
  using Vec13 = Eigen::Matrix<double, kConstraintDirections, 1>;
  /// One row per equation, over [q₁, q₂, t] or over G's directions (time last).
  using Rows13 = Eigen::Matrix<double, kMaxConstraintRows, kConstraintDirections>;

  ConstraintSecondDerivatives(const Model& model, const Constraint& c, const double* q, double t);

  int rows = 0;
  Eigen::Matrix<double, kMaxConstraintRows, 1> phi;
  /// G: ∂Φ/∂[δ₁, δ₂] and Φ_t (column kTimeDirection), as ConstraintDerivatives::G.
  Eigen::Matrix<double, kMaxConstraintRows, kConstraintDirections> G;
  /// Φ_q: ∂Φ/∂[q₁, q₂], the nodes' coordinates [r, φ].
  Eigen::Matrix<double, kMaxConstraintRows, 12> phi_q;

  /// Σᵢ wᵢ ∂G_ij/∂[q₁, q₂, t]_k (j over G's directions, time included; k over the coordinates).
  Mat13 weighted(const double* w) const;
  /// Row i: Σ_j u_j ∂G_ij/∂[q₁, q₂, t]_k, u over G's directions (time included).
  Rows13 directionContractions(const Vec13& u) const;
  /// Row i: Σ_k ∂G_ij/∂[q₁, q₂, t]_k u_k, u over the coordinates and time.
  Rows13 coordinateContractions(const Vec13& u) const;
  /// ∂G_ij/∂[q₁, q₂, t]_k of row i (weighted by the unit vector of row i).
  Mat13 secondDerivative(int i) const;

 private:
  using Mat12 = Eigen::Matrix<double, 12, 12>;
  using Vec12 = Eigen::Matrix<double, 12, 1>;
  using Mat3x12 = Eigen::Matrix<double, 3, 12>;
  /// h's derivatives are taken in the primitives' directions and time (index kTime).
  static constexpr int kTime = kMaxConstraintPrimitives;
  static constexpr int kHDirections = kMaxConstraintPrimitives + 1;
  using HessianH = Eigen::Matrix<double, kHDirections, kHDirections>;
  using RowRef = Eigen::Ref<Eigen::Matrix<double, 1, kConstraintDirections>, 0, Eigen::InnerStride<>>;

  /// One joint of the constraint: its node's frame and rate map, and the joint frame on it.
  struct Side {
    bool moves = false;    // on a node (not the ground)
    bool rotates = false;  // on a frame node
    Mat3 R = Mat3::Identity(), T = Mat3::Identity();
    Vec3 offset = Vec3::Zero();
    Mat3 relative = Mat3::Identity();
    Vec3 rJ = Vec3::Zero();
    Mat3 RJ = Mat3::Identity();
  };
  /// A vector of the equations, affine in the twists: x = value + J δ, J's 3 × 3 blocks
  /// [δr₁, δθ₁, δr₂, δθ₂] non-zero where `blocks` has their bit. Its rotation R(I + δθ̃) u on
  /// side s contributes W_x(y), with u = lever[s] and sign[s] (0: none).
  struct Jet {
    Vec3 value;
    Mat3x12 J;
    unsigned blocks;
    Vec3 lever[2];
    double sign[2];
    /// J δ and Jᵀ v (added to out), over the non-zero blocks.
    Vec3 apply(const Vec12& delta) const;
    void addTransposed(const Vec3& v, Vec12& out) const;
  };

  static Side side(const Model& model, int joint, const double* q);
  Jet jet(ConstraintVectorRef ref) const;
  /// Σ_a W_a ∇²p_a over the twists (12 × 12), added to H.
  void addCurvatures(const double* W, Eigen::Ref<Mat12> H) const;
  /// Row i: ∂G_i/∂[δ, t] (both indices over the twists and time) contracted with u, in the
  /// twists, over its first index (over G's directions) or its second.
  Rows13 twistContractions(const Vec13& u, bool over_directions) const;
  /// From the twists to the coordinates over the columns: ∂/∂φ = ∂/∂a T(φ) (a = the twist).
  template <class Matrix> void toCoordinateColumns(Matrix& m) const;
  /// ĝ_a·u and row += scale ĝ_aᵀ, ĝ_a = [∇p_a, 0] over the twists and time, or e_time for a = kTime.
  double gradientDot(int a, const Vec13& u) const;
  void addGradient(int a, double scale, RowRef row) const;
  /// The directions of h: the primitives, then time.
  int hDirection(int n) const { return n < primitives_ ? n : kTime; }

  std::array<Side, 2> side_;
  int primitives_ = 0;
  std::array<Jet, kMaxConstraintPrimitives> x_, y_;
  std::array<Vec12, kMaxConstraintPrimitives> gradient_;
  /// ∂h_i/∂(p, t) and, when `curved_` (h not linear in p or depending on time), ∂²h_i/∂(p, t)².
  Eigen::Matrix<double, kMaxConstraintRows, kHDirections> h1_;
  std::array<HessianH, kMaxConstraintRows> h2_;
  bool curved_ = false;
};

}  // namespace cranesim
