// Smooth drives from discrete control trajectories (6.4): resampled, padded with steady
// state and interpolated by a cubic spline that starts and ends at rest.

#include <catch2/catch.hpp>

#include <cmath>

#include "cranesim/planning/control_trajectory.hpp"

using namespace cranesim;

namespace {

/// An unequally spaced, dense trajectory sample of y(t) over [2, 12].
std::pair<std::vector<double>, std::vector<double>> samples(double (*y)(double)) {
  std::vector<double> t, values;
  const int intervals = 500;
  for (int k = 0; k <= intervals; ++k) {
    const double s = static_cast<double>(k) / intervals;
    t.push_back(2 + 10 * s * s);
    values.push_back(y(t.back()));
  }
  return {t, values};
}

double linear(double t) { return 1.5 - 0.25 * t; }
double smoothStep(double t) { return 40 + 20 * std::tanh(t - 7); }

}  // namespace

TEST_CASE("Linear controls: knots, steady pads, resampled values and zero end slopes", "[planning][controls]") {
  const auto [t, y] = samples(linear);
  const int points = 41, steady = 5;
  const TableProfile table = smoothControlTrajectory(t, y, points, steady);
  REQUIRE(table.t.size() == points + 2 * steady);
  REQUIRE(table.y.size() == table.t.size());
  REQUIRE(table.slopes.size() == table.t.size());
  CHECK(table.slopes.front() == 0.0);
  CHECK(table.slopes.back() == 0.0);

  const double spacing = 10.0 / (points - 1);
  for (std::size_t k = 0; k < table.t.size(); ++k) {
    INFO("knot " << k);
    CHECK(table.t[k] == k * spacing);  // on the simulation's axis: the first steady knot at 0
    if (k > 0) CHECK(table.t[k] > table.t[k - 1]);
  }
  for (int k = 0; k < steady; ++k) {
    CHECK(table.y[k] == y.front());
    CHECK(table.y[steady + points + k] == y.back());
  }

  const Profile profile(table);
  const double lead = steady * spacing - 2;  // simulation time − trajectory time
  for (int m = 0; m < points; ++m) CHECK(profile(table.t[steady + m]) == Approx(linear(2 + m * spacing)).margin(1e-12));
  CHECK(profile(table.t.front() - 3.0) == y.front());
  CHECK(profile(table.t.back() + 3.0) == y.back());

  const double h = 1e-6;
  CHECK(std::abs(profile(table.t.front() + h) - profile(table.t.front())) / h < 1e-4);
  CHECK(std::abs(profile(table.t.back()) - profile(table.t.back() - h)) / h < 1e-4);
  // Inside, the spline follows the ramp (slope −0.25) well away from the pads.
  CHECK((profile(7.0 + lead + h) - profile(7.0 + lead - h)) / (2 * h) == Approx(-0.25).epsilon(1e-3));
}

TEST_CASE("A smooth control is followed between knots and starts and stops at rest", "[planning][controls]") {
  const auto [t, y] = samples(smoothStep);
  const TableProfile table = smoothControlTrajectory(t, y, 101, 10);
  const Profile profile(table);
  const double lead = table.t[10] - 2;  // simulation time − trajectory time
  for (double time = 3.05; time < 11.9; time += 0.1) {
    INFO("t = " << time);
    // Linear interpolation of the samples (spacing ≤ 0.04, |y''| ≤ 15.4) limits the agreement
    // to 0.04² / 8 · 15.4 = 3.1e-3.
    CHECK(profile(time + lead) == Approx(smoothStep(time)).margin(3.5e-3));
  }
  const double h = 1e-6;
  CHECK(std::abs(profile(table.t.front() + h) - profile(table.t.front())) / h < 1e-3);
  CHECK(std::abs(profile(table.t.back()) - profile(table.t.back() - h)) / h < 1e-3);
  CHECK(profile(0.0) == y.front());
  CHECK(profile(20.0) == y.back());

  const TableProfile unpadded = smoothControlTrajectory(t, y, 2, 0);
  CHECK(unpadded.t == std::vector<double>{0.0, 10.0});
  CHECK(unpadded.y == std::vector<double>{y.front(), y.back()});
  CHECK(unpadded.slopes == std::vector<double>{0.0, 0.0});
}

TEST_CASE("Control trajectory validation", "[planning][controls]") {
  const std::vector<double> t{0, 1, 2}, y{0, 1, 4};
  CHECK_NOTHROW(smoothControlTrajectory(t, y, 2, 0));
  CHECK_THROWS_AS(smoothControlTrajectory(t, y, 1, 3), std::invalid_argument);
  CHECK_THROWS_AS(smoothControlTrajectory(t, y, 10, -1), std::invalid_argument);
  CHECK_THROWS_AS(smoothControlTrajectory(t, {0, 1}, 10, 3), std::invalid_argument);
  CHECK_THROWS_AS(smoothControlTrajectory({0}, {0}, 10, 3), std::invalid_argument);
  CHECK_THROWS_AS(smoothControlTrajectory({0, 1, 1}, y, 10, 3), std::invalid_argument);
  CHECK_THROWS_AS(smoothControlTrajectory({0, 2, 1}, y, 10, 3), std::invalid_argument);
}

TEST_CASE("A control spline's peak rate, acceleration and jerk, against its samples", "[planning][controls]") {
  const auto [t, y] = samples(smoothStep);
  const TableProfile spline = smoothControlTrajectory(t, y, 20, 5);
  const RatePeaks peaks = ratePeaks(spline);
  // Dense central differences of the spline itself (the drive the crane follows): h = 1e-4 s
  // errs by ~h² y⁽⁵⁾ in the rate; the jerk is piecewise constant, sampled inside its pieces.
  const Profile drive{spline};
  double speed = 0.0, acceleration = 0.0, jerk = 0.0;
  constexpr double h = 1e-4;
  for (double s = spline.t.front() + 2 * h; s < spline.t.back() - 2 * h; s += 1e-3) {
    const double y0 = drive(s), yp = drive(s + h), ym = drive(s - h), ypp = drive(s + 2 * h), ymm = drive(s - 2 * h);
    speed = std::max(speed, std::abs(yp - ym) / (2 * h));
    acceleration = std::max(acceleration, std::abs(yp - 2 * y0 + ym) / (h * h));
    jerk = std::max(jerk, std::abs(ypp - 2 * yp + 2 * ym - ymm) / (2 * h * h * h));
  }
  INFO("peaks " << peaks.speed << ", " << peaks.acceleration << ", " << peaks.jerk << " against " << speed << ", "
                << acceleration << ", " << jerk);
  CHECK(peaks.speed == Approx(speed).epsilon(1e-6));
  CHECK(peaks.acceleration == Approx(acceleration).epsilon(2e-4));  // measured 6e-5
  CHECK(peaks.jerk == Approx(jerk).epsilon(1e-3));  // measured 1e-4
  CHECK(ratePeaks(smoothControlTrajectory(t, std::vector<double>(t.size(), 3.0), 20, 5)).speed == 0.0);
}
