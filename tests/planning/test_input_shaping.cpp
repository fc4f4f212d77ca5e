// Input shaping of a planned path (planning/input_shaping.hpp): the shaped path's samples
// against the convolution in closed form, and the residual sway it leaves on an undamped
// pendulum against the shaper's analytic residual (Singer & Seering 1990).

#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <numbers>

#include "cranesim/planning/input_shaping.hpp"

using namespace cranesim;

namespace {

constexpr double kAccel = 0.2, kHalf = 2.0, kStep = 0.01;  // bang-bang: +a for 2 s, −a for 2 s

/// x of the rest-to-rest bang-bang move (z moves half as far in the test paths), held outside [0, 4].
double position(double t) {
  if (t <= 0.0) return 0.0;
  if (t <= kHalf) return 0.5 * kAccel * t * t;
  if (t <= 2.0 * kHalf) return kAccel * kHalf * kHalf - 0.5 * kAccel * (2.0 * kHalf - t) * (2.0 * kHalf - t);
  return kAccel * kHalf * kHalf;
}

QrTrajectory bangBang() {
  QrTrajectory tr;
  const int steps = static_cast<int>(std::lround(2.0 * kHalf / kStep));
  for (int k = 0; k <= steps; ++k) {
    const double t = k * kStep;
    const double v = t <= kHalf ? kAccel * t : kAccel * (2.0 * kHalf - t);
    tr.t.push_back(t);
    tr.states.push_back(EndState(position(t), 0.5 * position(t), v, 0.5 * v));
    if (k < steps) {
      const double a = t < kHalf ? kAccel : -kAccel;
      tr.controls.push_back(EndControl(a, 0.5 * a));
    }
  }
  return tr;
}

/// Amplitude of the sway y'' + ω² y = −a(t) left after a path with piecewise-constant
/// accelerations (its controls) ends, starting from rest: |∫ a e^{iωt} dt| / ω.
double residualSway(const QrTrajectory& path, double omega) {
  std::complex<double> integral = 0.0;
  const std::complex<double> i(0.0, 1.0);
  for (std::size_t k = 0; k < path.controls.size(); ++k)
    integral += path.controls[k](0) * (std::exp(i * omega * path.t[k + 1]) - std::exp(i * omega * path.t[k])) / (i * omega);
  return std::abs(integral) / omega;
}

}  // namespace

TEST_CASE("ZV and ZVD shapers: impulses and their analytic residual", "[planning][shaping]") {
  const InputShaper zv = makeShaper(ShaperKind::ZV, 6.0), zvd = makeShaper(ShaperKind::ZVD, 6.0);
  CHECK(zv.times == std::vector<double>{0.0, 3.0});
  CHECK(zv.amplitudes == std::vector<double>{0.5, 0.5});
  CHECK(zvd.times == std::vector<double>{0.0, 3.0, 6.0});
  CHECK(zvd.amplitudes == std::vector<double>{0.25, 0.5, 0.25});
  CHECK(zvd.duration() == 6.0);
  CHECK_THROWS_AS(makeShaper(ShaperKind::ZV, 0.0), std::invalid_argument);
}

TEST_CASE("A shaped path is the convolution of the QR path, sampled exactly", "[planning][shaping]") {
  const QrTrajectory path = bangBang();
  const double period = 3.0037;  // T/2 between samples: the copies' corners fall inside steps
  const InputShaper zvd = makeShaper(ShaperKind::ZVD, period);
  const QrTrajectory shaped = shapeTrajectory(path, zvd);
  REQUIRE(shaped.t.size() == path.t.size() + static_cast<std::size_t>(std::ceil(period / kStep)));
  REQUIRE(shaped.controls.size() + 1 == shaped.t.size());
  for (std::size_t j = 0; j < shaped.t.size(); ++j) {
    const double t = shaped.t[j];
    CHECK(shaped.t[j] == Approx(j * kStep).margin(1e-12));
    const double x = 0.25 * position(t) + 0.5 * position(t - 0.5 * period) + 0.25 * position(t - period);
    CHECK(shaped.states[j](0) == Approx(x).margin(1e-12));
    CHECK(shaped.states[j](1) == Approx(0.5 * x).margin(1e-12));
  }
  CHECK(shaped.states.front() == path.states.front());
  CHECK(shaped.states.back()(0) == Approx(path.states.back()(0)).margin(1e-12));
  CHECK(shaped.states.back().tail<2>().norm() < 1e-12);  // at rest at the end
}

TEST_CASE("Shaped paths leave an undamped pendulum still at the design period, and as the "
          "analytic residual off it", "[planning][shaping]") {
  const QrTrajectory path = bangBang();
  const double period = 3.0037, design = 2.0 * std::numbers::pi / period;
  const double unshaped = residualSway(path, design);
  REQUIRE(unshaped > 0.05);  // the 4 s bang-bang move leaves the 3 s pendulum swinging
  for (ShaperKind kind : {ShaperKind::ZV, ShaperKind::ZVD}) {
    const QrTrajectory shaped = shapeTrajectory(path, makeShaper(kind, period));
    INFO((kind == ShaperKind::ZV ? "ZV" : "ZVD"));
    CHECK(residualSway(shaped, design) < 1e-4 * unshaped);
    // A pendulum 10 % slower or faster than designed for: residual |cos(πr/2)| (ZV), cos²(πr/2) (ZVD).
    for (double r : {1.0 / 1.1, 1.1}) {
      const double omega = r * design, ratio = residualSway(shaped, omega) / residualSway(path, omega);
      const double c = std::cos(0.5 * std::numbers::pi * r);
      CHECK(ratio == Approx(kind == ShaperKind::ZV ? std::abs(c) : c * c).margin(1e-4));
    }
  }
}
