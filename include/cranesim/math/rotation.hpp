#pragma once
// Rotation-vector kinematics (thesis 2.1.2, B.2.1). All functions are templated on the
// scalar so that the same code yields values and exact derivatives.
//
// Convention: R = exp(φ̃) maps body axes to inertial axes; the body-frame angular velocity is
// ω = T(φ) φ̇ (2-10, B-8). The coefficient functions are evaluated through θ² with Taylor
// series near θ = 0, so they and their derivatives stay finite at the identity.

#include <cmath>
#include <numbers>

#include "cranesim/math/autodiff.hpp"

namespace cranesim {

template <class S> Mat3T<S> skew(const Vec3T<S>& a) {
  Mat3T<S> m;
  m << S(0.0), -a(2), a(1), a(2), S(0.0), -a(0), -a(1), a(0), S(0.0);
  return m;
}

inline Vec3 unskew(const Mat3& m) { return {m(2, 1), m(0, 2), m(1, 0)}; }

namespace detail {
inline constexpr double kSeriesThreshold = 1e-4;  // θ² below which Taylor series are used

// sin θ / θ
template <class S> S sinc(const S& t2) {
  using std::sin, std::sqrt;
  if (t2 < kSeriesThreshold) return 1.0 - t2 / 6.0 + t2 * t2 / 120.0 - t2 * t2 * t2 / 5040.0;
  const S t = sqrt(t2);
  return sin(t) / t;
}
// (1 − cos θ) / θ²
template <class S> S cosc(const S& t2) {
  using std::cos, std::sqrt;
  if (t2 < kSeriesThreshold) return 0.5 - t2 / 24.0 + t2 * t2 / 720.0 - t2 * t2 * t2 / 40320.0;
  return (1.0 - cos(sqrt(t2))) / t2;
}
// (θ − sin θ) / θ³
template <class S> S sinc3(const S& t2) {
  using std::sin, std::sqrt;
  if (t2 < kSeriesThreshold) return 1.0 / 6.0 - t2 / 120.0 + t2 * t2 / 5040.0 - t2 * t2 * t2 / 362880.0;
  const S t = sqrt(t2);
  return (t - sin(t)) / (t2 * t);
}
// (1 − (θ/2) cot(θ/2)) / θ²
template <class S> S cotc(const S& t2) {
  using std::sqrt, std::tan;
  if (t2 < kSeriesThreshold) return 1.0 / 12.0 + t2 / 720.0 + t2 * t2 / 30240.0 + t2 * t2 * t2 / 1209600.0;
  const S t = sqrt(t2);
  return (1.0 - 0.5 * t / tan(0.5 * t)) / t2;
}
}  // namespace detail

/// Rodrigues' formula (2-4): R = I + (sin θ/θ) φ̃ + ((1 − cos θ)/θ²) φ̃².
template <class S> Mat3T<S> rotationMatrix(const Vec3T<S>& phi) {
  const S t2 = phi.squaredNorm();
  const Mat3T<S> P = skew(phi);
  return Mat3T<S>::Identity() + detail::sinc(t2) * P + detail::cosc(t2) * (P * P);
}

/// T(φ) of (2-5)/(B-8): body angular velocity ω = T(φ) φ̇.
template <class S> Mat3T<S> angularVelocityMap(const Vec3T<S>& phi) {
  const S t2 = phi.squaredNorm();
  const Mat3T<S> P = skew(phi);
  return Mat3T<S>::Identity() - detail::cosc(t2) * P + detail::sinc3(t2) * (P * P);
}

/// R = exp(φ̃) and T(φ) together, sharing θ, its sine and cosine and φ̃² (the interpolated
/// sections of the beam kernels need both at every Gauss point).
template <class S> struct RotationAndRateMap {
  Mat3T<S> R, T;
};
template <class S> RotationAndRateMap<S> rotationAndRateMap(const Vec3T<S>& phi) {
  using std::cos, std::sin, std::sqrt;
  const S t2 = phi.squaredNorm();
  const Mat3T<S> P = skew(phi), P2 = P * P;
  S sinc, cosc, sinc3;  // sin θ/θ, (1 − cos θ)/θ², (θ − sin θ)/θ³
  if (t2 < detail::kSeriesThreshold) {
    sinc = detail::sinc(t2), cosc = detail::cosc(t2), sinc3 = detail::sinc3(t2);
  } else {
    const S t = sqrt(t2), st = sin(t);
    sinc = st / t, cosc = (1.0 - cos(t)) / t2, sinc3 = (t - st) / (t2 * t);
  }
  return {Mat3T<S>::Identity() + sinc * P + cosc * P2, Mat3T<S>::Identity() - cosc * P + sinc3 * P2};
}

/// The coefficients of exp(φ̃) = I + a P + b P² and T(φ) = I − b P + c P² (P = φ̃) as functions
/// of θ² = |φ|²: a = sin θ/θ, b = (1 − cos θ)/θ², c = (θ − sin θ)/θ³, and their derivatives
/// with respect to θ²,
///   a' = (cos θ − a)/(2θ²),  b' = (a − 2b)/(2θ²),  c' = (b − 3c)/(2θ²),
/// with Taylor series of a', b', c' below θ² = 0.01, where those quotients lose digits.
template <class S> struct ExpCoefficients {
  S a, b, c, da, db, dc;
};
template <class S> ExpCoefficients<S> expCoefficients(const S& t2) {
  using std::cos, std::sin, std::sqrt;
  ExpCoefficients<S> k;
  if (t2 < detail::kSeriesThreshold) {
    k.a = detail::sinc(t2), k.b = detail::cosc(t2), k.c = detail::sinc3(t2);
  } else {
    const S t = sqrt(t2), st = sin(t);
    k.a = st / t, k.b = (1.0 - cos(t)) / t2, k.c = (t - st) / (t2 * t);
  }
  if (t2 < 1e-2) {
    k.da = -1.0 / 6.0 + t2 * (1.0 / 60.0 + t2 * (-1.0 / 1680.0 + t2 * (1.0 / 90720.0 + t2 * (-1.0 / 7983360.0))));
    k.db = -1.0 / 24.0 + t2 * (1.0 / 360.0 + t2 * (-1.0 / 13440.0 + t2 * (1.0 / 907200.0 + t2 * (-1.0 / 95800320.0))));
    k.dc = -1.0 / 120.0 + t2 * (1.0 / 2520.0 + t2 * (-1.0 / 120960.0 + t2 * (1.0 / 9979200.0 + t2 * (-1.0 / 1245404160.0))));
  } else {
    k.da = (1.0 - k.b * t2 - k.a) / (2.0 * t2), k.db = (k.a - 2.0 * k.b) / (2.0 * t2), k.dc = (k.b - 3.0 * k.c) / (2.0 * t2);  // cos θ = 1 − b θ²
  }
  return k;
}

/// b″ and c″, the derivatives of expCoefficients' b′ and c′ with respect to θ² (what the
/// coordinate tangent of Ė_T ψ̇ needs, section_inertia_coordinate_tangent.hpp). Below θ² = 1 by
/// their series b″ = Σₙ₌₂ n(n−1)(−θ²)ⁿ⁻²/(2n+2)!, c″ = Σₙ₌₂ n(n−1)(−θ²)ⁿ⁻²/(2n+3)! (the closed
/// forms lose ~8 digits to cancellation at θ² = 10⁻²), above it in closed form.
struct ExpCoefficientCurvatures {
  double ddb, ddc;
};
inline ExpCoefficientCurvatures expCoefficientCurvatures(double t2, const ExpCoefficients<double>& k) {
  if (t2 >= 1.0) return {(k.da - 4.0 * k.db) / (2.0 * t2), (k.db - 5.0 * k.dc) / (2.0 * t2)};  // from b′ = (a − 2b)/(2θ²), c′ = (b − 3c)/(2θ²)
  ExpCoefficientCurvatures out{0.0, 0.0};
  double term = 1.0, factorial_b = 720.0, factorial_c = 5040.0;  // (−θ²)ⁿ⁻², (2n+2)!, (2n+3)! at n = 2
  for (int n = 2; n <= 12; ++n) {  // the terms fall below 10⁻²⁰ by n = 12
    out.ddb += n * (n - 1) * term / factorial_b;
    out.ddc += n * (n - 1) * term / factorial_c;
    term *= -t2;
    factorial_b *= (2.0 * n + 3.0) * (2.0 * n + 4.0);
    factorial_c *= (2.0 * n + 4.0) * (2.0 * n + 5.0);
  }
  return out;
}

/// R = exp(φ̃), T(φ) and their rates along φ̇ = w, in closed form (instead of a forward-AD
/// direction through rotationAndRateMap): with P = φ̃, W = w̃ and the coefficients of
/// expCoefficients,
///   Ṙ = 2(φ·w)(a' P + b' P²) + a W + b (W P + P W),
///   Ṫ = 2(φ·w)(−b' P + c' P²) − b W + c (W P + P W).
template <class S> struct RotationAndRateMapRates {
  Mat3T<S> R, T, R_dot, T_dot;
};
template <class S> RotationAndRateMapRates<S> rotationAndRateMapRates(const Vec3T<S>& phi, const Vec3T<S>& w) {
  const ExpCoefficients<S> k = expCoefficients<S>(S(phi.squaredNorm()));
  const Mat3T<S> P = skew(phi), P2 = P * P, W = skew(w), WP = W * P + P * W;
  const S t2_dot = 2.0 * phi.dot(w);
  RotationAndRateMapRates<S> out;
  out.R = Mat3T<S>::Identity() + k.a * P + k.b * P2;
  out.T = Mat3T<S>::Identity() - k.b * P + k.c * P2;
  out.R_dot = t2_dot * (k.da * P + k.db * P2) + k.a * W + k.b * WP;
  out.T_dot = t2_dot * (k.dc * P2 - k.db * P) - k.b * W + k.c * WP;
  return out;
}

/// T(φ)⁻¹: φ̇ = T(φ)⁻¹ ω. Singular at θ = 2π, hence the re-parameterisation below.
template <class S> Mat3T<S> angularVelocityMapInverse(const Vec3T<S>& phi) {
  const S t2 = phi.squaredNorm();
  const Mat3T<S> P = skew(phi);
  return Mat3T<S>::Identity() + S(0.5) * P + detail::cotc(t2) * (P * P);
}

namespace detail {
/// ∂(T(φ)⁻¹ x)/∂φ (sign +1) or ∂(T(φ)⁻ᵀ x)/∂φ (sign −1) at x held: with
/// T(φ)^{-1|-ᵀ} x = x ± ½ φ × x + γ φ × (φ × x), γ = cotc(θ²) and γ′ = dγ/dθ²,
///   ∓½ x̃ + γ ((φ·x) I + φ xᵀ − 2 x φᵀ) + 2γ′ (φ × (φ × x)) φᵀ.
inline Mat3 rateMapInverseDerivative(const Vec3& phi, const Vec3& x, double sign) {
  using P = Dual<double, 1>;
  const P gamma = cotc<P>(P(phi.squaredNorm(), Eigen::Matrix<double, 1, 1>(1.0)));
  Mat3 out = (-0.5 * sign) * skew<double>(x) + gamma.value() * (phi * x.transpose() - 2.0 * x * phi.transpose());
  out.diagonal().array() += gamma.value() * phi.dot(x);
  out.noalias() += (2.0 * gamma.derivatives()(0)) * phi.cross(Vec3(phi.cross(x))) * phi.transpose();
  return out;
}
}  // namespace detail

/// ∂(T(φ)⁻¹ x)/∂φ at x held.
inline Mat3 rateMapInverseDerivative(const Vec3& phi, const Vec3& x) { return detail::rateMapInverseDerivative(phi, x, 1.0); }
/// ∂(T(φ)⁻ᵀ x)/∂φ at x held.
inline Mat3 rateMapInverseTransposedDerivative(const Vec3& phi, const Vec3& x) {
  return detail::rateMapInverseDerivative(phi, x, -1.0);
}

/// Rotation vector of a rotation matrix (inverse of Rodrigues (2-4)), angle in [0, π),
/// templated and series-safe at the identity. It is a smooth function of all 3×3 matrices near
/// SO(3): v = vee of the skew part (sin θ n), c = (tr R − 1)/2 (cos θ), φ = θ/sin θ · v.
template <class S> Vec3T<S> rotationLog(const Mat3T<S>& R) {
  using std::acos, std::asin, std::sqrt;
  const Vec3T<S> v(0.5 * (R(2, 1) - R(1, 2)), 0.5 * (R(0, 2) - R(2, 0)), 0.5 * (R(1, 0) - R(0, 1)));
  const S c = 0.5 * (R.trace() - 1.0);
  const S s2 = v.squaredNorm();
  const double c0 = valueOf(c);
  S factor;
  if (valueOf(s2) < 1e-4 && c0 > 0.0) {
    // asin(s)/s = 1 + s²/6 + 3s⁴/40 + 5s⁶/112 + 35s⁸/1152 + O(s¹⁰)
    factor = 1.0 + s2 * (1.0 / 6.0 + s2 * (3.0 / 40.0 + s2 * (5.0 / 112.0 + s2 * (35.0 / 1152.0))));
  } else {
    const S s = sqrt(s2);
    S theta;
    if (c0 >= 0.7) {
      theta = asin(s);
    } else if (c0 > -0.7) {
      theta = acos(c);
    } else {
      theta = std::numbers::pi - asin(s);
    }
    factor = theta / s;
  }
  return factor * v;
}

/// Rotation vector of a rotation matrix, with angle in [0, π] (Eigen, doubles only).
inline Vec3 rotationVector(const Mat3& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

/// Rotation about a unit axis by an angle.
inline Mat3 axisAngle(const Vec3& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

/// Angle above which a rotation vector is re-parameterised
/// (docs/numerics.md#rotation-vector-re-parameterisation): any θ > π would do; the margin above π
/// is hysteresis, so a body rocking about θ = π does not trigger a restart of the integrator at
/// every step (T⁻¹ is singular only at 2π).
inline constexpr double kReparameterisationAngle = 1.25 * std::numbers::pi;

/// Replaces φ by the rotation vector of the same rotation with angle θ − 2π when
/// θ exceeds kReparameterisationAngle. Returns whether φ changed.
inline bool reparameterise(Vec3& phi) {
  const double t = phi.norm();
  if (t <= kReparameterisationAngle) return false;
  phi *= 1.0 - 2.0 * std::numbers::pi / t;
  return true;
}

/// Section axes of a straight member: x along it, z as close to `z_hint` as possible.
inline Mat3 memberFrame(const Vec3& start, const Vec3& end, const Vec3& z_hint) {
  const Vec3 x = (end - start).normalized();
  Vec3 z = z_hint - z_hint.dot(x) * x;
  if (z.norm() < 1e-6) {  // hint along the member: fall back to the global z, then y
    z = Vec3::UnitZ() - x.z() * x;
    if (z.norm() < 1e-6) z = Vec3::UnitY() - x.y() * x;
  }
  z.normalize();
  Mat3 R;
  R << x, z.cross(x), z;
  return R;
}

}  // namespace cranesim
