// Rotation-vector kinematics (2-4, 2-5, B-8) against finite differences and identities.

#include <catch2/catch.hpp>

#include <numbers>
#include <random>

#include "cranesim/math/autodiff.hpp"
#include "cranesim/math/rotation.hpp"

using namespace cranesim;

namespace {

std::vector<Vec3> samplePhis() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> out = {Vec3::Zero(), Vec3(1e-5, -2e-5, 3e-6), Vec3(0.004, 0.003, -0.002), Vec3(0, 0, 3.0)};
  for (int k = 0; k < 20; ++k) {
    Vec3 axis(u(rng), u(rng), u(rng));
    out.push_back(axis.normalized() * (3.9 * std::abs(u(rng))));
  }
  return out;
}

}  // namespace

TEST_CASE("Rodrigues' formula is a rotation and agrees with Eigen's angle-axis", "[rotation]") {
  for (const Vec3& phi : samplePhis()) {
    const Mat3 R = rotationMatrix<double>(phi);
    CHECK((R.transpose() * R - Mat3::Identity()).norm() < 1e-14);
    CHECK(R.determinant() == Approx(1.0).margin(1e-14));
    const Mat3 expected = phi.norm() > 0 ? axisAngle(phi, phi.norm()) : Mat3::Identity();
    CHECK((R - expected).norm() < 1e-14);
  }
}

TEST_CASE("T(φ) maps φ̇ to the body angular velocity Rᵀ Ṙ", "[rotation]") {
  const Vec3 phidot(0.3, -0.7, 0.5);
  for (const Vec3& phi : samplePhis()) {
    const double h = 1e-6;
    const Mat3 Rdot = (rotationMatrix<double>(phi + h * phidot) - rotationMatrix<double>(phi - h * phidot)) / (2 * h);
    const Vec3 omega_fd = unskew(rotationMatrix<double>(phi).transpose() * Rdot);
    CHECK((angularVelocityMap<double>(phi) * phidot - omega_fd).norm() < 1e-8);
  }
}

TEST_CASE("T(φ)⁻¹ inverts T(φ) up to the re-parameterisation threshold", "[rotation]") {
  for (const Vec3& phi : samplePhis()) {
    CHECK((angularVelocityMapInverse<double>(phi) * angularVelocityMap<double>(phi) - Mat3::Identity()).norm() < 1e-12);
  }
}

TEST_CASE("Derivatives of T(φ) by automatic differentiation equal finite differences, also at φ = 0", "[rotation]") {
  using D = Dual<double, 3>;
  const Vec3 w(0.2, -0.4, 0.9);
  for (const Vec3& phi : samplePhis()) {
    Vec3T<D> p;
    for (int k = 0; k < 3; ++k) p(k) = seeded<double, 3>(phi(k), k);
    const Vec3T<D> Tw = angularVelocityMap<D>(p) * w.cast<D>();
    for (int k = 0; k < 3; ++k) {
      const double h = 1e-6;
      const Vec3 e = Vec3::Unit(k) * h;
      const Vec3 fd = (angularVelocityMap<double>(phi + e) * w - angularVelocityMap<double>(phi - e) * w) / (2 * h);
      for (int i = 0; i < 3; ++i) CHECK(Tw(i).derivatives()(k) == Approx(fd(i)).margin(1e-8));
    }
  }
}

TEST_CASE("Series and closed forms of the coefficient functions join continuously", "[rotation]") {
  // Just below and above the switching point θ² = 1e-4 the two branches must agree.
  const double below = std::sqrt(detail::kSeriesThreshold) * (1 - 1e-13);
  const double above = std::sqrt(detail::kSeriesThreshold) * (1 + 1e-13);
  const Vec3 n = Vec3(1, 2, 2) / 3.0;
  CHECK((rotationMatrix<double>(below * n) - rotationMatrix<double>(above * n)).norm() < 1e-12);
  CHECK((angularVelocityMap<double>(below * n) - angularVelocityMap<double>(above * n)).norm() < 1e-12);
  CHECK((angularVelocityMapInverse<double>(below * n) - angularVelocityMapInverse<double>(above * n)).norm() < 1e-12);
}

TEST_CASE("The curvatures b″, c″ of the coefficients equal their closed forms in extended precision", "[rotation]") {
  // b′ = (a − 2b)/(2θ²), c′ = (b − 3c)/(2θ²) differentiated once more, in long double (the closed
  // forms cancel less there), either side of the series' switch at θ² = 1; near θ² = 0 against
  // forward AD of b′ and c′ (their series).
  for (long double t2 : {0.1L, 0.3L, 0.99L, 1.01L, 4.0L, 9.0L}) {
    INFO("θ² = " << static_cast<double>(t2));
    const long double t = std::sqrt(t2), a = std::sin(t) / t, b = (1.0L - std::cos(t)) / t2, c = (t - std::sin(t)) / (t2 * t);
    const long double da = (std::cos(t) - a) / (2.0L * t2), db = (a - 2.0L * b) / (2.0L * t2), dc = (b - 3.0L * c) / (2.0L * t2);
    const ExpCoefficientCurvatures closed = expCoefficientCurvatures(static_cast<double>(t2), expCoefficients<double>(static_cast<double>(t2)));
    CHECK(closed.ddb == Approx(static_cast<double>((da - 4.0L * db) / (2.0L * t2))).epsilon(1e-12));
    CHECK(closed.ddc == Approx(static_cast<double>((db - 5.0L * dc) / (2.0L * t2))).epsilon(1e-12));
  }
  using P = Dual<double, 1>;
  for (double t2 : {0.0, 1e-6, 1e-3}) {
    const ExpCoefficients<P> ad = expCoefficients<P>(P(t2, Eigen::Matrix<double, 1, 1>(1.0)));
    const ExpCoefficientCurvatures closed = expCoefficientCurvatures(t2, expCoefficients<double>(t2));
    CHECK(closed.ddb == Approx(ad.db.derivatives()(0)).epsilon(1e-12));
    CHECK(closed.ddc == Approx(ad.dc.derivatives()(0)).epsilon(1e-12));
  }
}

TEST_CASE("Re-parameterisation keeps the rotation and maps θ to 2π − θ", "[rotation]") {
  Vec3 phi = Vec3(0.2, -0.5, 0.8).normalized() * (1.3 * std::numbers::pi);
  const Mat3 before = rotationMatrix<double>(phi);
  REQUIRE(reparameterise(phi));
  CHECK(phi.norm() == Approx(0.7 * std::numbers::pi));
  CHECK((rotationMatrix<double>(phi) - before).norm() < 1e-14);
  Vec3 small = Vec3(0.1, 0.2, 0.3);
  CHECK_FALSE(reparameterise(small));
}

TEST_CASE("exp and T(φ) computed together equal Rodrigues' formula and (B-8)", "[rotation]") {
  for (const Vec3& phi : samplePhis()) {
    const RotationAndRateMap<double> both = rotationAndRateMap<double>(phi);
    CHECK((both.R - rotationMatrix<double>(phi)).cwiseAbs().maxCoeff() < 1e-15);
    CHECK((both.T - angularVelocityMap<double>(phi)).cwiseAbs().maxCoeff() < 1e-15);
  }
}

TEST_CASE("The rates of exp and T(φ) in closed form equal forward AD along φ̇, at every angle", "[rotation]") {
  using P = Dual<double, 1>;
  const Vec3 w(0.3, -0.7, 0.4);
  std::vector<Vec3> phis = samplePhis();
  // Either side of the series' thresholds (θ² = 1e-4 for the values, 1e-2 for the rates).
  for (double t2 : {0.99e-4, 1.01e-4, 0.99e-2, 1.01e-2}) phis.push_back(Vec3(1.0, -2.0, 0.5).normalized() * std::sqrt(t2));
  for (const Vec3& phi : phis) {
    INFO("φ = " << phi.transpose());
    Vec3T<P> path;
    for (int i = 0; i < 3; ++i) path(i) = P(phi(i), Eigen::Matrix<double, 1, 1>(w(i)));
    const RotationAndRateMap<P> ad = rotationAndRateMap<P>(path);
    const RotationAndRateMapRates<double> closed = rotationAndRateMapRates<double>(phi, w);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        CHECK(closed.R(i, j) == Approx(ad.R(i, j).value()).margin(1e-15));
        CHECK(closed.T(i, j) == Approx(ad.T(i, j).value()).margin(1e-15));
        CHECK(closed.R_dot(i, j) == Approx(ad.R(i, j).derivatives()(0)).margin(1e-14));
        CHECK(closed.T_dot(i, j) == Approx(ad.T(i, j).derivatives()(0)).margin(1e-14));
      }
    // Ṙ = R (T w)~: the body angular velocity of the path.
    CHECK((closed.R_dot - closed.R * skew<double>(Vec3(closed.T * w))).cwiseAbs().maxCoeff() < 1e-14);
  }
}
