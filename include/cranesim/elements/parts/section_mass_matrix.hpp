#pragma once
// The mass matrix of material riding on an interpolated section (timoshenko_beam.hpp: cubic
// Hermite centre line with unit end slopes Rⁿ e_x, geodesic section rotation R_c = R¹ E_R with
// E_R = exp(ψ̃), ψ = ξφ, φ = log(R¹ᵀR²)), summed over mass stations (ξ, m, s, J) as in
// section_inertia_tangent.hpp:
//   M = Σ H_xᵀ (m H_x − R_c s̃ H_Ω) + H_Ωᵀ (s̃ R_cᵀ H_x + J H_Ω),
//   H_x = [N₀ I, −N₁ R¹ Ẽ₀, N₂ I, −N₃ R¹ Ẽ₁],  Ẽ₀ = ẽ_x,  Ẽ₁ = R_rel ẽ_x,  R_rel = R¹ᵀR²,
//   H_Ω = [0, W₀, 0, W₁],  W₁ = ξ E_T T(φ)⁻¹,  W₀ = E_Rᵀ − W₁ R_relᵀ,  E_T = T(ψ) (B-8).
// R¹, R_rel and T(φ)⁻¹ do not depend on ξ: they leave the station sums, which keep only
// station-sized pieces in the axes of end 1. With u = E_R s and E_R E_T = E_Tᵀ (so that
// E_R s̃ W₁ = ξ ũ E_Tᵀ T(φ)⁻¹):
//   μ_kl = Σ m N_k N_l,   U_k = Σ N_k u,   S_k = Σ ξ N_k ũ E_Tᵀ,
//   A₀₀ = Σ E_R J E_Rᵀ,   A₀₁ = Σ ξ E_R J E_T,   A₁₁ = Σ ξ² E_Tᵀ J E_T;
// then B_kj = Σ N_k E_R s̃ W_j and D_ij = Σ W_iᵀ J W_j are
//   B_k1 = S_k T(φ)⁻¹,   B_k0 = Ũ_k − B_k1 R_relᵀ,
//   D₁₁ = T(φ)⁻ᵀ A₁₁ T(φ)⁻¹,   X = Σ E_R J W₁ = A₀₁ T(φ)⁻¹,   D₀₁ = X − R_rel D₁₁,
//   D₀₀ = A₀₀ − X R_relᵀ − R_rel Xᵀ + R_rel D₁₁ R_relᵀ,
// and M's blocks (nodes i, j; t(i) = 2i and r(i) = 2i + 1 number the Hermite functions):
//   M[rⁱ, rʲ] = μ_t(i)t(j) I,
//   M[rⁱ, θʲ] = −R¹ (μ_t(i)r(j) Ẽ_j + B_t(i)j),
//   M[θⁱ, θʲ] = μ_r(i)r(j) Ẽ_iᵀ Ẽ_j + Ẽ_iᵀ B_r(i)j + B_r(j)iᵀ Ẽ_j + D_ij.
// A station costs E_R, E_T (or none, when the caller has them) and five 3 × 3 products.

#include "cranesim/math/hermite.hpp"
#include "cranesim/math/rotation.hpp"

namespace cranesim {

template <class S> class SectionMassMatrix {
 public:
  using Mat12 = Eigen::Matrix<S, 12, 12>;

  /// End rotation R¹, relative rotation R_rel = R¹ᵀR², φ = log(R_rel), T(φ)⁻¹, and the length
  /// that scales the Hermite slopes.
  SectionMassMatrix(const Mat3T<S>& R1, const Mat3T<S>& Rrel, const Vec3T<S>& phi, const Mat3T<S>& Tinv, double length)
      : length_(length), R1_(R1), Rrel_(Rrel), phi_(phi), Tinv_(Tinv) {
    for (auto& row : mu_)
      for (S& x : row) x = S(0.0);
    for (int k = 0; k < 4; ++k) U_[k].setZero(), S_[k].setZero();
    A00_.setZero(), A01_.setZero(), A11_.setZero();
  }

  /// Adds a mass station: mass m, first moment s and inertia J about the axis point (section
  /// axes) on the section at ξ.
  void add(double xi, double mass, const Vec3& first_moment, const Mat3& inertia) {
    const RotationAndRateMap<S> E = rotationAndRateMap<S>(Vec3T<S>(S(xi) * phi_));
    add(xi, E.R, E.T, mass, first_moment, inertia);
  }

  /// The same with E_R = exp(ξφ̃) and E_T = T(ξφ) at hand.
  void add(double xi, const Mat3T<S>& ER, const Mat3T<S>& ET, double mass, const Vec3& first_moment, const Mat3& inertia) {
    addStation(hermiteBasis(xi, length_), xi, ER, ET, mass, first_moment, inertia);
  }

  /// M of the stations added (file comment).
  Mat12 matrix() const {
    using M3 = Mat3T<S>;
    const M3 RrelT = Rrel_.transpose();
    const M3 ex = skew<S>(Vec3T<S>(Vec3::UnitX().cast<S>()));
    const M3 E[2] = {ex, M3(Rrel_ * ex)};
    M3 B[4][2];
    for (int k = 0; k < 4; ++k) {
      B[k][1] = S_[k] * Tinv_;
      B[k][0] = skew<S>(U_[k]) - B[k][1] * RrelT;
    }
    const M3 D11 = Tinv_.transpose() * A11_ * Tinv_;
    const M3 X = A01_ * Tinv_;
    const M3 D01 = X - Rrel_ * D11;
    const M3 D[2][2] = {{M3(A00_ - X * RrelT - Rrel_ * X.transpose() + Rrel_ * D11 * RrelT), D01},
                        {M3(D01.transpose()), D11}};
    Mat12 M;
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) {
        M.template block<3, 3>(6 * i, 6 * j) = mu(2 * i, 2 * j) * M3::Identity();
        const M3 translation_rotation = -R1_ * (mu(2 * i, 2 * j + 1) * E[j] + B[2 * i][j]);
        M.template block<3, 3>(6 * i, 6 * j + 3) = translation_rotation;
        M.template block<3, 3>(6 * j + 3, 6 * i) = translation_rotation.transpose();
        M.template block<3, 3>(6 * i + 3, 6 * j + 3) = mu(2 * i + 1, 2 * j + 1) * (E[i].transpose() * E[j]) +
                                                       E[i].transpose() * B[2 * i + 1][j] +
                                                       B[2 * j + 1][i].transpose() * E[j] + D[i][j];
      }
    return M;
  }

 protected:
  /// add with the station's Hermite basis h at hand.
  [[gnu::flatten]] void addStation(const HermiteBasis& h, double xi, const Mat3T<S>& ER, const Mat3T<S>& ET, double mass,
                            const Vec3& first_moment, const Mat3& inertia) {
    for (int k = 0; k < 4; ++k)
      for (int l = k; l < 4; ++l) mu_[k][l] += S(mass * h.N[k] * h.N[l]);
    if (first_moment != Vec3::Zero()) {
      const Vec3T<S> u = ER * first_moment.cast<S>();
      const Mat3T<S> uET = skew<S>(u) * ET.transpose();
      for (int k = 0; k < 4; ++k) {
        U_[k] += S(h.N[k]) * u;
        S_[k] += S(xi * h.N[k]) * uET;
      }
    }
    const Mat3T<S> J = inertia.cast<S>();
    const Mat3T<S> RJ = ER * J, TJ = ET.transpose() * J;
    A00_.noalias() += RJ * ER.transpose();
    A01_.noalias() += S(xi) * (RJ * ET);
    A11_.noalias() += S(xi * xi) * (TJ * ET);
  }

  /// μ_kl = Σ m N_k N_l.
  S mu(int k, int l) const { return k <= l ? mu_[k][l] : mu_[l][k]; }

  double length_;
  Mat3T<S> R1_, Rrel_;
  Vec3T<S> phi_;
  Mat3T<S> Tinv_;
  S mu_[4][4];  // μ_kl, k ≤ l
  Vec3T<S> U_[4];
  Mat3T<S> S_[4], A00_, A01_, A11_;
};

}  // namespace cranesim
