// Co-rotational Timoshenko beam kernel (thesis 3.3, C.2): consistent shape functions, objectivity,
// forces as exact gradients, AD Jacobians, energy conservation, and beam theory (statics without
// shear locking, cantilever eigenfrequencies).

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "cranesim/elements/parts/corotated_elastic_tangent.hpp"
#include "cranesim/elements/rotated_ends.hpp"
#include "cranesim/elements/timoshenko_beam.hpp"
#include "cranesim/model/kernel_elements.hpp"
#include "random_states.hpp"
#include "cantilever_theory.hpp"
#include "element_differences.hpp"

using namespace cranesim;

namespace {

using Q12 = Eigen::Matrix<double, 12, 1>;
using M12 = Eigen::Matrix<double, 12, 12>;

constexpr double kPi = std::numbers::pi;

TimoshenkoBeamKernel makeBeam(double L, double outer, double inner, double E = 2.06e11, double nu = 0.25,
                              double rho = 7850.0) {
  TimoshenkoBeamKernel k;
  k.length = L;
  k.section = Section::circular(outer, inner, nu);
  k.material.youngs_modulus = E;
  k.material.shear_modulus = E / (2.0 * (1.0 + nu));
  k.material.density = rho;
  return k;
}

/// A section with unequal principal axes (I_y ≠ I_z) and a torsion constant of its own.
TimoshenkoBeamKernel makeRectangularBeam(double L) {
  TimoshenkoBeamKernel k;
  k.length = L;
  const double b = 0.12, h = 0.2;  // width along y, height along z
  k.section.area = b * h;
  k.section.Iy = b * h * h * h / 12.0;  // ∫ z² dA
  k.section.Iz = h * b * b * b / 12.0;  // ∫ y² dA
  k.section.J = 0.196 * b * b * b * h;  // rectangle h/b = 1.67
  k.section.shear_factor = 5.0 / 6.0;
  k.material.youngs_modulus = 2.1e11;
  k.material.shear_modulus = 8.1e10;
  k.material.density = 7850.0;
  return k;
}

std::vector<int> range(int from, int n) {
  std::vector<int> v(n);
  for (int i = 0; i < n; ++i) v[i] = from + i;
  return v;
}

std::unique_ptr<Element> beamElement(const TimoshenkoBeamKernel& k) { return makeElement(k, {0, 1}, range(0, 12), range(0, 12)); }

/// q of two frames.
Q12 coordinates(const Vec3& r1, const Mat3& R1, const Vec3& r2, const Mat3& R2) {
  Q12 q;
  q << r1, rotationVector(R1), r2, rotationVector(R2);
  return q;
}

/// q moved by the twist δ = [δr¹, δθ¹, δr², δθ²]: r + δr, R exp(δθ̃) (body-frame rotation).
Q12 twisted(const Q12& q, const Q12& delta) {
  Q12 p = q;
  for (int e = 0; e < 2; ++e) {
    p.segment<3>(6 * e) += delta.segment<3>(6 * e);
    const Mat3 R = rotationMatrix<double>(Vec3(q.segment<3>(6 * e + 3))) *
                   rotationMatrix<double>(Vec3(delta.segment<3>(6 * e + 3)));
    p.segment<3>(6 * e + 3) = rotationVector(R);
  }
  return p;
}

/// q̇ from dq: φ̇ = T(φ)⁻¹ ω.
Q12 coordinateRates(const Q12& q, const Q12& v) {
  Q12 qdot = v;
  for (int e = 0; e < 2; ++e)
    qdot.segment<3>(6 * e + 3) = angularVelocityMapInverse<double>(Vec3(q.segment<3>(6 * e + 3))) * v.segment<3>(6 * e + 3);
  return qdot;
}

using test::Rng;

/// A randomly placed, moderately deformed element: end rotations and stretch of order `strain`.
Q12 deformedState(Rng& rng, const TimoshenkoBeamKernel& k, double strain) {
  const Vec3 r1 = rng.vec(5.0);
  const Mat3 R1 = rng.rotation(3.0);
  const Mat3 R2 = R1 * rng.rotation(3.0 * strain) ;
  const Vec3 r2 = r1 + R1 * (k.length * (Vec3::UnitX() + rng.vec(strain)));
  return coordinates(r1, R1, r2, R2);
}

/// dq of a rigid motion: translation velocity `v0` of the origin and inertial angular velocity Ω.
Q12 rigidVelocity(const Q12& q, const Vec3& v0, const Vec3& Omega) {
  Q12 v;
  for (int e = 0; e < 2; ++e) {
    const Vec3 r = q.segment<3>(6 * e);
    v.segment<3>(6 * e) = v0 + Omega.cross(r);
    v.segment<3>(6 * e + 3) = rotationMatrix<double>(Vec3(q.segment<3>(6 * e + 3))).transpose() * Omega;
  }
  return v;
}

/// ∂F/∂q at (q, v = 0), no gravity, from the element's AD Jacobian.
M12 stiffness(const TimoshenkoBeamKernel& k, const Q12& q) {
  const std::unique_ptr<Element> el = beamElement(k);
  const Q12 zero = Q12::Zero();
  const ElementInput in{q.data(), zero.data(), zero.data(), 0.0, Vec3::Zero()};
  Eigen::Matrix<double, 12, 24> J;
  el->jacobian(in, 0.0, J.data());
  return J.leftCols<12>();
}

/// The undeformed element along x from `x0`.
Q12 straightState(double x0, double L) {
  Q12 q = Q12::Zero();
  q(0) = x0;
  q(6) = x0 + L;
  return q;
}

using D6 = Dual<double, 6>;

/// The co-rotated elastic forces and their end-2 columns by forward AD: r² + δr², R² exp(δθ̃²) seeded.
CoRotatedElasticTangent forwardAD(const TimoshenkoBeamKernel& k, const Vec3& r1, const Mat3& R1, const Vec3& r2,
                                  const Mat3& R2, const Q12& v, const Eigen::Matrix<double, 12, 12>& K) {
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

TEST_CASE("Timoshenko beam: consistent shape functions give the exact Timoshenko stiffness", "[timoshenko]") {
  const TimoshenkoBeamKernel k = makeRectangularBeam(1.3);
  const double L = k.length, E = k.material.youngs_modulus, G = k.material.shear_modulus;
  // Interpolation: identity at the ends.
  const auto f0 = k.shapeFunctions(0.0), f1 = k.shapeFunctions(1.0);
  CHECK((f0.N.leftCols<6>() - Eigen::Matrix<double, 6, 6>::Identity()).norm() < 1e-14);
  CHECK(f0.N.rightCols<6>().norm() < 1e-14);
  CHECK((f1.N.rightCols<6>() - Eigen::Matrix<double, 6, 6>::Identity()).norm() < 1e-14);
  CHECK(f1.N.leftCols<6>().norm() < 1e-14);
  // Shear strains are constant along the element (homogeneous solutions, C-18).
  const auto B0 = k.strainMatrix(0.1), B1 = k.strainMatrix(0.8);
  CHECK((B0.bottomRows<2>() - B1.bottomRows<2>()).norm() < 1e-12 * B0.bottomRows<2>().norm());

  // Closed form (Przemieniecki): plane x–y with (v, ψ_z), plane x–z with (w, ψ_y).
  const TimoshenkoBeamKernel::Mat12 K = k.localStiffness();
  TimoshenkoBeamKernel::Mat12 Kc = TimoshenkoBeamKernel::Mat12::Zero();
  const auto bar = [&](int i, int j, double s) {
    Kc(i, i) += s, Kc(j, j) += s, Kc(i, j) -= s, Kc(j, i) -= s;
  };
  bar(0, 6, E * k.section.area / L);
  bar(3, 9, G * k.section.J / L);
  const auto bending = [&](const int idx[4], double I, double sign) {
    const double Phi = 12.0 * E * I / (k.section.shear_factor * G * k.section.area * L * L);
    const double c = E * I / ((1.0 + Phi) * L * L * L);
    // dofs (v¹, θ¹, v², θ²); for x–z, θ = −ψ_y (sign = −1)
    const double s[4] = {1.0, sign, 1.0, sign};
    const double m[4][4] = {{12, 6 * L, -12, 6 * L},
                            {6 * L, (4 + Phi) * L * L, -6 * L, (2 - Phi) * L * L},
                            {-12, -6 * L, 12, -6 * L},
                            {6 * L, (2 - Phi) * L * L, -6 * L, (4 + Phi) * L * L}};
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) Kc(idx[a], idx[b]) += c * s[a] * s[b] * m[a][b];
  };
  const int xy[4] = {1, 5, 7, 11}, xz[4] = {2, 4, 8, 10};
  bending(xy, k.section.Iz, 1.0);
  bending(xz, k.section.Iy, -1.0);
  CHECK((K - Kc).norm() < 1e-12 * Kc.norm());
}

TEST_CASE("Timoshenko beam: mass matrix is symmetric positive definite and exact for rigid motion", "[timoshenko]") {
  const TimoshenkoBeamKernel k = makeRectangularBeam(2.5);
  Rng rng(7);
  const double rho = k.material.density, A = k.section.area, L = k.length, m = rho * A * L;
  for (int trial = 0; trial < 5; ++trial) {
    const Q12 q = deformedState(rng, k, 0.05);
    const M12 M = k.massMatrix<double>(q);
    CHECK((M - M.transpose()).norm() < 1e-14 * M.norm());
    const double lmin = Eigen::SelfAdjointEigenSolver<M12>(M).eigenvalues().minCoeff();
    CHECK(lmin > 1e-6 * M.norm());
  }
  // Rigid motion of the straight element: T = ½ m |v_c|² + ½ Ωᵀ Θ_c Ω.
  for (int trial = 0; trial < 5; ++trial) {
    const Vec3 r1 = rng.vec(3.0);
    const Mat3 R = rng.rotation(3.0);
    const Q12 q = coordinates(r1, R, Vec3(r1 + L * R.col(0)), R);
    const Vec3 vc = rng.vec(), Omega = rng.vec();
    const Vec3 c = r1 + 0.5 * L * R.col(0);
    const Q12 v = rigidVelocity(q, Vec3(vc - Omega.cross(c)), Omega);
    const Vec3 theta_body(rho * (k.section.Iy + k.section.Iz) * L, rho * k.section.Iy * L + m * L * L / 12.0,
                          rho * k.section.Iz * L + m * L * L / 12.0);
    const Vec3 Ob = R.transpose() * Omega;
    const double expected = 0.5 * m * vc.squaredNorm() + 0.5 * Ob.dot(theta_body.cwiseProduct(Ob));
    CHECK(k.kineticEnergy(q, v) == Approx(expected).epsilon(1e-12));
  }
}

TEST_CASE("Timoshenko beam: no internal force under rigid placements and rigid velocities", "[timoshenko]") {
  TimoshenkoBeamKernel k = makeBeam(3.0, 0.15, 0.12);
  k.damping = 0.01;
  const double EA = k.material.youngs_modulus * k.section.area;
  Rng rng(13);
  double worst = 0.0, worst_energy = 0.0, worst_rate = 0.0;
  for (int trial = 0; trial < 20; ++trial) {
    const Vec3 r1 = rng.vec(20.0);
    const Mat3 R = rng.rotation(3.1);
    Q12 q = coordinates(r1, R, Vec3(r1 + k.length * R.col(0)), R);
    // Node 2 may carry another rotation vector of the same rotation (angle θ − 2π).
    if (trial % 2 == 1) {
      Vec3 phi = q.segment<3>(9);
      phi *= 1.0 - 2.0 * kPi / phi.norm();
      q.segment<3>(9) = phi;
    }
    const Q12 v = rigidVelocity(q, rng.vec(3.0), rng.vec(2.0));
    worst = std::max(worst, k.elasticForce<double>(q, Q12::Zero()).norm());
    worst = std::max(worst, k.elasticForce<double>(q, v).norm());
    worst_energy = std::max(worst_energy, k.strainEnergy(q));
    // Deformed element moving rigidly: the damping force (∝ strain rates) is zero.
    const Q12 qd = deformedState(rng, k, 0.01);
    const Q12 vd = rigidVelocity(qd, rng.vec(3.0), rng.vec(2.0));
    const Q12 Fd = k.elasticForce<double>(qd, vd) - k.elasticForce<double>(qd, Q12::Zero());
    worst_rate = std::max(worst_rate, Fd.norm() / k.elasticForce<double>(qd, Q12::Zero()).norm());
  }
  std::printf("[timoshenko] rigid placements: max |F_int| = %.3g N (EA = %.3g N), max U = %.3g J, "
              "max |F_damp|/|F_int| under rigid velocity = %.3g\n", worst, EA, worst_energy, worst_rate);
  CHECK(worst < 1e-13 * EA);
  CHECK(worst_energy < 1e-16 * EA * k.length);
  CHECK(worst_rate < 1e-10);
}

TEST_CASE("Timoshenko beam: elastic and gravity forces are gradients along twist perturbations", "[timoshenko]") {
  const TimoshenkoBeamKernel k = makeRectangularBeam(2.0);
  const Vec3 g(0.3, -0.2, -9.81);
  Rng rng(21);
  double worst_el = 0.0, worst_g = 0.0;
  for (int trial = 0; trial < 5; ++trial) {
    const Q12 q = deformedState(rng, k, 0.02);
    const Q12 F = k.elasticForce<double>(q, Q12::Zero());
    const Q12 Fg = k.force<double>(q, Q12::Zero(), 0.0, g) - k.force<double>(q, Q12::Zero(), 0.0, Vec3::Zero());
    Q12 dU, dV;
    for (int i = 0; i < 12; ++i) {
      const double h = 1e-6;
      const Q12 e = Q12::Unit(i);
      dU(i) = (k.strainEnergy(twisted(q, h * e)) - k.strainEnergy(twisted(q, -h * e))) / (2 * h);
      dV(i) = (k.gravityPotential(twisted(q, h * e), g) - k.gravityPotential(twisted(q, -h * e), g)) / (2 * h);
    }
    worst_el = std::max(worst_el, (F - dU).norm() / F.norm());
    worst_g = std::max(worst_g, (Fg - dV).norm() / Fg.norm());
  }
  std::printf("[timoshenko] gradient checks: elastic rel. err %.3g, gravity rel. err %.3g\n", worst_el, worst_g);
  CHECK(worst_el < 1e-6);
  CHECK(worst_g < 1e-7);
}

TEST_CASE("Timoshenko beam: closed-form J_d equals central differences of the local deformations", "[timoshenko]") {
  const TimoshenkoBeamKernel k = makeRectangularBeam(2.0);
  Rng rng(34);
  double worst = 0.0;
  // Small to large deformations (relative end rotations up to ~2.7 rad, chord off the mid-frame
  // x axis by up to ~1 rad), frames anywhere up to angle 3.
  for (const double strain : {0.0, 1e-3, 0.05, 0.3, 0.9}) {
    for (int trial = 0; trial < 4; ++trial) {
      const Q12 q = deformedState(rng, k, strain);
      const Vec3 r1 = q.segment<3>(0), r2 = q.segment<3>(6);
      const Mat3 R1 = rotationMatrix<double>(Vec3(q.segment<3>(3))), R2 = rotationMatrix<double>(Vec3(q.segment<3>(9)));
      const auto c = k.coRotateWithTangent<double>(r1, R1, r2, R2);
      CHECK((c.d - k.localDeformation<double>(q)).norm() == 0.0);
      M12 Jfd;
      for (int j = 0; j < 12; ++j) {
        const double h = 1e-6;
        Jfd.col(j) = (k.localDeformation<double>(twisted(q, h * Q12::Unit(j))) -
                      k.localDeformation<double>(twisted(q, -h * Q12::Unit(j)))) / (2 * h);
      }
      worst = std::max(worst, (c.matrix() - Jfd).norm() / Jfd.norm());
      // The forces apply J_d and J_dᵀ through its factors: the matrix's products to rounding.
      const Q12 x = Q12::Random();
      CHECK((c.apply(x) - c.matrix() * x).norm() <= 1e-13 * (c.matrix().norm() * x.norm()));
      CHECK((c.applyTransposed(x) - c.matrix().transpose() * x).norm() <= 1e-13 * (c.matrix().norm() * x.norm()));
    }
  }
  std::printf("[timoshenko] closed-form J_d vs central differences: rel. err %.3g\n", worst);
  CHECK(worst < 1e-8);
}

TEST_CASE("Co-rotated beam: elastic forces' end-2 columns in closed form match forward AD", "[timoshenko][corotation]") {
  Rng rng(41);
  double worst = 0.0;
  for (const double damping : {0.0, 0.03}) {
    for (const double strain : {1e-6, 0.05, 0.4}) {
      TimoshenkoBeamKernel k = makeRectangularBeam(1.7);
      k.damping = damping;
      const Eigen::Matrix<double, 12, 12> K = k.localStiffness();
      for (int trial = 0; trial < 6; ++trial) {
        const Vec3 r1 = rng.vec(5.0);
        const Mat3 R1 = rng.rotation(3.0);
        const Mat3 R2 = R1 * rng.rotation(3.0 * strain);
        const Vec3 r2 = r1 + R1 * (k.length * (Vec3::UnitX() + rng.vec(strain)));
        Q12 v;
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

TEST_CASE("Timoshenko beam: AD Jacobian equals finite differences of the residual", "[timoshenko]") {
  TimoshenkoBeamKernel k = makeRectangularBeam(1.5);
  k.damping = 2e-3;
  const std::unique_ptr<Element> el = beamElement(k);
  const Vec3 g(0.1, 0.2, -9.81);
  Rng rng(5);
  double worst = 0.0;
  for (int trial = 0; trial < 3; ++trial) {
    const Q12 q = deformedState(rng, k, 0.02);
    Q12 v, a;
    for (int i = 0; i < 12; ++i) v(i) = 2.0 * rng(), a(i) = 10.0 * rng();
    const double cj = 37.0;
    const ElementInput in{q.data(), v.data(), a.data(), 0.0, g};
    Eigen::Matrix<double, 12, 24> J, Jfd;
    el->jacobian(in, cj, J.data());
    for (int c = 0; c < 24; ++c) {
      const double h = 1e-6;
      Q12 qp = q, qm = q, vp = v, vm = v, ap = a, am = a;
      if (c < 12) {
        qp(c) += h, qm(c) -= h;
      } else {
        vp(c - 12) += h, vm(c - 12) -= h, ap(c - 12) += cj * h, am(c - 12) -= cj * h;
      }
      Q12 rp, rm;
      const ElementInput inp{qp.data(), vp.data(), ap.data(), 0.0, g}, inm{qm.data(), vm.data(), am.data(), 0.0, g};
      el->residual(inp, rp.data());
      el->residual(inm, rm.data());
      Jfd.col(c) = (rp - rm) / (2 * h);
    }
    // Column blocks scaled separately: stiffness dominates the q block.
    worst = std::max(worst, (J.leftCols<12>() - Jfd.leftCols<12>()).norm() / Jfd.leftCols<12>().norm());
    worst = std::max(worst, (J.rightCols<12>() - Jfd.rightCols<12>()).norm() / Jfd.rightCols<12>().norm());
  }
  std::printf("[timoshenko] Jacobian vs central differences: rel. err %.3g\n", worst);
  CHECK(worst < 1e-6);
}

TEST_CASE("Timoshenko beam: the velocity columns of the Jacobian (closed form) equal forward AD to rounding", "[timoshenko]") {
  // velocityTangent (section_inertia_tangent.hpp) against ∂r/∂dq by forward AD (12 directions)
  // at states with large velocities, where the twist bracket terms matter.
  TimoshenkoBeamKernel k = makeRectangularBeam(1.5);
  k.damping = 2e-3;
  const std::unique_ptr<Element> el = beamElement(k);
  const Vec3 g(0.1, 0.2, -9.81);
  using D = Dual<double, 12>;
  Rng rng(8);
  double worst = 0.0;
  for (int trial = 0; trial < 4; ++trial) {
    const Q12 q = deformedState(rng, k, 0.05);
    Q12 v, a;
    for (int i = 0; i < 12; ++i) v(i) = 20.0 * rng(), a(i) = 100.0 * rng();
    const ElementInput in{q.data(), v.data(), a.data(), 0.0, g};
    Eigen::Matrix<double, 12, 24> J;
    el->jacobian(in, 0.0, J.data());
    Eigen::Matrix<D, 12, 1> vd;
    for (int i = 0; i < 12; ++i) vd(i) = seeded<double, 12>(v(i), i);
    const Eigen::Matrix<D, 12, 1> r =
        k.massMatrix<double>(q).cast<D>() * a.cast<D>() + k.force<D>(q.cast<D>(), vd, 0.0, g);
    M12 Jad;
    for (int i = 0; i < 12; ++i) Jad.row(i) = r(i).derivatives().transpose();
    worst = std::max(worst, (J.rightCols<12>() - Jad).norm() / Jad.norm());
    // The coordinate columns (inertia in the rotation directions only) against forward AD of
    // the whole residual in all twelve.
    Eigen::Matrix<D, 12, 1> qd;
    for (int i = 0; i < 12; ++i) qd(i) = seeded<double, 12>(q(i), i);
    const Eigen::Matrix<D, 12, 1> rq = k.residual<D>(qd, v.cast<D>(), a.cast<D>(), 0.0, g);
    for (int i = 0; i < 12; ++i) Jad.row(i) = rq(i).derivatives().transpose();
    worst = std::max(worst, (J.leftCols<12>() - Jad).norm() / Jad.norm());
  }
  std::printf("[timoshenko] closed-form ∂r/∂dq and split ∂r/∂q vs forward AD: rel. err %.3g\n", worst);
  CHECK(worst < 1e-10);
}

TEST_CASE("Timoshenko beam: the coordinate columns by frame indifference equal forward AD, inertia dominating", "[timoshenko]") {
  // The DAE Jacobian's ∂r/∂q from end 2's six columns (objective_tangent.hpp) against forward AD
  // of the whole residual in all twelve, column block by column block, for a beam a million
  // times softer than steel (inertia, gravity and damping not hidden under the stiffness), at
  // large end rotations, fast turning and with mass damping.
  TimoshenkoBeamKernel k = makeRectangularBeam(1.5);
  k.material.youngs_modulus *= 1e-6;
  k.material.shear_modulus *= 1e-6;
  k.damping = 0.05;
  const std::unique_ptr<Element> el = beamElement(k);
  const Vec3 g(1.5, -2.0, -9.81);
  Rng rng(17);
  double worst = 0.0;
  for (int trial = 0; trial < 6; ++trial) {
    const Q12 q = deformedState(rng, k, 0.1);
    Q12 v, a;
    for (int i = 0; i < 12; ++i) v(i) = 5.0 * rng(), a(i) = 30.0 * rng();
    const double alpha = trial % 2 ? 0.6 : 0.0;
    ElementInput in{q.data(), v.data(), a.data(), 0.0, g};
    in.mass_damping = alpha;
    Eigen::Matrix<double, 12, 24> J;
    el->jacobian(in, 3.0, J.data());
    const M12 Jad = coordinateDerivative(q, [&]<class S>(const Eigen::Matrix<S, 12, 1>& qs) {
      return k.residual<S>(qs, v.cast<S>(), Eigen::Matrix<S, 12, 1>((a + alpha * v).cast<S>()), 0.0, g);
    });
    INFO("trial " << trial);
    const double error = test::worstColumnBlockError(J.leftCols<12>(), Jad);
    CHECK(error < 1e-10);
    worst = std::max(worst, error);
  }
  std::printf("[timoshenko] frame-indifferent ∂r/∂q vs forward AD (soft beam): rel. err %.3g\n", worst);
}

TEST_CASE("Rotated-ends beam: the Jacobian (closed-form velocity columns, frame-indifferent coordinate columns) equals forward AD", "[timoshenko]") {
  // A beam whose section axes differ from its nodes' axes by constant rotations (rotated_ends.hpp,
  // every tube of a full-member truss): its velocity tangent Tᵀ C_b T and its coordinate columns
  // from end 2's six against forward AD of the whole residual in all twelve directions, column
  // block by column block, stiff (steel) and a million times softer (inertia, gravity and
  // damping not hidden under the stiffness), with mass damping.
  const Vec3 g(1.5, -2.0, -9.81);
  Rng rng(29);
  double worst = 0.0;
  for (const double softness : {1.0, 1e-6}) {
    TimoshenkoBeamKernel beam = makeRectangularBeam(1.5);
    beam.material.youngs_modulus *= softness;
    beam.material.shear_modulus *= softness;
    beam.damping = 0.02;
    const RotatedEndsBeamKernel k(beam, rng.rotation(3.0), rng.rotation(3.0));
    const std::unique_ptr<Element> el = makeElement(k, {0, 1}, range(0, 12), range(0, 12));
    for (int trial = 0; trial < 4; ++trial) {
      const Q12 q = deformedState(rng, beam, 0.1);
      Q12 v, a;
      for (int i = 0; i < 12; ++i) v(i) = 5.0 * rng(), a(i) = 30.0 * rng();
      const double alpha = trial % 2 ? 0.6 : 0.0, cj = 9.0;
      ElementInput in{q.data(), v.data(), a.data(), 0.0, g};
      in.mass_damping = alpha;
      Eigen::Matrix<double, 12, 24> J;
      el->jacobian(in, cj, J.data());
      const auto residual = [&]<class S>(const Eigen::Matrix<S, 12, 1>& qq, const Eigen::Matrix<S, 12, 1>& vv) {
        return Eigen::Matrix<S, 12, 1>(k.massMatrix<S>(qq) * Eigen::Matrix<S, 12, 1>(a.cast<S>() + S(alpha) * vv) + k.force<S>(qq, vv, 0.0, g));
      };
      Eigen::Matrix<double, 12, 24> Jad;
      Jad << coordinateDerivative(q, [&]<class S>(const Eigen::Matrix<S, 12, 1>& qs) { return residual(qs, Eigen::Matrix<S, 12, 1>(v.cast<S>())); }),
          coordinateDerivative(v, [&]<class S>(const Eigen::Matrix<S, 12, 1>& vs) { return residual(Eigen::Matrix<S, 12, 1>(q.cast<S>()), vs); });
      Jad.rightCols<12>() += cj * k.massMatrix<double>(q);
      INFO("softness " << softness << ", trial " << trial);
      const double error = test::worstColumnBlockError(J, Jad);
      CHECK(error < 1e-10);
      worst = std::max(worst, error);
    }
  }
  std::printf("[rotated ends] Jacobian vs forward AD: rel. err %.3g\n", worst);
}

TEST_CASE("Timoshenko beam: free motion conserves kinetic + strain + gravity energy", "[timoshenko]") {
  // With M a = −F: d(T + U + V)/dt = v·M a + ½ vᵀ Ṁ v + U̇ + V̇ must vanish (and equal −η ḋᵀKḋ
  // with material damping).
  TimoshenkoBeamKernel k = makeRectangularBeam(2.0);
  k.material.youngs_modulus = 2.1e9;  // soft, so that elastic and inertial powers are comparable
  k.material.shear_modulus = 8.1e8;
  const Vec3 g(0.3, -0.2, -9.81);
  Rng rng(17);
  for (int damped = 0; damped < 2; ++damped) {
    k.damping = damped ? 0.01 : 0.0;
    double worst = 0.0;
    for (int trial = 0; trial < 5; ++trial) {
      const Q12 q = deformedState(rng, k, 0.05);
      Q12 v;
      for (int i = 0; i < 12; ++i) v(i) = 3.0 * rng();
      const M12 M = k.massMatrix<double>(q);
      const Q12 F = k.force<double>(q, v, 0.0, g);
      const Q12 a = -M.ldlt().solve(F);
      const Q12 qdot = coordinateRates(q, v);
      const double h = 1e-6;
      const M12 Mdot = (k.massMatrix<double>(q + h * qdot) - k.massMatrix<double>(q - h * qdot)) / (2 * h);
      const double Vdot = (k.potentialEnergy(q + h * qdot, 0.0, g) - k.potentialEnergy(q - h * qdot, 0.0, g)) / (2 * h);
      const double Edot = v.dot(M * a) + 0.5 * v.dot(Mdot * v) + Vdot;
      const Q12 Fdamp = k.elasticForce<double>(q, v) - k.elasticForce<double>(q, Q12::Zero());
      const double expected = -v.dot(Fdamp);
      const double scale = std::abs(v.dot(M * a)) + std::abs(Vdot);
      worst = std::max(worst, std::abs(Edot - expected) / scale);
      if (damped) CHECK(expected < 0.0);
    }
    std::printf("[timoshenko] energy balance (%s): max |dE/dt − P_damp| / scale = %.3g\n",
                damped ? "damped" : "undamped", worst);
    CHECK(worst < 1e-7);
  }
}

TEST_CASE("Timoshenko beam: one-element cantilever statics are exact (no shear locking)", "[timoshenko]") {
  const double nu = 0.25;
  for (const auto& [L, r] : {std::pair{15.0, 0.15}, std::pair{2.0, 0.3}}) {
    const TimoshenkoBeamKernel k = makeBeam(L, r, 0.0, 2.06e11, nu);
    const double E = k.material.youngs_modulus, G = k.material.shear_modulus;
    const double A = k.section.area, I = k.section.Iz, J = k.section.J, kappa = k.section.shear_factor;
    const M12 K = stiffness(k, straightState(0.0, L));
    // Node 1 clamped: K₂₂ u₂ = f₂.
    const Eigen::Matrix<double, 6, 6> K22 = K.bottomRightCorner<6, 6>();
    const auto solve = [&](int dof, double load) {
      Eigen::Matrix<double, 6, 1> f = Eigen::Matrix<double, 6, 1>::Zero();
      f(dof) = load;
      return Eigen::Matrix<double, 6, 1>(K22.fullPivLu().solve(f));
    };
    const double P = 1.0e3, Mz = 1.0e3, T = 1.0e3;
    const auto uy = solve(1, P), uz = solve(2, P), ux = solve(0, P), tz = solve(5, Mz), tx = solve(3, T);
    const double bend = P * L * L * L / (3 * E * I), shear = P * L / (kappa * G * A);
    const double tip = bend + shear;
    std::printf("[timoshenko] cantilever L=%g r=%g: tip v %.10g (exact %.10g, EB %.10g), w %.10g, "
                "slope %.10g (exact %.10g)\n", L, r, uy(1), tip, bend, uz(2), uy(5), P * L * L / (2 * E * I));
    std::printf("[timoshenko]   end moment: rotation %.10g (ML/EI %.10g), deflection %.10g (ML²/2EI %.10g); "
                "axial %.10g (PL/EA %.10g); torsion %.10g (TL/GJ %.10g)\n", tz(5), Mz * L / (E * I), tz(1),
                Mz * L * L / (2 * E * I), ux(0), P * L / (E * A), tx(3), T * L / (G * J));
    CHECK(uy(1) == Approx(tip).epsilon(1e-6));
    CHECK(uz(2) == Approx(tip).epsilon(1e-6));
    CHECK(uy(5) == Approx(P * L * L / (2 * E * I)).epsilon(1e-6));
    CHECK(uz(4) == Approx(-P * L * L / (2 * E * I)).epsilon(1e-6));
    CHECK(tz(5) == Approx(Mz * L / (E * I)).epsilon(1e-6));
    CHECK(tz(1) == Approx(Mz * L * L / (2 * E * I)).epsilon(1e-6));
    CHECK(ux(0) == Approx(P * L / (E * A)).epsilon(1e-6));
    CHECK(tx(3) == Approx(T * L / (G * J)).epsilon(1e-6));
  }
  // Without a shear factor the element is Euler–Bernoulli: PL³/(3EI) exactly.
  TimoshenkoBeamKernel k = makeBeam(2.0, 0.3, 0.0, 2.06e11, nu);
  k.section.shear_factor = 0.0;
  const M12 K = stiffness(k, straightState(0.0, k.length));
  Eigen::Matrix<double, 6, 1> f = Eigen::Matrix<double, 6, 1>::Zero();
  f(1) = 1e3;
  const Eigen::Matrix<double, 6, 1> u = K.bottomRightCorner<6, 6>().fullPivLu().solve(f);
  CHECK(u(1) == Approx(1e3 * 8.0 / (3 * k.material.youngs_modulus * k.section.Iz)).epsilon(1e-9));
}

namespace {

/// First bending eigenfrequency (Hz) of a clamped–free beam of `n` elements along x.
double cantileverFrequency(const TimoshenkoBeamKernel& element, int n) {
  const int N = 6 * (n + 1);
  MatX M = MatX::Zero(N, N), K = MatX::Zero(N, N);
  for (int e = 0; e < n; ++e) {
    const Q12 q = straightState(e * element.length, element.length);
    M.block<12, 12>(6 * e, 6 * e) += element.massMatrix<double>(q);
    K.block<12, 12>(6 * e, 6 * e) += stiffness(element, q);
  }
  const MatX Kf = K.bottomRightCorner(N - 6, N - 6), Mf = M.bottomRightCorner(N - 6, N - 6);
  const Eigen::GeneralizedSelfAdjointEigenSolver<MatX> eig(0.5 * (Kf + Kf.transpose()), Mf);
  return std::sqrt(eig.eigenvalues().minCoeff()) / (2.0 * kPi);
}

}  // namespace

TEST_CASE("Timoshenko beam: cantilever eigenfrequencies (Euler–Bernoulli slender, Timoshenko thick)", "[timoshenko]") {
  const double nu = 0.25;
  {
    const double L = 15.0;
    const TimoshenkoBeamKernel k = makeBeam(L / 10, 0.15, 0.0, 2.06e11, nu);
    const double EI = k.material.youngs_modulus * k.section.Iz, rhoA = k.material.density * k.section.area;
    const double f_eb = 1.8751 * 1.8751 / (2 * kPi * L * L) * std::sqrt(EI / rhoA);
    const double f = cantileverFrequency(k, 10);
    std::printf("[timoshenko] slender cantilever (L=15, r=0.15), 10 elements: f1 = %.6f Hz, EB %.6f Hz (%+.4f %%)\n", f,
                f_eb, 100 * (f / f_eb - 1));
    CHECK(f == Approx(f_eb).epsilon(5e-3));
  }
  {
    const double L = 2.0;
    const TimoshenkoBeamKernel k = makeBeam(L / 10, 0.3, 0.0, 2.06e11, nu);
    const double EI = k.material.youngs_modulus * k.section.Iz, rhoA = k.material.density * k.section.area;
    const double kGA = k.section.shear_factor * k.material.shear_modulus * k.section.area;
    const double f_eb = 1.8751 * 1.8751 / (2 * kPi * L * L) * std::sqrt(EI / rhoA);
    const double f_t = test::timoshenkoCantileverFrequencies(L, EI, kGA, rhoA, k.material.density * k.section.Iz, 1)[0];
    // The reference itself: Euler–Bernoulli in the slender limit (same section, 100× longer).
    const double f_slender = test::timoshenkoCantileverFrequencies(100 * L, EI, kGA, rhoA, k.material.density * k.section.Iz, 1)[0];
    CHECK(f_slender == Approx(f_eb / 1e4).epsilon(1e-4));
    const double f = cantileverFrequency(k, 10);
    std::printf("[timoshenko] thick cantilever (L=2, r=0.3), 10 elements: f1 = %.4f Hz, Timoshenko %.4f Hz "
                "(%+.4f %%), EB %.4f Hz (%+.4f %%)\n", f, f_t, 100 * (f / f_t - 1), f_eb, 100 * (f / f_eb - 1));
    CHECK(std::abs(f - f_t) < std::abs(f - f_eb));
    CHECK(f == Approx(f_t).epsilon(5e-3));
  }
}
