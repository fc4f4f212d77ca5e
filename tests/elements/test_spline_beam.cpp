// Cubic spline beam kernel (thesis 3.4, C.4): mass matrix, internal forces, Jacobians, energy
// consistency of the inertial terms, and the classical cantilever results.

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include "cranesim/elements/spline_beam.hpp"
#include "cranesim/model/kernel_elements.hpp"

using namespace cranesim;

namespace {

using Kernel = SplineBeamKernel;
using Q14 = Eigen::Matrix<double, 14, 1>;
using M14 = Eigen::Matrix<double, 14, 14>;

/// A test element of moderate stiffness, so that inertial, elastic and gravity forces are of
/// comparable size.
Kernel testKernel(double damping = 0.0) {
  Kernel k;
  k.length = 2.0;
  k.section = Section::circular(0.12, 0.08, 0.3);
  k.section.Iz *= 1.3;  // unequal principal axes: exercises the section inertia and stiffness
  k.material = {2000.0, 2e7, 8e6};
  k.damping = damping;
  return k;
}

Vec3 randomVector(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return scale * Vec3(u(rng), u(rng), u(rng));
}

Q14 pack(const Vec3& r1, const Mat3& R1, double s1, const Vec3& r2, const Mat3& R2, double s2) {
  Q14 q;
  q << r1, rotationVector(R1), s1, r2, rotationVector(R2), s2;
  return q;
}

/// A deformed element in a random placement (large rotations); `deformation` scales the
/// bending, torsion and stretch.
Q14 randomConfiguration(const Kernel& k, std::mt19937& rng, double deformation) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Vec3 r1 = randomVector(rng, 3.0);
  Vec3 phi1 = randomVector(rng, 1.0);
  phi1 *= 2.4 * std::abs(u(rng)) / phi1.norm();
  const Mat3 R1 = rotationMatrix<double>(phi1);
  const Mat3 R2 = R1 * rotationMatrix<double>(randomVector(rng, 0.5 * deformation));
  const Vec3 r2 = r1 + R1 * (k.length * (Vec3::UnitX() + randomVector(rng, 0.15 * deformation)));
  return pack(r1, R1, 1.0 + 0.05 * deformation * u(rng), r2, R2, 1.0 + 0.05 * deformation * u(rng));
}

/// q ⊕ δ: r + δr, R exp(δθ̃), s + δs at both ends (the perturbations dq is conjugate to).
Q14 plus(const Q14& q, const Q14& d) {
  Q14 p = q;
  for (int n = 0; n < 2; ++n) {
    const int o = 7 * n;
    p.segment<3>(o) += d.segment<3>(o);
    const Mat3 R = rotationMatrix<double>(Vec3(q.segment<3>(o + 3))) * rotationMatrix<double>(Vec3(d.segment<3>(o + 3)));
    p.segment<3>(o + 3) = rotationVector(R);
    p(o + 6) += d(o + 6);
  }
  return p;
}

/// Straight, unstrained element (s = 1) in the placement (r1, R).
Q14 straight(const Kernel& k, const Vec3& r1, const Mat3& R) {
  return pack(r1, R, 1.0, r1 + k.length * R.col(0), R, 1.0);
}

/// Velocities of a rigid motion with node-1 velocity V and inertial angular velocity Ω.
Q14 rigidVelocity(const Q14& q, const Vec3& V, const Vec3& Omega) {
  Q14 v;
  const Mat3 R1 = rotationMatrix<double>(Vec3(q.segment<3>(3))), R2 = rotationMatrix<double>(Vec3(q.segment<3>(10)));
  v << V, R1.transpose() * Omega, 0.0, V + Omega.cross(q.segment<3>(7) - q.head<3>()), R2.transpose() * Omega, 0.0;
  return v;
}

template <class F> Q14 twistGradient(const Q14& q, F&& f, double h) {
  Q14 g;
  for (int k = 0; k < 14; ++k) {
    const Q14 d = h * Q14::Unit(k);
    g(k) = (f(plus(q, d)) - f(plus(q, -d))) / (2 * h);
  }
  return g;
}

M14 massRate(const Kernel& k, const Q14& q, const Q14& v, double h = 1e-6) {
  return (k.massMatrix<double>(plus(q, h * v)) - k.massMatrix<double>(plus(q, -h * v))) / (2 * h);
}

}  // namespace

TEST_CASE("Spline beam mass matrix is symmetric positive definite and is the beam's kinetic energy", "[spline_beam]") {
  const Kernel k = testKernel();
  std::mt19937 rng(1);
  for (int trial = 0; trial < 5; ++trial) {
    const M14 M = k.massMatrix<double>(randomConfiguration(k, rng, 1.0));
    CHECK((M - M.transpose()).norm() <= 1e-12 * M.norm());
    CHECK(Eigen::SelfAdjointEigenSolver<M14>(M).eigenvalues().minCoeff() > 0.0);
  }
  // Rigid motion of the straight element: the kinetic energy of a rigid cylinder.
  for (int trial = 0; trial < 5; ++trial) {
    const Mat3 R = rotationMatrix<double>(randomVector(rng, 1.7));
    const Q14 q = straight(k, randomVector(rng, 2.0), R);
    const Vec3 V = randomVector(rng, 1.0), Omega = randomVector(rng, 2.0);
    const Q14 v = rigidVelocity(q, V, Omega);
    const double rho = k.material.density, A = k.section.area, L = k.length, m = rho * A * L;
    const Vec3 vc = V + Omega.cross(0.5 * L * R.col(0));
    const Vec3 w = R.transpose() * Omega;
    const Vec3 theta(rho * L * (k.section.Iy + k.section.Iz), rho * L * k.section.Iy + m * L * L / 12.0,
                     rho * L * k.section.Iz + m * L * L / 12.0);
    const double T = 0.5 * m * vc.squaredNorm() + 0.5 * w.dot(theta.cwiseProduct(w));
    CHECK(k.kineticEnergy(q, v) == Approx(T).epsilon(1e-12));
  }
}

TEST_CASE("Spline beam fused residual is M a + F", "[spline_beam]") {
  // The residual adds G_r a and G_ω a to the sections' accelerations instead of forming M: the
  // same sum to rounding, at deformed states with every velocity and acceleration non-zero.
  const Kernel k = testKernel(2e-3);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Vec3 g(0.3, -0.2, -9.81);
  for (int trial = 0; trial < 6; ++trial) {
    const Q14 q = randomConfiguration(k, rng, 1.0);
    Q14 v, a;
    for (int i = 0; i < 14; ++i) v(i) = u(rng), a(i) = 3.0 * u(rng);
    const Q14 split = k.massMatrix<double>(q) * a + k.force<double>(q, v, 0.0, g);
    const Q14 fused = k.residual<double>(q, v, a, 0.0, g);
    CHECK((fused - split).norm() <= 1e-12 * (split.norm() + (k.massMatrix<double>(q) * a).norm()));
    // M a alone: the fused residual's change with a.
    const Q14 Ma = k.residual<double>(q, v, a, 0.0, g) - k.residual<double>(q, v, Q14::Zero(), 0.0, g);
    CHECK((Ma - k.massMatrix<double>(q) * a).norm() <= 1e-12 * (k.massMatrix<double>(q) * a).norm());
  }
}

TEST_CASE("Spline beam has no internal force in rigid placements and under rigid velocities", "[spline_beam]") {
  const Kernel k = testKernel(0.05);
  const double scale = k.stiffness()(0);
  std::mt19937 rng(2);
  for (int trial = 0; trial < 10; ++trial) {
    // Large rotations, up to and beyond π (the rotation vector is re-drawn in [0, π]).
    const Mat3 R = rotationMatrix<double>(randomVector(rng, 3.0));
    const Q14 q = straight(k, randomVector(rng, 5.0), R);
    CHECK(k.force<double>(q, Q14::Zero(), 0.0, Vec3::Zero()).norm() < 1e-9 * scale);
    CHECK(k.strainEnergy(q) < 1e-20 * scale);
    for (double xi : {0.0, 0.3, 1.0}) CHECK(k.strains(q, xi).norm() < 1e-12);
    // Damping acts on strain rates only: none under a rigid motion.
    const Q14 v = rigidVelocity(q, randomVector(rng, 2.0), randomVector(rng, 3.0));
    CHECK(k.internalForce<double>(q, v).norm() < 1e-9 * scale);
    // The frame at ξ = 1 is that of node 2, and the centre line is the straight chord.
    const Frame f = k.sectionFrame(q, 0.37);
    CHECK((f.R - R).norm() < 1e-12);
    CHECK((f.r - (q.head<3>() + 0.37 * k.length * R.col(0))).norm() < 1e-12);
  }
}

TEST_CASE("Spline beam elastic and gravity forces are twist gradients of the potential energy", "[spline_beam]") {
  const Kernel k = testKernel();
  const Vec3 g(0.3, -1.2, -9.81);
  std::mt19937 rng(3);
  for (int trial = 0; trial < 6; ++trial) {
    const Q14 q = randomConfiguration(k, rng, 1.0);
    const Q14 Fint = k.internalForce<double>(q, Q14::Zero());
    const Q14 dU = twistGradient(q, [&](const Q14& p) { return k.strainEnergy(p); }, 1e-6);
    CHECK((Fint - dU).norm() <= 1e-6 * dU.norm());
    const Q14 F = k.force<double>(q, Q14::Zero(), 0.0, g);
    const Q14 dV = twistGradient(q, [&](const Q14& p) { return k.potentialEnergy(p, 0.0, g); }, 1e-6);
    CHECK((F - dV).norm() <= 1e-6 * dV.norm());
    // The frame at ξ = 1 is node 2's, whatever the deformation.
    const Frame f = k.sectionFrame(q, 1.0);
    CHECK((f.R - rotationMatrix<double>(Vec3(q.segment<3>(10)))).norm() < 1e-12);
    CHECK((f.r - q.segment<3>(7)).norm() < 1e-12);
  }
  // Equilibrium of the element: under a virtual rigid rotation δΘ (δr = δΘ × r, δθ = Rᵀ δΘ,
  // δs = 0) the internal forces do no work, so their resultant force and moment vanish.
  const Q14 q = randomConfiguration(k, rng, 1.0);
  const Q14 F = k.internalForce<double>(q, Q14::Zero());
  const Mat3 R1 = rotationMatrix<double>(Vec3(q.segment<3>(3))), R2 = rotationMatrix<double>(Vec3(q.segment<3>(10)));
  CHECK((F.head<3>() + F.segment<3>(7)).norm() < 1e-9 * F.norm());
  const Vec3 moment = Vec3(q.head<3>()).cross(Vec3(F.head<3>())) + Vec3(q.segment<3>(7)).cross(Vec3(F.segment<3>(7))) +
                      R1 * F.segment<3>(3) + R2 * F.segment<3>(10);
  CHECK(moment.norm() < 1e-9 * F.norm() * (1.0 + q.head<3>().norm()));
}

TEST_CASE("Spline beam Jacobian matches finite differences of the residual", "[spline_beam]") {
  const Kernel kernel = testKernel(0.02);
  const std::unique_ptr<Element> element = makeElement(kernel, {0, 1}, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13},
                                                       {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13});
  std::mt19937 rng(4);
  for (int trial = 0; trial < 3; ++trial) {
    const Q14 q = randomConfiguration(kernel, rng, 1.0);
    Q14 v, a;
    v << randomVector(rng, 1.0), randomVector(rng, 2.0), 0.1, randomVector(rng, 1.0), randomVector(rng, 2.0), -0.1;
    a << randomVector(rng, 3.0), randomVector(rng, 3.0), 0.5, randomVector(rng, 3.0), randomVector(rng, 3.0), -0.3;
    const double cj = 37.0;
    const Vec3 g(0.0, 0.0, -9.81);
    Eigen::Matrix<double, 14, 28> J;
    element->jacobian({q.data(), v.data(), a.data(), 0.0, g}, cj, J.data());
    Eigen::Matrix<double, 14, 28> Jfd;
    for (int c = 0; c < 28; ++c) {
      const double h = c < 14 ? 1e-6 : 1e-5;
      Q14 q1 = q, q2 = q, v1 = v, v2 = v, a1 = a, a2 = a;
      if (c < 14) {
        q1(c) += h, q2(c) -= h;
      } else {
        v1(c - 14) += h, v2(c - 14) -= h, a1(c - 14) += cj * h, a2(c - 14) -= cj * h;
      }
      Q14 r1, r2;
      element->residual({q1.data(), v1.data(), a1.data(), 0.0, g}, r1.data());
      element->residual({q2.data(), v2.data(), a2.data(), 0.0, g}, r2.data());
      Jfd.col(c) = (r1 - r2) / (2 * h);
    }
    for (int c = 0; c < 28; ++c) {
      INFO("column " << c);
      CHECK((J.col(c) - Jfd.col(c)).norm() <= 1e-6 * J.norm());
    }
  }
}

TEST_CASE("Spline beam conserves energy in free motion and its inertial terms are Lagrange's", "[spline_beam]") {
  const Kernel k = testKernel();
  const Vec3 g(0.0, -2.0, -9.81);
  std::mt19937 rng(5);
  for (int trial = 0; trial < 5; ++trial) {
    const Q14 q = randomConfiguration(k, rng, 1.0);
    Q14 v;
    v << randomVector(rng, 1.0), randomVector(rng, 3.0), 0.2, randomVector(rng, 1.0), randomVector(rng, 3.0), -0.1;
    const M14 M = k.massMatrix<double>(q);
    const M14 Mdot = massRate(k, q, v);

    // d/dt (T + U) = vᵀ M a + ½ vᵀ Ṁ v + dU/dt = 0 with M a = −F.
    const Q14 a = -M.ldlt().solve(k.force<double>(q, v, 0.0, g));
    const double h = 1e-6;
    const double dU = (k.potentialEnergy(plus(q, h * v), 0.0, g) - k.potentialEnergy(plus(q, -h * v), 0.0, g)) / (2 * h);
    const double power = v.dot(M * a) + 0.5 * v.dot(Mdot * v);
    CHECK(power + dU == Approx(0.0).margin(1e-6 * std::abs(dU)));

    // Hamel's form of Lagrange's equations from T = ½ vᵀ M(q) v alone:
    //   F_ine = Ṁ v − ∂T/∂δ + [ω^n × (M v)_ω^n]_n.
    Q14 hamel = Mdot * v - twistGradient(q, [&](const Q14& p) { return 0.5 * v.dot(k.massMatrix<double>(p) * v); }, 1e-6);
    const Q14 p = M * v;
    for (int n = 0; n < 2; ++n)
      hamel.segment<3>(7 * n + 3) += Vec3(v.segment<3>(7 * n + 3)).cross(Vec3(p.segment<3>(7 * n + 3)));
    const Q14 Fine = k.inertialForce<double>(q, v);
    CHECK((Fine - hamel).norm() <= 1e-6 * Fine.norm());
  }
  // With damping, the energy decays at the rate of the dissipation function.
  const Kernel kd = testKernel(0.01);
  const Q14 q = randomConfiguration(kd, rng, 1.0);
  Q14 v;
  v << randomVector(rng, 1.0), randomVector(rng, 3.0), 0.2, randomVector(rng, 1.0), randomVector(rng, 3.0), -0.1;
  const Q14 damping = kd.internalForce<double>(q, v) - kd.internalForce<double>(q, Q14::Zero());
  CHECK(v.dot(damping) > 0.0);
}

namespace {

/// A cantilever of n spline beam elements along x (φ = 0 at all nodes, so twists and φ agree
/// to first order and ∂F/∂q is the tangent stiffness), clamped at node 0 (r, φ; s stays free).
struct Cantilever {
  static constexpr double L = 15.0, radius = 0.15, E = 2.06e11, nu = 0.25, rho = 7850.0;
  int n;
  Kernel kernel;
  std::vector<std::unique_ptr<Element>> elements;
  int size;

  explicit Cantilever(int segments) : n(segments), size(7 * (segments + 1)) {
    kernel.length = L / n;
    kernel.section = Section::circular(radius, 0.0, nu);
    kernel.material = {rho, E, E / (2.0 * (1.0 + nu))};
    for (int e = 0; e < n; ++e) {
      std::vector<int> idx(14);
      for (int k = 0; k < 14; ++k) idx[k] = 7 * e + k;
      elements.push_back(makeElement(kernel, {e, e + 1}, idx, idx));
    }
  }
  VecX reference() const {
    VecX q = VecX::Zero(size);
    for (int i = 0; i <= n; ++i) q(7 * i) = i * L / n, q(7 * i + 6) = 1.0;
    return q;
  }
  /// Assembled ∂F/∂q (v = a = 0, no gravity) and M at q, free dofs only (6 … size).
  void assemble(const VecX& q, MatX& K, MatX& M, VecX* F = nullptr) const {
    const VecX zero = VecX::Zero(size);
    const ElementInput in{q.data(), zero.data(), zero.data(), 0.0, Vec3::Zero()};
    MatX Kf = MatX::Zero(size, size), Mf = MatX::Zero(size, size);
    VecX Ff = VecX::Zero(size);
    for (int e = 0; e < n; ++e) {
      Eigen::Matrix<double, 14, 28> J;
      Eigen::Matrix<double, 14, 14> Me;
      Eigen::Matrix<double, 14, 1> r;
      elements[e]->jacobian(in, 0.0, J.data());
      elements[e]->mass(in, Me.data());
      elements[e]->residual(in, r.data());
      Kf.block<14, 14>(7 * e, 7 * e) += J.leftCols<14>();
      Mf.block<14, 14>(7 * e, 7 * e) += Me;
      Ff.segment<14>(7 * e) += r;
    }
    K = Kf.bottomRightCorner(size - 6, size - 6);
    M = Mf.bottomRightCorner(size - 6, size - 6);
    if (F) *F = Ff.tail(size - 6);
  }
  double EI() const { return E * kernel.section.Iz; }
};

}  // namespace

TEST_CASE("Spline beam cantilever: linear statics against beam theory", "[spline_beam]") {
  std::printf("\nSpline beam cantilever, L = 15 m, r = 0.15 m, E = 2.06e11 Pa, nu = 0.25 (relative errors)\n");
  std::printf("  n   tip load PL^3/3EI   end moment ML/EI   axial PL/EA   torsion TL/GJ\n");
  double previous = 1.0;
  for (int n : {1, 3, 5, 10}) {
    const Cantilever c(n);
    MatX K, M;
    c.assemble(c.reference(), K, M);
    REQUIRE((K - K.transpose()).norm() <= 1e-9 * K.norm());
    const auto solver = K.ldlt();
    const int tip = 7 * n - 6;  // tip node offset among the free dofs
    const auto solve = [&](int dof, double load) {
      VecX f = VecX::Zero(K.rows());
      f(tip + dof) = load;
      return VecX(solver.solve(f));
    };
    const double L = Cantilever::L, EI = c.EI(), EA = Cantilever::E * c.kernel.section.area;
    const double GJ = c.kernel.material.shear_modulus * c.kernel.section.J;
    const double P = 1e3, Mo = 1e4, N = 1e5, T = 1e4;
    const double tipLoad = std::abs(solve(1, P)(tip + 1) / (P * L * L * L / (3 * EI)) - 1.0);
    const double moment = std::abs(solve(5, Mo)(tip + 5) / (Mo * L / EI) - 1.0);
    const double axial = std::abs(solve(0, N)(tip + 0) / (N * L / EA) - 1.0);
    const double torsion = std::abs(solve(3, T)(tip + 3) / (T * L / GJ) - 1.0);
    std::printf("%3d   %.3e           %.3e          %.3e     %.3e\n", n, tipLoad, moment, axial, torsion);
    // Cubic Hermite interpolation contains the exact Euler–Bernoulli solutions of these load
    // cases (cubic deflection, linear twist and axial displacement): the errors are at
    // round-off level for every mesh, so "decreasing" can only hold up to round-off.
    CHECK(tipLoad <= previous + 1e-9);
    previous = tipLoad;
    CHECK(tipLoad < 1e-8);
    CHECK(moment < 1e-8);
    CHECK(axial < 1e-8);
    CHECK(torsion < 1e-8);
  }
  CHECK(previous < 0.01);
}

TEST_CASE("Spline beam cantilever: first bending frequency against Euler-Bernoulli", "[spline_beam]") {
  // The element carries the rotary inertia of the section (3-75), so the mesh converges to the
  // Rayleigh-beam frequency, a little below Euler–Bernoulli's (by ≈ ½(1.875 r/2L)²·1.4 ≈ 6e-5
  // here): convergence is measured against a fine mesh, the 1 % bound against Euler–Bernoulli.
  const auto frequency = [](int n, double* exact) {
    const Cantilever c(n);
    MatX K, M;
    c.assemble(c.reference(), K, M);
    const Eigen::GeneralizedSelfAdjointEigenSolver<MatX> eig(0.5 * (K + K.transpose()), M);
    const double rhoA = Cantilever::rho * c.kernel.section.area;
    *exact = 1.8751040687 * 1.8751040687 / (2 * std::numbers::pi * Cantilever::L * Cantilever::L) *
             std::sqrt(c.EI() / rhoA);
    return std::sqrt(eig.eigenvalues()(0)) / (2 * std::numbers::pi);
  };
  double exact = 0.0;
  const double converged = frequency(40, &exact);
  std::printf("\nSpline beam cantilever, first bending frequency; Euler-Bernoulli %.6f Hz, 40 elements %.6f Hz\n",
              exact, converged);
  double previous = 1.0, error = 1.0;
  for (int n : {1, 3, 5, 10}) {
    const double f = frequency(n, &exact);
    error = std::abs(f / exact - 1.0);
    const double discretisation = std::abs(f / converged - 1.0);
    std::printf("  n = %2d: f1 = %.6f Hz, error vs Euler-Bernoulli %.3e, vs 40 elements %.3e\n", n, f, error,
                discretisation);
    CHECK(discretisation < previous);
    previous = discretisation;
  }
  CHECK(error < 0.01);
}

TEST_CASE("Spline beam cantilever: large bending under an end moment (thesis 8.1)", "[spline_beam]") {
  // End moment M = k 2π EI/L bends the cantilever into an arc of angle 2πk (a full circle for
  // k = 1). Newton on the twist increments, R ← R exp(Δθ̃), with tangent ∂F/∂q · ∂q/∂δ
  // (∂φ/∂δθ = T(φ)⁻¹), increments limited to 0.5 rad of rotation, one load step.
  std::printf("\nSpline beam, end moment k*2*pi*EI/L, tip position error / L\n");
  for (double k : {0.25, 1.0}) {
    double previous = 1.0;
    for (int n : {1, 3, 5, 10}) {
      if (k == 1.0 && n < 5) continue;  // a full circle on fewer elements is not a sensible mesh
      const Cantilever c(n);
      VecX q = c.reference();
      const double L = Cantilever::L, moment = k * 2 * std::numbers::pi * c.EI() / L;
      VecX f = VecX::Zero(c.size - 6);
      f(7 * n - 6 + 5) = moment;  // body-frame moment about z (planar: also inertial)
      int iterations = 0;
      bool converged = false;
      while (!converged && iterations < 60) {
        ++iterations;
        MatX Kq, M;
        VecX F;
        c.assemble(q, Kq, M, &F);
        for (int i = 1; i <= n; ++i) {
          const int o = 7 * i - 6 + 3;
          Kq.middleCols<3>(o) = Kq.middleCols<3>(o) * angularVelocityMapInverse<double>(Vec3(q.segment<3>(7 * i + 3)));
        }
        VecX dx = Kq.partialPivLu().solve(f - F);
        double rotation = 0.0;
        for (int i = 1; i <= n; ++i) rotation = std::max(rotation, dx.segment<3>(7 * i - 6 + 3).norm());
        if (rotation > 0.5) dx *= 0.5 / rotation;
        for (int i = 0; i < c.size - 6; ++i) {
          const int g = i + 6, local = g % 7;
          if (local < 3 || local == 6) q(g) += dx(i);
        }
        for (int i = 1; i <= n; ++i) {
          const Mat3 R = rotationMatrix<double>(Vec3(q.segment<3>(7 * i + 3))) *
                         rotationMatrix<double>(Vec3(dx.segment<3>(7 * i - 6 + 3)));
          q.segment<3>(7 * i + 3) = rotationVector(R);
        }
        converged = dx.norm() < 1e-10 * L;
      }
      REQUIRE(converged);
      const double kappa = moment / c.EI(), angle = kappa * L;
      const Vec3 exact(std::sin(angle) / kappa, (1.0 - std::cos(angle)) / kappa, 0.0);
      const double error = (Vec3(q.segment<3>(7 * n)) - exact).norm() / L;
      const double tipAngle = rotationVector(rotationMatrix<double>(Vec3(q.segment<3>(7 * n + 3)))).z();
      std::printf("  k = %.2f, n = %2d: tip error %.3e, tip angle %+.6f rad (%d Newton iterations)\n", k, n, error,
                  tipAngle, iterations);
      CHECK(error < previous);
      previous = error;
    }
    CHECK(previous < 1e-3);
  }
}
