// The drive dynamics of an input (math/input_signal.hpp) against the lag chain integrated
// numerically, its continuity across commands and its limits.

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <limits>

#include "cranesim/math/input_signal.hpp"
#include "cranesim/math/profile.hpp"

using namespace cranesim;

namespace {

/// The chain x, z₁ … z_order integrated by classical Runge–Kutta with step h under command u.
struct ChainReference {
  InputSpec spec;
  double x;
  std::array<double, 2> z;

  void advance(double u, double duration, double h) {
    const int steps = static_cast<int>(std::lround(duration / h));
    for (int k = 0; k < steps; ++k) {
      const auto rate = [&](const std::array<double, 3>& s) {  // s = [x, z₁, z₂]
        std::array<double, 3> d{};
        const double tau = spec.time_constant;
        d[1] = (u - s[1]) / tau;
        d[2] = spec.order == 2 ? (s[1] - s[2]) / tau : 0.0;
        const double last = s[spec.order];
        d[0] = spec.command == InputCommand::Speed ? last : 0.0;
        return d;
      };
      std::array<double, 3> s{x, z[0], z[1]}, k1 = rate(s), s2, s3, s4;
      for (int i = 0; i < 3; ++i) s2[i] = s[i] + 0.5 * h * k1[i];
      const auto k2 = rate(s2);
      for (int i = 0; i < 3; ++i) s3[i] = s[i] + 0.5 * h * k2[i];
      const auto k3 = rate(s3);
      for (int i = 0; i < 3; ++i) s4[i] = s[i] + h * k3[i];
      const auto k4 = rate(s4);
      for (int i = 0; i < 3; ++i) s[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
      x = s[0], z = {s[1], s[2]};
      if (spec.command == InputCommand::Value) x = z[spec.order - 1];
    }
  }
};

/// A feedback-like command sequence: changes every 20 ms, both signs.
double commandAt(int k) { return 0.3 * std::sin(0.37 * k) + 0.1 * std::cos(1.3 * k); }

}  // namespace

TEST_CASE("An input follows its command through the lag chain in closed form", "[input]") {
  for (const InputCommand command : {InputCommand::Speed, InputCommand::Value}) {
    for (const int order : {1, 2}) {
      INFO("command " << (command == InputCommand::Speed ? "speed" : "value") << ", order " << order);
      InputSpec spec;
      spec.command = command;
      spec.order = order;
      spec.time_constant = 0.05;
      spec.value = 7.0;
      InputSignal signal(spec, 2.0);
      ChainReference reference{spec, 7.0, {command == InputCommand::Speed ? 0.0 : 7.0, command == InputCommand::Speed ? 0.0 : 7.0}};
      const double dt = 0.02;
      for (int k = 0; k < 100; ++k) {
        const double t = 2.0 + k * dt;
        const double u = command == InputCommand::Speed ? commandAt(k) : 7.0 + commandAt(k);
        signal.command(t, u);
        reference.advance(u, dt, 1e-5);
        const std::array<double, 4> d = signal.derivatives(t + dt);
        REQUIRE(d[0] == Approx(reference.x).margin(1e-11));
      }
    }
  }
}

TEST_CASE("An input's derivatives are those of its value, and the ones a command keeps stay continuous",
          "[input]") {
  for (const InputCommand command : {InputCommand::Speed, InputCommand::Value}) {
    for (const int order : {1, 2}) {
      for (const bool ramp : {false, true}) {
        INFO("command " << (command == InputCommand::Speed ? "speed" : "value") << ", order " << order
                        << (ramp ? ", with a ramp" : ""));
        InputSpec spec{command, 3.0, order, 0.1};
        if (ramp) (command == InputCommand::Speed ? spec.max_acceleration : spec.max_speed) = 1.5;
        InputSignal signal(spec, 0.0);
        for (int k = 0; k < 10; ++k) {
          const double t = 0.02 * k;
          const std::array<double, 4> left = signal.derivatives(t, true);
          signal.command(t, command == InputCommand::Speed ? commandAt(k) : 3.0 + commandAt(k));
          const std::array<double, 4> right = signal.derivatives(t);
          // The command sets where the chain's input heads: the value and the derivatives below
          // the first one it reaches are continuous (a speed command's one more, its integral;
          // a ramp's one more, as the reference itself is continuous).
          const int continuous = order + (command == InputCommand::Speed ? 1 : 0) + (ramp ? 1 : 0);
          for (int m = 0; m < std::min(continuous, 4); ++m) CHECK(right[m] == Approx(left[m]).margin(1e-13));
          // Central differences of each derivative give the next one inside the interval (away
          // from the ramp's end, where the highest one jumps).
          const double tm = t + 0.01, h = 1e-6;
          const auto ahead = signal.derivatives(tm + h), behind = signal.derivatives(tm - h), here = signal.derivatives(tm);
          for (int m = 0; m < 3; ++m)
            CHECK((ahead[m] - behind[m]) / (2.0 * h) == Approx(here[m + 1]).epsilon(1e-6).margin(1e-6));
        }
      }
    }
  }
}

TEST_CASE("An input profile carries the signal's derivatives to the automatic differentiation", "[input]") {
  InputProfile input;
  input.spec = {InputCommand::Speed, 10.0, 2, 0.2};
  input.signal = std::make_shared<InputSignal>(input.spec, 0.0);
  input.signal->command(0.0, 0.5);
  const Profile profile(input, 2.0);
  const double t = 0.3;
  const std::array<double, 4> d = input.signal->derivatives(t);
  using D1 = Dual<double, 1>;
  using D2 = Dual<D1, 1>;
  const D2 tt(D1(t, D1::Derivatives::Constant(1.0)), D2::Derivatives::Constant(D1(1.0)));
  const D2 y = profile(tt);
  CHECK(y.value().value() == Approx(2.0 * d[0]).epsilon(1e-15));
  CHECK(y.value().derivatives()(0) == Approx(2.0 * d[1]).epsilon(1e-15));
  CHECK(y.derivatives()(0).derivatives()(0) == Approx(2.0 * d[2]).epsilon(1e-15));
  // A scene's input profile, before a model gives it its signal, reads as its value at rest.
  InputProfile unattached;
  unattached.spec.value = 4.5;
  CHECK(Profile(unattached)(1.0) == 4.5);
}

TEST_CASE("An input's limits hold while it follows its commands", "[input]") {
  SECTION("speed and acceleration of a speed command: a ramp, then the lags") {
    for (const int order : {1, 2}) {
      INFO("order " << order);
      InputSpec spec{InputCommand::Speed, 0.0, order, 0.1};
      spec.max_speed = 0.5;
      spec.max_acceleration = 0.4;
      InputSignal signal(spec, 0.0);
      double peak_speed = 0.0, peak_acceleration = 0.0, t = 0.0;
      for (int k = 0; k < 400; ++k, t += 0.02) {
        const double wanted = k < 200 ? 2.0 : -2.0;  // beyond the speed limit both ways
        CHECK(signal.command(t, wanted) == (k < 200 ? 0.5 : -0.5));
        for (int i = 0; i < 20; ++i) {
          const auto d = signal.derivatives(t + 0.001 * (i + 1));
          peak_speed = std::max(peak_speed, std::abs(d[1]));
          peak_acceleration = std::max(peak_acceleration, std::abs(d[2]));
        }
      }
      CHECK(peak_speed <= 0.5 + 1e-12);
      CHECK(peak_speed > 0.49);
      CHECK(peak_acceleration <= 0.4 + 1e-12);
      CHECK(peak_acceleration > 0.39);  // the ramp runs at its limit for 1.25 s: the lags catch up
    }
  }
  SECTION("a ramp and one lag in closed form") {
    // From rest, speed command 1 at 2 /s², τ = 0.05 s: for t ≤ 0.5 s the reference is 2t and the
    // speed v = 2(t − τ + τ e^{−t/τ}); then the reference holds at 1.
    InputSpec spec{InputCommand::Speed, 0.0, 1, 0.05};
    spec.max_acceleration = 2.0;
    InputSignal signal(spec, 0.0);
    signal.command(0.0, 1.0);
    const double tau = 0.05;
    for (const double t : {0.1, 0.3, 0.5}) {
      const auto d = signal.derivatives(t);
      CHECK(d[1] == Approx(2.0 * (t - tau + tau * std::exp(-t / tau))).epsilon(1e-13));
      CHECK(d[0] == Approx(t * t - 2.0 * tau * t + 2.0 * tau * tau * (1.0 - std::exp(-t / tau))).epsilon(1e-12));
      CHECK(d[2] == Approx(2.0 * (1.0 - std::exp(-t / tau))).epsilon(1e-12));
    }
    const double v_half = 2.0 * (0.5 - tau + tau * std::exp(-0.5 / tau));
    const double x_half = 0.25 - tau + 2.0 * tau * tau * (1.0 - std::exp(-0.5 / tau));
    const double t = 0.8, decay = std::exp(-(t - 0.5) / tau);
    const auto d = signal.derivatives(t);
    CHECK(d[1] == Approx(1.0 + (v_half - 1.0) * decay).epsilon(1e-13));
    CHECK(d[0] == Approx(x_half + (t - 0.5) + (v_half - 1.0) * tau * (1.0 - decay)).epsilon(1e-12));
  }
  SECTION("a speed command stops at a value limit (a limit switch)") {
    InputSpec spec{InputCommand::Speed, 5.0, 1, 0.05};
    spec.min = 4.9;
    InputSignal signal(spec, 0.0);
    double t = 0.0;
    for (int k = 0; k < 100; ++k, t += 0.02) signal.command(t, -0.2);
    const auto d = signal.derivatives(t);
    CHECK(d[0] < 4.9);
    CHECK(d[0] > 4.9 - 0.2 * 0.02 - 0.2 * 0.05 - 1e-12);  // past it by at most a sample and the lag
    CHECK(std::abs(d[1]) < 1e-6);
    CHECK(signal.command(t, 0.3) == 0.3);  // away from the limit again
  }
  SECTION("the range and the speed of a value command") {
    InputSpec spec{InputCommand::Value, 0.0, 2, 0.2};
    spec.min = -1.0;
    spec.max = 1.0;
    spec.max_speed = 0.3;
    InputSignal signal(spec, 0.0);
    CHECK(signal.command(0.0, 5.0) == 1.0);
    double peak_speed = 0.0;
    for (int k = 0; k < 1000; ++k) peak_speed = std::max(peak_speed, std::abs(signal.derivatives(0.01 * k)[1]));
    CHECK(peak_speed <= 0.3 + 1e-12);
    CHECK(peak_speed > 0.29);
    CHECK(signal.derivatives(20.0)[0] == Approx(1.0).margin(1e-9));
  }
  SECTION("a command that is not a number is refused, and time does not run back") {
    InputSignal signal(InputSpec{}, 1.0);
    CHECK_THROWS_WITH(signal.command(1.0, std::numeric_limits<double>::quiet_NaN()), Catch::Contains("not a finite number"));
    CHECK_THROWS_WITH(signal.command(1.0, std::numeric_limits<double>::infinity()), Catch::Contains("not a finite number"));
    signal.command(2.0, 0.1);
    CHECK_THROWS_WITH(signal.command(1.5, 0.1), Catch::Contains("comes before"));
  }
  SECTION("a restored signal goes on as the saved one") {
    InputSpec spec{InputCommand::Speed, 2.0, 2, 0.1};
    spec.max_acceleration = 0.3;
    InputSignal signal(spec, 0.0);
    signal.command(0.0, 0.4);
    signal.command(0.5, -0.2);
    const InputState saved = signal.state();
    InputSignal other(spec, 0.0);
    other.restore(saved);
    for (const double t : {0.5, 0.7, 1.9, 3.0}) CHECK(other.derivatives(t) == signal.derivatives(t));
  }
}
