// The sway sensor (control/sway_sensor.hpp): its delay against the signal it delays, its noise's
// statistics, the sampled pendulum under the LQR fed by it exactly as the delayed loop's linear
// model predicts, and the prediction over the delay against the pendulum's motion.

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "cranesim/control/lqr.hpp"
#include "cranesim/control/sway_axis.hpp"
#include "cranesim/control/sway_sensor.hpp"

using namespace cranesim;

namespace {

Session::Sway uniform(double value, double rate) { return {value, value, rate, rate}; }

}  // namespace

TEST_CASE("The sensor's delay gives a ramp's value that many seconds back, between samples too", "[control][sensor]") {
  const double h = 0.02;
  for (const double delay : {0.0, 0.02, 0.05, 0.13}) {
    SwaySensor sensor({.delay = delay}, h);
    for (int k = 0; k < 40; ++k) {
      const double t = k * h;
      const Session::Sway read = sensor.read({0.3 + 2.0 * t, -1.0 * t, 2.0, -1.0});
      const double back = std::max(t - delay, 0.0);  // before the first sample: the first sample
      INFO("delay " << delay << " s at t = " << t << " s");
      CHECK(read.radial == Approx(0.3 + 2.0 * back).margin(1e-14));
      CHECK(read.across == Approx(-1.0 * back).margin(1e-14));
      CHECK(read.radial_rate == 2.0);
      CHECK(read.across_rate == -1.0);
    }
  }
  CHECK_THROWS_WITH(SwaySensor({.delay = -0.1}, h), Catch::Contains("delay must be 0 or positive"));
  CHECK_THROWS_WITH(SwaySensor({.angle_noise = NAN}, h), Catch::Contains("angle noise"));
}

TEST_CASE("The sensor's noise is white with the standard deviations asked, the same for the same seed",
          "[control][sensor]") {
  const double sigma_angle = 2e-3, sigma_rate = 5e-3;
  SwaySensor sensor({.angle_noise = sigma_angle, .rate_noise = sigma_rate, .seed = 7}, 0.02);
  constexpr int n = 40000;
  std::vector<double> radial(n), across(n), rate(n);
  for (int k = 0; k < n; ++k) {
    const Session::Sway read = sensor.read(uniform(0.1, -0.2));
    radial[k] = read.radial - 0.1;
    across[k] = read.across - 0.1;
    rate[k] = read.radial_rate + 0.2;
  }
  const auto mean = [](const std::vector<double>& x, const std::vector<double>& y) {
    double s = 0.0;
    for (std::size_t k = 0; k < x.size(); ++k) s += x[k] * y[k];
    return s / static_cast<double>(x.size());
  };
  const auto average = [](const std::vector<double>& x) {
    double s = 0.0;
    for (const double v : x) s += v;
    return s / static_cast<double>(x.size());
  };
  // The sample standard deviation of n normal values scatters by σ/√(2n) = 0.35 % of σ; the mean by σ/√n.
  CHECK(std::sqrt(mean(radial, radial)) == Approx(sigma_angle).epsilon(0.02));
  CHECK(std::sqrt(mean(across, across)) == Approx(sigma_angle).epsilon(0.02));
  CHECK(std::sqrt(mean(rate, rate)) == Approx(sigma_rate).epsilon(0.02));
  CHECK(std::abs(average(radial)) < 5.0 * sigma_angle / std::sqrt(n));
  // Independent channels and samples: correlations scatter by 1/√n = 0.005.
  CHECK(std::abs(mean(radial, across)) / (sigma_angle * sigma_angle) < 0.03);
  const std::vector<double> next(radial.begin() + 1, radial.end()), now(radial.begin(), radial.end() - 1);
  CHECK(std::abs(mean(now, next)) / (sigma_angle * sigma_angle) < 0.03);

  SwaySensor same({.angle_noise = sigma_angle, .rate_noise = sigma_rate, .seed = 7}, 0.02),
      other({.angle_noise = sigma_angle, .rate_noise = sigma_rate, .seed = 8}, 0.02);
  const Session::Sway first = same.read(uniform(0.1, -0.2)), third = other.read(uniform(0.1, -0.2));
  CHECK(first.radial - 0.1 == radial[0]);
  CHECK(third.radial - 0.1 != radial[0]);
}

TEST_CASE("The pendulum under the LQR fed by a late sensor moves as the delayed loop's linear model predicts",
          "[control][sensor]") {
  // The design model (sway_axis.hpp) sampled with u held; the controller reads position and speed
  // at once (encoders) and the angle and its rate 2.5 samples late. The loop is then linear in
  // [x_k, x_{k−1}, x_{k−2}, x_{k−3}]: the reading is ½ x_{k−2} + ½ x_{k−3} in its angle rows.
  const double L = 30.0, h = 0.02, delay = 0.05;
  SwayAxisController controller{SwayAxisSpec{}};
  SwaySensor sensor({.delay = delay}, h);
  controller.command(L, 0, 0, 0, 0, 0);
  const Eigen::RowVector4d K = controller.gain();
  const Eigen::Matrix4d closed_free = controller.closedLoop();
  const PendulumAxisModel m = pendulumAxisModel(L, 9.81, 0.1);
  const DiscreteSystem d = zeroOrderHold(m.A, m.B, h);
  Eigen::MatrixXd loop = Eigen::MatrixXd::Zero(16, 16);
  const Eigen::Matrix4d encoders = Eigen::Vector4d(1, 1, 0, 0).asDiagonal(), angles = Eigen::Vector4d(0, 0, 1, 1).asDiagonal();
  loop.block<4, 4>(0, 0) = d.A - d.B * K * encoders;
  loop.block<4, 4>(0, 8) = -0.5 * d.B * K * angles;
  loop.block<4, 4>(0, 12) = -0.5 * d.B * K * angles;
  loop.block<12, 12>(4, 0).setIdentity();

  Eigen::Vector4d x(0.0, 0.0, 0.5 / L, 0.0);
  Eigen::VectorXd predicted(16);
  predicted << x, x, x, x;  // the sensor holds its first reading back in time
  SwayAxisController fresh{SwayAxisSpec{}};
  for (int k = 0; k < 1500; ++k) {
    const Session::Sway read = sensor.read({x(2), 0.0, x(3), 0.0});
    const double u = fresh.command(L, x(0), x(1), 0.0, read.radial, read.radial_rate);
    x = d.A * x + d.B * Eigen::Matrix<double, 1, 1>(u);
    predicted = loop * predicted;
    REQUIRE((x - predicted.head<4>()).norm() < 1e-12);
  }
  const double radius = loop.eigenvalues().cwiseAbs().maxCoeff();
  INFO("spectral radius per sample: delayed " << radius << ", at once " << closed_free.eigenvalues().cwiseAbs().maxCoeff());
  CHECK(radius < 1.0);
  CHECK(std::abs(x(2)) * L < 1e-3);  // the 0.5 m swing is gone after 30 s
}

TEST_CASE("The prediction over the sensor's delay is the pendulum's motion to second order in the delay",
          "[control][sensor]") {
  // θ = −a/g + A cos ωt + B sin ωt solves θ̈ = −ω² θ − a/L under a head accelerating at a along the
  // axis (radial) and at −a across; the prediction from the reading d late against the truth now.
  const double g = 9.81, L = 40.0, w = std::sqrt(g / L), a = 0.15, A = 0.02, B = -0.01, t = 3.0;
  const auto truth = [&](double time, double accel) {
    return std::array<double, 2>{-accel / g + A * std::cos(w * time) + B * std::sin(w * time),
                                 w * (-A * std::sin(w * time) + B * std::cos(w * time))};
  };
  const auto error = [&](double d) {
    const auto [r0, rr0] = truth(t - d, a);
    const auto [c0, cr0] = truth(t - d, -a);
    const Session::Sway now = predictOverDelay({r0, c0, rr0, cr0}, d, g, L, Eigen::Vector2d(a * d, -a * d));
    const auto [r, rr] = truth(t, a);
    const auto [c, cr] = truth(t, -a);
    return std::max({std::abs(now.radial - r), std::abs(now.across - c), std::abs(now.radial_rate - rr) / w,
                     std::abs(now.across_rate - cr) / w});
  };
  const double coarse = error(0.2), fine = error(0.1);
  INFO("errors " << coarse << " at 0.2 s, " << fine << " at 0.1 s, of a swing of " << std::hypot(A, B) + a / g);
  CHECK(fine < 1e-3 * (std::hypot(A, B) + a / g));
  CHECK(coarse / fine == Approx(4.0).epsilon(0.1));  // second order
  // Without the head's change of speed the rate would be a·d/L off: first order.
  CHECK(a * 0.1 / L / w > 20.0 * fine);
}
