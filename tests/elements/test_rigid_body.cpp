// Rigid body kernel (3-4, 3-5): mass matrix against the definition by integration over
// point masses, and the quadratic-velocity terms against energy conservation.

#include <catch2/catch.hpp>

#include <random>

#include "cranesim/elements/rigid_body.hpp"

using namespace cranesim;

namespace {

using Q6 = Eigen::Matrix<double, 6, 1>;

/// A body made of point masses: the kernel's parameters must reproduce it exactly.
struct PointCloud {
  std::vector<Vec3> points;  // body frame, relative to the origin
  std::vector<double> masses;

  RigidBodyKernel kernel() const {
    RigidBodyKernel k;
    k.mass = 0.0;
    Vec3 first = Vec3::Zero();
    Mat3 inertia = Mat3::Zero();
    for (std::size_t i = 0; i < points.size(); ++i) {
      k.mass += masses[i];
      first += masses[i] * points[i];
      inertia -= masses[i] * skew(points[i]) * skew(points[i]);
    }
    k.centroid = first / k.mass;
    k.inertia_origin = inertia;
    return k;
  }
  double kineticEnergy(const Q6& q, const Q6& v) const {
    const Mat3 R = rotationMatrix<double>(q.tail<3>());
    double T = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Vec3 vel = v.head<3>() + R * v.tail<3>().cross(points[i]);  // (3-2)
      T += 0.5 * masses[i] * vel.squaredNorm();
    }
    return T;
  }
};

PointCloud randomCloud() {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  PointCloud c;
  for (int i = 0; i < 7; ++i) {
    c.points.emplace_back(u(rng) + 0.5, u(rng), u(rng) - 0.2);
    c.masses.push_back(1.0 + u(rng) * 0.5);
  }
  return c;
}

}  // namespace

TEST_CASE("Rigid-body mass matrix is the kinetic-energy quadratic form of the body", "[elements][rigid]") {
  const PointCloud cloud = randomCloud();
  const RigidBodyKernel k = cloud.kernel();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 5; ++trial) {
    Q6 q, v;
    for (int i = 0; i < 6; ++i) q(i) = 2.0 * u(rng), v(i) = u(rng);
    const auto M = k.massMatrix<double>(q);
    CHECK((M - M.transpose()).norm() < 1e-12);
    CHECK(Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>>(M).eigenvalues().minCoeff() > 0.0);
    CHECK(0.5 * v.dot(M * v) == Approx(cloud.kineticEnergy(q, v)).epsilon(1e-12));
  }
}

TEST_CASE("Quadratic-velocity terms conserve kinetic energy in free motion", "[elements][rigid]") {
  // With M a = −F (no gravity), dT/dt = v·M a + ½ vᵀ Ṁ v must vanish.
  const RigidBodyKernel k = randomCloud().kernel();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 5; ++trial) {
    Q6 q, v;
    for (int i = 0; i < 6; ++i) q(i) = 2.0 * u(rng), v(i) = u(rng);
    const auto M = k.massMatrix<double>(q);
    const Q6 a = -M.ldlt().solve(k.force<double>(q, v, 0.0, Vec3::Zero()));
    Q6 qdot;
    qdot.head<3>() = v.head<3>();
    qdot.tail<3>() = angularVelocityMapInverse<double>(Vec3(q.tail<3>())) * v.tail<3>();
    const double h = 1e-6;
    const Eigen::Matrix<double, 6, 6> Mdot = (k.massMatrix<double>(q + h * qdot) - k.massMatrix<double>(q - h * qdot)) / (2 * h);
    CHECK(v.dot(M * a) + 0.5 * v.dot(Mdot * v) == Approx(0.0).margin(1e-8));
  }
}

TEST_CASE("Gravity terms are the gradient of the potential energy", "[elements][rigid]") {
  const RigidBodyKernel k = randomCloud().kernel();
  const Vec3 g(0.1, -0.3, -9.81);
  Q6 q;
  q << 0.3, -0.2, 1.0, 0.4, -0.7, 0.9;
  const Q6 F = k.force<double>(q, Q6::Zero(), 0.0, g);
  // Generalized force along dq = [ṙ, ω]: perturb r directly and R by R exp(ε ω̃).
  for (int i = 0; i < 6; ++i) {
    const double h = 1e-6;
    const auto potentialAt = [&](double e) {
      Q6 p = q;
      if (i < 3) {
        p(i) += e;
      } else {
        const Mat3 R = rotationMatrix<double>(Vec3(q.tail<3>())) * axisAngle(Vec3::Unit(i - 3), e);
        p.tail<3>() = rotationVector(R);
      }
      return k.potentialEnergy(p, 0.0, g);
    };
    CHECK(F(i) == Approx((potentialAt(h) - potentialAt(-h)) / (2 * h)).margin(1e-6));
  }
}
