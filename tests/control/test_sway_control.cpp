// The anti-sway controller (control/): the sampled model against the continuous one, the
// Riccati solution against its closed form and its equation, the pendulum under the controller
// exactly as the design predicts, and the feedback on the flexible crane against open loop.

#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <memory>
#include <limits>
#include <numbers>

#include "cranesim/control/crane_sway.hpp"
#include "cranesim/control/low_pass.hpp"
#include "cranesim/control/lqr.hpp"
#include "cranesim/control/shaped_head_path.hpp"
#include "cranesim/control/sway_axis.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

/// ẋ = A x + B u over h with u held, by classical RK4 in `steps` steps.
Eigen::VectorXd heldRk4(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, Eigen::VectorXd x, const Eigen::VectorXd& u,
                        double h, int steps) {
  const double dt = h / steps;
  const auto f = [&](const Eigen::VectorXd& y) -> Eigen::VectorXd { return A * y + B * u; };
  for (int k = 0; k < steps; ++k) {
    const Eigen::VectorXd k1 = f(x), k2 = f(x + 0.5 * dt * k1), k3 = f(x + 0.5 * dt * k2), k4 = f(x + dt * k3);
    x += dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
  return x;
}

double spectralRadius(const Eigen::MatrixXd& M) { return M.eigenvalues().cwiseAbs().maxCoeff(); }

}  // namespace

TEST_CASE("The held model is the continuous model integrated over a sample", "[control]") {
  const PendulumAxisModel m = pendulumAxisModel(40.0, 9.81, 0.1);
  const DiscreteSystem d = zeroOrderHold(m.A, m.B, 0.02);
  const Eigen::VectorXd x0 = (Eigen::VectorXd(4) << 0.3, -0.2, 0.05, -0.01).finished();
  const Eigen::VectorXd u = Eigen::VectorXd::Constant(1, 0.7);
  const Eigen::VectorXd exact = heldRk4(m.A, m.B, x0, u, 0.02, 200);
  CHECK((d.A * x0 + d.B * u - exact).norm() < 1e-13);
}

TEST_CASE("A slewing lever's first step swings the shaped path's pendulum as a velocity step swings a pendulum",
          "[control]") {
  // The head 50 m from the slewing axis; the lever steps to 0.006 rad/s with no acceleration
  // limit, so the shaped head's speed steps by half of 0.3 m/s within one sample. A pendulum of
  // period T under a velocity step Δv swings across as θ = −(Δv ω/g) sin ωt until the second half
  // comes.
  const double period = 17.12, dt = 0.02, g = 9.81, omega = 2.0 * std::numbers::pi / period;
  const double infinite = std::numeric_limits<double>::infinity();
  ShapedHeadPath path(Eigen::Vector2d(-50.0, 0.0), period, {infinite, infinite}, dt, g);
  CHECK(path.delay() == Approx(8.56).margin(1e-12));
  double worst = 0.0;
  for (int k = 0; k < 400; ++k) {  // up to 8 s, before the second half at 8.56 s
    const ShapedHeadPath::Sample r = path.advance(0.006, 0.0, period);
    const double t = (k - 0.5) * dt;  // the velocity steps in the middle of the first sample
    if (k > 0) worst = std::max(worst, std::abs(r.across + 0.15 * omega / g * std::sin(omega * t)));
  }
  // The differences: the step spread over a sample, the head's centripetal acceleration (0.8 % of
  // the step's swing) and its turn off the first direction (0.024 rad by 8 s).
  CHECK(worst < 0.02 * 0.15 * omega / g);
}

TEST_CASE("A stop-and-go slew with a reversal, shaped in the plane, ends rest to rest with the pendulum still",
          "[control]") {
  // 3 °/s for 6 s, then −3 °/s from 14 to 18 s, within 2 °/s², on a head 5.35 m from the axis:
  // half a period later the crane has turned by 13°. The halves of each change cancel on the
  // pendulum in the plane exactly (T/2 is a whole number of samples), wherever the crane has
  // turned meanwhile.
  const double period = 17.12, dt = 0.02, degree = std::numbers::pi / 180.0;
  const double omega = 2.0 * std::numbers::pi / period;
  const auto lever = [&](double t) { return (t < 6.0 ? 3.0 : 14.0 <= t && t < 18.0 ? -3.0 : 0.0) * degree; };
  ShapedHeadPath path(Eigen::Vector2d(-5.35, 0.0), period, {2.0 * degree, 0.3}, dt);
  double largest = 0.0;
  ShapedHeadPath::Sample r;
  for (int k = 0; k <= 2000; ++k) {
    r = path.advance(lever(k * dt), 0.0, period);
    if (k * dt < 18.0 + path.delay() + 2.0)
      largest = std::max(largest, std::hypot(std::hypot(r.radial, r.across), std::hypot(r.radial_rate, r.across_rate) / omega));
  }
  CHECK(r.slewing == Approx((3.0 * 6.0 - 3.0 * 4.0) * degree).epsilon(1e-12));  // where the lever left it
  CHECK(r.radius == Approx(5.35).epsilon(1e-12));
  CHECK(std::abs(r.slewing_speed) < 1e-15);
  CHECK(std::abs(r.radius_speed) < 1e-12);
  // The swing while it moves (measured 0.0094 rad), and none left once it has stopped (measured
  // 1e-16 rad; shaping the slewing angle instead leaves 3 % of it here).
  CHECK(largest > 0.005);
  CHECK(std::hypot(std::hypot(r.radial, r.across), std::hypot(r.radial_rate, r.across_rate) / omega) < 1e-9 * largest);
}

TEST_CASE("The LQR gain of a scalar system is the closed form's", "[control]") {
  // x⁺ = a x + b u, cost q x² + r u²: b² p² + (r (1 − a²) − q b²) p − q r = 0, k = a b p / (r + b² p).
  const double a = 1.3, b = 0.4, q = 2.0, r = 0.5;
  const double c1 = r * (1 - a * a) - q * b * b;
  const double p = (-c1 + std::sqrt(c1 * c1 + 4 * b * b * q * r)) / (2 * b * b);
  const LqrDesign design = discreteLqr({Eigen::MatrixXd::Constant(1, 1, a), Eigen::MatrixXd::Constant(1, 1, b)},
                                       Eigen::MatrixXd::Constant(1, 1, q), Eigen::MatrixXd::Constant(1, 1, r));
  CHECK(design.P(0, 0) == Approx(p).epsilon(1e-13));
  CHECK(design.K(0, 0) == Approx(a * b * p / (r + b * b * p)).epsilon(1e-13));
  CHECK(std::abs(a - b * design.K(0, 0)) < 1.0);
}

TEST_CASE("The sway controller's gain solves the Riccati equation of the pendulum", "[control]") {
  SwayAxisController controller{SwayAxisSpec{}};
  controller.command(48.0, 0, 0, 0, 0, 0);
  const PendulumAxisModel m = pendulumAxisModel(48.0, 9.81, 0.1);
  const DiscreteSystem d = zeroOrderHold(m.A, m.B, 0.02);
  const SwayAxisSpec& s = controller.spec();
  const Eigen::Matrix4d Q = Eigen::Vector4d(1 / (s.position * s.position), 1 / (s.speed * s.speed), 1 / (s.angle * s.angle),
                                            1 / (s.angle_rate * s.angle_rate)).asDiagonal();
  const Eigen::MatrixXd R = Eigen::MatrixXd::Constant(1, 1, 1 / (s.command * s.command));
  const LqrDesign design = discreteLqr(d, Q, R);
  const Eigen::MatrixXd& P = design.P;
  const Eigen::MatrixXd residual =
      d.A.transpose() * P * d.A - d.A.transpose() * P * d.B * (R + d.B.transpose() * P * d.B).inverse() * d.B.transpose() * P * d.A + Q - P;
  CHECK(residual.norm() < 1e-9 * P.norm());
  CHECK((controller.gain() - design.K).norm() == 0.0);
  // The open pendulum does not decay (|λ| = 1); the closed loop does.
  CHECK(spectralRadius(d.A) == Approx(1.0).epsilon(1e-12));
  CHECK(spectralRadius(controller.closedLoop()) < 0.999);
}

TEST_CASE("The pendulum under the sampled controller moves as the design predicts", "[control]") {
  const double L = 30.0, h = 0.02;
  SwayAxisController controller{SwayAxisSpec{}};
  const PendulumAxisModel m = pendulumAxisModel(L, 9.81, 0.1);
  // A load swinging 0.5 m (θ = 1/60 rad) under a suspension point at rest at its reference.
  Eigen::VectorXd x = (Eigen::VectorXd(4) << 0.0, 0.0, 0.5 / L, 0.0).finished();
  Eigen::VectorXd predicted = x;
  double swing[6] = {};  // the largest swing in each 5 s
  for (int k = 0; k < 1500; ++k) {  // 30 s
    const double u = controller.command(L, x(0), x(1), 0.0, x(2), x(3));
    x = heldRk4(m.A, m.B, x, Eigen::VectorXd::Constant(1, u), h, 20);
    predicted = controller.closedLoop() * predicted;
    REQUIRE((x - predicted).norm() < 1e-9);
    swing[k / 250] = std::max(swing[k / 250], L * std::abs(x(2)));
  }
  INFO("closed-loop spectral radius " << controller.closedLoop().eigenvalues().cwiseAbs().maxCoeff());
  CHECK(swing[1] < 0.1);    // 0.5 m: below 10 cm after 5 s (0.085 m by the design's closed loop)
  CHECK(swing[2] < 0.02);   // below 2 cm after 10 s (0.015 m)
  CHECK(swing[5] < 0.001);  // and on (0.0005 m)
  CHECK(std::abs(x(0)) < 0.01);  // the suspension point is back at its reference
}

TEST_CASE("The sway controller redesigns its gain as the rope's length changes", "[control]") {
  SwayAxisController controller{SwayAxisSpec{}};
  controller.command(20.0, 0, 0, 0, 0, 0);
  const Eigen::RowVector4d short_rope = controller.gain();
  controller.command(20.05, 0, 0, 0, 0, 0);  // within 0.5 %: kept
  CHECK(controller.designLength() == 20.0);
  controller.command(40.0, 0, 0, 0, 0, 0);
  CHECK(controller.designLength() == 40.0);
  SwayAxisController fresh{SwayAxisSpec{}};
  fresh.command(40.0, 0, 0, 0, 0, 0);
  CHECK(controller.gain() == fresh.gain());
  CHECK(controller.gain() != short_rope);
  CHECK_THROWS_WITH(controller.command(-1.0, 0, 0, 0, 0, 0), Catch::Contains("length must be positive"));
  CHECK_THROWS_WITH(SwayAxisController(SwayAxisSpec{.sample_time = 0.0}), Catch::Contains("sample time"));
}

TEST_CASE("The steady angle leaves the feedback: a constant offset is tracked out at its time constant",
          "[control]") {
  // A load held off plumb at 0.01 rad (a steady wind) under a head at its reference: fed back as
  // it is, the angle asks for a constant speed −K_θ θ₀; with a steady-angle time τ the feedback
  // sees θ₀ e^(−t/τ), the first-order low-pass's part not yet taken out.
  const double tau = 20.0, dt = 0.02, offset = 0.01;
  SwayAxisController plain{SwayAxisSpec{}}, steady{SwayAxisSpec{.steady_angle_time = tau}};
  const double held = plain.command(48.0, 0.0, 0.0, 0.0, offset, 0.0);
  CHECK(held == Approx(-plain.gain()(2) * offset).epsilon(1e-14));
  CHECK(std::abs(held) > 0.3);  // m/s: the head would run downwind
  double u = 0.0;
  for (int k = 1; k <= 10000; ++k) {
    u = steady.command(48.0, 0.0, 0.0, 0.0, offset, 0.0);
    if (k == 1) CHECK(u == Approx(held * std::exp(-dt / tau)).epsilon(1e-12));
    if (k == 1000) CHECK(u == Approx(held * std::exp(-1000 * dt / tau)).epsilon(1e-9));  // after 20 s, e⁻¹ of it
  }
  CHECK(std::abs(u) < 1e-4 * std::abs(held));  // after 200 s
  CHECK_THROWS_WITH(SwayAxisController(SwayAxisSpec{.steady_angle_time = -1.0}), Catch::Contains("steady angle"));
}

TEST_CASE("The measurement filter is the sampled Butterworth filter: all of a constant, 1/√2 at its cutoff",
          "[control]") {
  // The bilinear map of a second-order Butterworth filter with its cutoff prewarped: |H(e^{iωh})|² =
  // 1 / (1 + (tan(ωh/2) / tan(ω_c h/2))⁴) at every frequency below the Nyquist frequency.
  const double h = 0.02, cutoff = 0.3;
  LowPassFilter filter(cutoff, h);
  const auto gain = [&](double f) {
    const std::complex<double> z1 = std::polar(1.0, -2.0 * std::numbers::pi * f * h);  // z⁻¹
    return std::abs((filter.b0 + filter.b1 * z1 + filter.b2 * z1 * z1) / (1.0 + filter.a1 * z1 + filter.a2 * z1 * z1));
  };
  for (const double f : {0.0, 0.06, 0.3, 0.76, 5.0, 20.0}) {
    const double ratio = std::tan(std::numbers::pi * f * h) / std::tan(std::numbers::pi * cutoff * h);
    CHECK(gain(f) == Approx(1.0 / std::sqrt(1.0 + std::pow(ratio, 4))).epsilon(1e-12));
  }
  CHECK(gain(cutoff) == Approx(1.0 / std::sqrt(2.0)).epsilon(1e-12));
  CHECK(gain(0.76) < 0.16);  // the thesis crane's sideways boom mode: less than a sixth of it passes
  // It starts at rest at its first sample and settles on a constant.
  CHECK(filter(0.25) == Approx(0.25).epsilon(1e-14));
  double y = 0.0;
  for (int k = 0; k < 2000; ++k) y = filter(1.0);
  CHECK(y == Approx(1.0).epsilon(1e-12));
  CHECK_THROWS_WITH(LowPassFilter(25.0, h), Catch::Contains("Nyquist frequency 25 Hz"));
}

TEST_CASE("On the flexible crane the anti-sway feedback damps the swing an operator's slew leaves, within "
          "the drives' limits", "[control][session]") {
  const std::string scene = std::string(CRANESIM_SOURCE_DIR) + "/configs/crane_inputs.yaml";
  // The lever slews at 3 °/s for 10 s; the swing over the 10 s from 30 s on, open loop and with the
  // feedback holding the head where it was at the lever's release.
  const auto swing = [&](bool feedback) {
    Session session(scene);
    const int hook = session.joint("load.origin"), head = session.joint("head.sheave"), slewing = session.input("slewing");
    std::unique_ptr<CraneSwayController> controller;
    double largest = 0.0, fastest = 0.0;
    for (int k = 1; k <= 2000; ++k) {
      const double t = session.time();
      if (t < 10.0) {
        session.setInput(slewing, 3.0);
      } else if (!feedback) {
        session.setInput(slewing, 0.0);
      } else {
        if (!controller) controller = std::make_unique<CraneSwayController>(session, CraneSwaySpec{});
        controller->apply(0.0, 0.0, 0.0);
      }
      REQUIRE(session.advanceTo(0.02 * k));
      for (std::size_t i = 0; i < session.model().inputs.size(); ++i)
        fastest = std::max(fastest, std::abs(session.inputRate(static_cast<int>(i))) /
                                        session.model().inputs[i].signal->spec().max_speed);
      if (session.time() > 30.0) largest = std::max(largest, (session.jointPosition(hook) - session.jointPosition(head)).head<2>().norm());
    }
    CHECK(fastest <= 1.0 + 1e-12);  // every drive within its speed limit all along
    return largest;
  };
  const double open = swing(false), closed = swing(true);
  INFO("swing from 30 to 40 s: open loop " << open << " m, with feedback " << closed << " m");
  CHECK(open > 0.5);
  CHECK(closed < 0.05 * open);  // 0.058 m against 2.01 m (0.15 m without the measurement filter)
}

TEST_CASE("The anti-sway feedback takes out most of the swing a gust leaves on the flexible crane",
          "[control][session]") {
  // 50 kN on the 390 t load, across the boom, rising and falling over 3 s (a gust); the swing from
  // 20 s to 40 s, open loop and with the feedback holding the boom head.
  const Scene scene = test::craneInputsWithGust();
  const auto swing = [&](bool feedback) {
    Session session(scene);
    const int hook = session.joint("load.origin"), head = session.joint("head.sheave");
    std::unique_ptr<CraneSwayController> controller;
    if (feedback) controller = std::make_unique<CraneSwayController>(session, CraneSwaySpec{});
    double largest = 0.0;
    for (int k = 1; k <= 2000; ++k) {
      if (controller) controller->apply(0.0, 0.0, 0.0);
      REQUIRE(session.advanceTo(0.02 * k));
      if (session.time() > 20.0) largest = std::max(largest, (session.jointPosition(hook) - session.jointPosition(head)).head<2>().norm());
    }
    return largest;
  };
  const double open = swing(false), closed = swing(true);
  INFO("swing from 20 to 40 s: open loop " << open << " m, with feedback " << closed << " m");
  CHECK(open > 0.3);
  CHECK(closed < 0.15 * open);  // 0.043 m against 0.394 m: 89 % less (0.073 m without the filter)
}

TEST_CASE("Shaped operator assistance stops an operator's stop-and-go slew with a reversal and a hoist within "
          "5 cm of plumb", "[control][session]") {
  // The lever slews at +3 °/s for 8 s, stops, slews back at −3 °/s from 16 to 22 s, while the hoist
  // lifts the load 2.4 m (0.3 m/s, 2–10 s). The head follows the lever's path shaped for the
  // crane's 17.1 s sway period, the hoist's speed is spread over the boom's 1.4 s period, and the
  // feedback acts on what the crane does differently; the crane stops half a period and the
  // lever's 1.5 s ramp after the lever, at 32.1 s.
  const std::string scene = std::string(CRANESIM_SOURCE_DIR) + "/configs/crane_inputs.yaml";
  const auto swing = [&](double boom_period) {
    Session session(scene);
    const int hook = session.joint("load.origin"), head = session.joint("head.sheave");
    CraneSwaySpec spec;
    spec.shaping_period = 17.1;
    spec.boom_period = boom_period;
    CraneSwayController controller(session, spec);
    double largest = 0.0;
    for (int k = 1; k <= 2100; ++k) {
      const double t = session.time();
      controller.apply(t < 8.0 ? 3.0 : 16.0 <= t && t < 22.0 ? -3.0 : 0.0, 0.0, 2.0 <= t && t < 10.0 ? -0.3 : 0.0);
      REQUIRE(session.advanceTo(0.02 * k));
      if (session.time() > 32.1 + 5.0)
        largest = std::max(largest, (session.jointPosition(hook) - session.jointPosition(head)).head<2>().norm());
    }
    return largest;
  };
  const double smoothed = swing(1.4), abrupt = swing(0.0);
  INFO("largest swing from 5 s after the crane's stop to 42 s: " << smoothed << " m, " << abrupt
                                                                   << " m with the hoist's speed as the lever gives it");
  CHECK(smoothed < 0.05);  // measured 0.017 m
  // 0.047 m: the hoist's 0.5 m/s² ramps set the boom bouncing at 0.7 Hz in its luffing plane: the head
  // moves against the load.
  CHECK(abrupt > smoothed + 0.01);
}
