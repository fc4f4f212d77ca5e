// The co-rotated beam's elastic forces and their end-2 columns in closed form
// (corotated_elastic_tangent.hpp) against forward AD through the whole co-rotation.

#include <catch2/catch.hpp>

#include <cstdio>

#include "cranesim/elements/corotated_elastic_tangent.hpp"
#include "cranesim/elements/timoshenko_beam.hpp"
#include "random_states.hpp"

using namespace cranesim;

namespace {

using V12 = Eigen::Matrix<double, 12, 1>;
using D6 = Dual<double, 6>;

TimoshenkoBeamKernel rectangularBeam(double length, double damping) {
  TimoshenkoBeamKernel k;
  k.length = length;
  const double b = 0.12, h = 0.2;
  k.section.area = b * h;
  k.section.Iy = b * h * h * h / 12.0;
  k.section.Iz = h * b * b * b / 12.0;
  k.section.J = 0.196 * b * b * b * h;
  k.section.shear_factor = 5.0 / 6.0;
  k.material.youngs_modulus = 2.1e11;
  k.material.shear_modulus = 8.1e10;
  k.material.density = 7850.0;
  k.damping = damping;
  return k;
}

/// f and ∂f/∂[δr², δθ²] by forward AD: r² + δr², R² exp(δθ̃²) seeded.
CoRotatedElasticTangent forwardAD(const TimoshenkoBeamKernel& k, const Vec3& r1, const Mat3& R1, const Vec3& r2,
                                  const Mat3& R2, const V12& v, const Eigen::Matrix<double, 12, 12>& K) {
  Vec3T<D6> r2d, theta;
  for (int i = 0; i < 3; ++i) r2d(i) = seeded<double, 6>(r2(i), i), theta(i) = seeded<double, 6>(0.0, 3 + i);
  const Mat3T<D6> R2d = R2.cast<D6>() * rotationMatrix<D6>(theta);
  const Eigen::Matrix<D6, 12, 1> f =
      k.elasticForce<D6>(r1.cast<D6>(), R1.cast<D6>(), r2d, R2d, Eigen::Matrix<D6, 12, 1>(v.cast<D6>()), K);
  CoRotatedElasticTangent out;
  for (int i = 0; i < 12; ++i) out.force(i) = f(i).value(), out.second_end.row(i) = f(i).derivatives().transpose();
  return out;
}

}  // namespace

TEST_CASE("Co-rotated beam: elastic forces' end-2 columns in closed form match forward AD", "[timoshenko][corotation]") {
  test::Rng rng(41);
  double worst = 0.0;
  for (const double damping : {0.0, 0.03}) {
    for (const double strain : {1e-6, 0.05, 0.4}) {
      const TimoshenkoBeamKernel k = rectangularBeam(1.7, damping);
      const Eigen::Matrix<double, 12, 12> K = k.localStiffness();
      for (int trial = 0; trial < 6; ++trial) {
        const Vec3 r1 = rng.vec(5.0);
        const Mat3 R1 = rng.rotation(3.0);
        const Mat3 R2 = R1 * rng.rotation(3.0 * strain);
        const Vec3 r2 = r1 + R1 * (k.length * (Vec3::UnitX() + rng.vec(strain)));
        V12 v;
        for (int i = 0; i < 12; ++i) v(i) = 4.0 * rng();
        const CoRotatedElasticTangent closed = coRotatedElasticTangent(k.length, k.damping, r1, R1, r2, R2, v, K);
        const CoRotatedElasticTangent ad = forwardAD(k, r1, R1, r2, R2, v, K);
        INFO("damping " << damping << ", strain " << strain << ", trial " << trial);
        CHECK((closed.force - ad.force).norm() <= 1e-12 * ad.force.norm() + 1e-15 * K.norm());  // rounding of K d near d = 0
        const double scale = ad.second_end.norm();
        const double error = (closed.second_end - ad.second_end).norm() / scale;
        CHECK(error < 1e-11);
        worst = std::max(worst, error);
      }
    }
  }
  std::printf("[co-rotated elastic tangent] closed form vs forward AD: rel. err %.3g\n", worst);
}
