// The generalized-α method (solvers/generalized_alpha.hpp) on the pendulum: second-order
// convergence at fixed steps against a tight IDAS run, the spectral radius ρ∞ as the damping of
// vibration the step does not resolve, energy kept by ρ∞ = 1, and the constraints held at steps.

#include <catch2/catch.hpp>

#include <cmath>
#include <vector>
#include <numbers>

#include "cranesim/math/rotation.hpp"
#include "cranesim/solvers/generalized_alpha.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

/// The pendulum scene (a 1 m rod hinged at its end) released from `amplitude_deg`.
Scene pendulum(double amplitude_deg) {
  Scene scene = test::loadScene("pendulum.yaml");
  const double a = amplitude_deg * std::numbers::pi / 180.0;
  RigidBodySpec& rod = scene.bodies[0];
  rod.rotation = axisAngle(Vec3::UnitY(), a);
  rod.position = -rod.rotation * Vec3(0, 0, 0.5);
  return scene;
}

/// The scene integrated by generalized-α at fixed steps (Newton still to rtol, atol).
Scene generalizedAlpha(Scene scene, double rho_inf, double step) {
  scene.solver.integrator = Integrator::GeneralizedAlpha;
  scene.solver.rho_inf = rho_inf;
  scene.solver.fixed_step = step;
  return scene;
}

/// θ_n / θ_0 of the method applied to the linear oscillator θ'' = −ω² θ released from rest, from
/// its relations in generalized_alpha.hpp solved as a linear system per step (h = 1, y = [θ, θ'],
/// w₀ = ẏ₀ as after a start).
std::vector<double> oscillatorSteps(double rho_inf, double omega_h, int steps) {
  const auto k = GeneralizedAlphaCoefficients::fromSpectralRadius(rho_inf);
  Eigen::Matrix2d A;
  A << 0.0, 1.0, -omega_h * omega_h, 0.0;
  Eigen::Vector2d y(1.0, 0.0), w = A * y, yp = w;
  std::vector<double> theta{1.0};
  for (int n = 0; n < steps; ++n) {
    // Unknowns [y₁, w₁]: y₁ − γ w₁ = y + (1 − γ) w;  (1 − α_m) w₁ − (1 − α_f) A y₁ = α_f ẏ − α_m w.
    Eigen::Matrix4d M = Eigen::Matrix4d::Zero();
    M.topLeftCorner<2, 2>().setIdentity();
    M.topRightCorner<2, 2>() = -k.gamma * Eigen::Matrix2d::Identity();
    M.bottomLeftCorner<2, 2>() = -(1.0 - k.alpha_f) * A;
    M.bottomRightCorner<2, 2>() = (1.0 - k.alpha_m) * Eigen::Matrix2d::Identity();
    Eigen::Vector4d rhs;
    rhs << y + (1.0 - k.gamma) * w, k.alpha_f * yp - k.alpha_m * w;
    const Eigen::Vector4d x = M.lu().solve(rhs);
    y = x.head<2>(), w = x.tail<2>(), yp = A * y;
    theta.push_back(y(0));
  }
  return theta;
}

/// Largest distance between the rod tip's samples of two runs.
double tipDeviation(const test::SimulationRun& a, const test::SimulationRun& b) {
  const auto &pa = a.jointPositions("rod.tip"), &pb = b.jointPositions("rod.tip");
  REQUIRE(pa.size() == pb.size());
  double worst = 0.0;
  for (std::size_t k = 0; k < pa.size(); k += 3)
    worst = std::max(worst, (Vec3(pa[k], pa[k + 1], pa[k + 2]) - Vec3(pb[k], pb[k + 1], pb[k + 2])).norm());
  return worst;
}

}  // namespace

TEST_CASE("Generalized-α: coefficients of the one-parameter family", "[dynamics][generalized_alpha]") {
  const auto trapezoidal = GeneralizedAlphaCoefficients::fromSpectralRadius(1.0);
  CHECK(trapezoidal.alpha_m == Approx(0.5));
  CHECK(trapezoidal.alpha_f == Approx(0.5));
  CHECK(trapezoidal.gamma == Approx(0.5));
  CHECK(trapezoidal.error_constant == Approx(1.0 / 12.0));  // the trapezoidal rule's
  const auto bdf2 = GeneralizedAlphaCoefficients::fromSpectralRadius(0.0);
  CHECK(bdf2.alpha_m == Approx(-0.5));
  CHECK(bdf2.alpha_f == Approx(0.0).margin(1e-15));
  CHECK(bdf2.gamma == Approx(1.0));
}

TEST_CASE("Generalized-α converges at second order on the pendulum", "[dynamics][generalized_alpha]") {
  Scene scene = pendulum(90.0);
  scene.solver.t_end = 2.0;
  scene.solver.rtol = 1e-10;
  scene.solver.atol = AbsoluteTolerance::uniform(1e-12);
  const test::SimulationRun reference(scene);
  REQUIRE(reference.outcome.complete);
  scene.solver.rtol = 1e-8;  // Newton's tolerance, far below the method's error
  scene.solver.atol = AbsoluteTolerance::uniform(1e-10);
  for (double rho : {1.0, 0.8, 0.3}) {
    const test::SimulationRun coarse(generalizedAlpha(scene, rho, 4e-4)), fine(generalizedAlpha(scene, rho, 2e-4));
    REQUIRE(coarse.outcome.complete);
    REQUIRE(fine.outcome.complete);
    CHECK(coarse.outcome.statistics.steps == 5000);
    const double e_coarse = tipDeviation(coarse, reference), e_fine = tipDeviation(fine, reference);
    INFO("ρ∞ = " << rho << ": tip error " << e_coarse << " m at h = 4e-4 s, " << e_fine << " m at 2e-4 s");
    CHECK(e_coarse / e_fine > 3.0);  // 4 for second order, 2 for first
    CHECK(e_fine < 1e-5);
    // GGL: position and velocity constraints hold at every step.
    CHECK(fine.outcome.statistics.max_step_constraint_residual < 1e-10);
  }
}

TEST_CASE("Generalized-α damps vibration the step does not resolve as its amplification says", "[dynamics][generalized_alpha]") {
  // A 0.1° swing (linear: ω = √(g (L/2) / (L²/3)) = 3.84 rad/s) integrated with ω h = 100: the
  // tip follows the method's own recurrence on θ'' = −ω² θ, whose amplification tends to −ρ∞
  // as ω h → ∞ (the swing alternates and shrinks, and not at all for ρ∞ = 1).
  const double omega = std::sqrt(9.81 * 0.5 / (1.0 / 3.0)), h = 100.0 / omega;
  for (double rho : {0.0, 0.5, 0.8, 1.0}) {
    Scene scene = generalizedAlpha(pendulum(0.1), rho, h);
    scene.solver.t_end = 8 * h;
    scene.solver.rtol = 1e-6;
    scene.solver.atol = AbsoluteTolerance::uniform(1e-6);
    scene.output.interval = h;  // samples at the steps
    const test::SimulationRun run(scene);
    REQUIRE(run.outcome.complete);
    const auto& tip = run.jointPositions("rod.tip");
    const std::vector<double> theta = oscillatorSteps(rho, 100.0, 8);
    INFO("ρ∞ = " << rho << ": after 8 steps θ/θ₀ = " << theta[8]);
    for (int n = 1; n <= 8; ++n) {
      INFO("step " << n << ": tip x_n / x_0 = " << tip[3 * n] / tip[0] << ", recurrence " << theta[n]);
      CHECK(tip[3 * n] / tip[0] == Approx(theta[n]).margin(2e-3));
    }
  }
}

TEST_CASE("Generalized-α with ρ∞ = 1 nearly keeps the pendulum's energy at coarse steps", "[dynamics][generalized_alpha]") {
  // 40 and 80 steps per period over 12 periods: BDF2 (ρ∞ = 0) visibly dissipates; at ρ∞ = 1 the
  // method itself keeps a linear oscillator's energy, and what remains is the projection of the
  // rates onto the motion at each step (generalized_alpha.cpp), third order in h (measured: 8×
  // less per halving of h).
  Scene scene = pendulum(30.0);
  scene.solver.t_end = 20.0;
  const double period = 2.0 * std::numbers::pi / std::sqrt(9.81 * 0.5 / (1.0 / 3.0));
  const auto energyLoss = [&](double rho, int steps_per_period) {
    const test::SimulationRun run(generalizedAlpha(scene, rho, period / steps_per_period));
    REQUIRE(run.outcome.complete);
    const auto& energy = run.recorder.energyBalance();  // T + V: no drives, no loads
    return energy.front() - energy.back();
  };
  const double swing = 1.0 * 9.81 * 0.5 * (1.0 - std::cos(30.0 * std::numbers::pi / 180.0));  // m g (L/2)(1 − cos θ₀)
  const double trapezoidal40 = energyLoss(1.0, 40), trapezoidal80 = energyLoss(1.0, 80), bdf2 = energyLoss(0.0, 40);
  INFO("energy lost over 20 s of " << swing << " J: ρ∞ = 1 " << trapezoidal40 << " J (40 steps per period), "
                                   << trapezoidal80 << " J (80); ρ∞ = 0 " << bdf2 << " J (40)");
  CHECK(std::abs(trapezoidal40) < 0.01 * swing);
  CHECK(std::abs(trapezoidal80) < std::abs(trapezoidal40) / 5.0);
  CHECK(bdf2 > 0.1 * swing);
}
