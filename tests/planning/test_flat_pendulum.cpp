// Flatness of a load on a rope from a rigid luffing boom's tip (planning/flat_pendulum.hpp):
// the static case in closed form, and the load of a pendulum whose tip and rope follow the flat
// controls, integrated tightly, against the path; the same through the pendulum's static map at
// the resting point, as crane-opt's method flatness drives the crane.

#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <numbers>

#include "cranesim/planning/flat_pendulum.hpp"
#include "cranesim/planning/rest_to_rest_path.hpp"

using namespace cranesim;

namespace {

const LuffingPendulum kJib{Eigen::Vector2d(0.0, 0.0), 20.0, 9.81};  // the luffing jib's boom (luffing_jib.yaml)
const Eigen::Vector2d kStart(-10.0, 7.320508), kTarget(-14.0, 10.0);  // target_luffing_jib.yaml's move
constexpr double kMotion = 8.0;                                       // s: 4.7 m in 8 s, brisk for a 10 m rope

const RestToRestPath kPath(kStart, kTarget, kMotion, kMotion / 2);  // no cruise: ramps of half the motion

Eigen::Vector2d loadPath(double t, int derivative) { return kPath.derivative(t, derivative); }

using Suspension = std::function<PendulumControls(double)>;

struct Swing {
  double max_path_error = 0.0;     // ‖load − planned‖ while moving, m
  double residual_sway = 0.0;      // max |x − x_target| over 10 s after arrival, m
};

/// A point load on a rope of length ℓ(t) from a tip moving as s(t), released hanging at rest:
/// φ̈ = (−g sin φ − s̈·(cos φ, sin φ) − 2 ℓ̇ φ̇) / ℓ, load = s + ℓ (sin φ, −cos φ); RK4 at 1 ms,
/// s̈ and ℓ̇ by central differences of the suspension (h = 1 ms: error ~1e-7 of their scale).
Swing swing(const Suspension& suspension) {
  constexpr double dt = 1e-3, h = 1e-3;
  const auto rates = [&](double t, const Eigen::Vector2d& y) {
    const PendulumControls before = suspension(t - h), now = suspension(t), after = suspension(t + h);
    const Eigen::Vector2d tip_acceleration = (after.tip - 2.0 * now.tip + before.tip) / (h * h);
    const double rope_rate = (after.rope_length - before.rope_length) / (2.0 * h);
    const double phi = y(0), omega = y(1);
    const double tangential = tip_acceleration.x() * std::cos(phi) + tip_acceleration.y() * std::sin(phi);
    return Eigen::Vector2d(omega, (-kJib.gravity * std::sin(phi) - tangential - 2.0 * rope_rate * omega) / now.rope_length);
  };
  Swing result;
  Eigen::Vector2d y = Eigen::Vector2d::Zero();
  const int steps = static_cast<int>(std::lround((kMotion + 10.0) / dt));
  for (int k = 0; k < steps; ++k) {
    const double t = k * dt;
    const Eigen::Vector2d k1 = rates(t, y), k2 = rates(t + dt / 2, y + dt / 2 * k1), k3 = rates(t + dt / 2, y + dt / 2 * k2),
                          k4 = rates(t + dt, y + dt * k3);
    y += dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    const double time = t + dt;
    const PendulumControls c = suspension(time);
    const Eigen::Vector2d load = c.tip + c.rope_length * Eigen::Vector2d(std::sin(y(0)), -std::cos(y(0)));
    if (time <= kMotion) result.max_path_error = std::max(result.max_path_error, (load - loadPath(time, 0)).norm());
    else result.residual_sway = std::max(result.residual_sway, std::abs(load.x() - kTarget.x()));
  }
  return result;
}

}  // namespace

TEST_CASE("Flat pendulum at rest: the rope plumb, the tip on the boom's circle", "[planning][flatness]") {
  const PendulumControls c = flatPendulumControls(kJib, kStart, Eigen::Vector2d::Zero());
  CHECK(c.rope_length == Approx(10.0).epsilon(1e-7));
  CHECK(c.tip.x() == Approx(-10.0).epsilon(1e-12));
  CHECK(c.tip.y() == Approx(20.0 * std::sin(std::numbers::pi / 3)).epsilon(1e-7));
  CHECK(c.boom_angle == Approx(std::numbers::pi / 3).epsilon(1e-7));
  // Accelerating outwards (−x) tilts the rope: the tip leads the load by ℓ a / g horizontally.
  const PendulumControls leaning = flatPendulumControls(kJib, kStart, Eigen::Vector2d(-0.5, 0.0));
  CHECK((leaning.tip.x() - kStart.x()) / (leaning.tip.y() - kStart.y()) == Approx(-0.5 / 9.81).epsilon(1e-12));
  CHECK((leaning.tip - kJib.foot).norm() == Approx(20.0).epsilon(1e-14));
  CHECK_THROWS_AS(flatPendulumControls(kJib, kStart, Eigen::Vector2d(0.0, -10.0)), std::domain_error);
  CHECK_THROWS_AS(flatPendulumControls(kJib, Eigen::Vector2d(-30.0, 0.0), Eigen::Vector2d::Zero()), std::domain_error);
}

TEST_CASE("Flat controls carry the load along its path and leave it still, quasi-static ones do not",
          "[planning][flatness]") {
  // Measured: the load within 1.9e-7 m of its path and 1.2e-7 m of the target after arrival (the
  // integration's error); with the tip held straight above the load, ±0.77 m of sway.
  const Swing flat = swing([](double t) { return flatPendulumControls(kJib, loadPath(t, 0), loadPath(t, 2)); });
  const Swing plumb = swing([](double t) { return flatPendulumControls(kJib, loadPath(t, 0), Eigen::Vector2d::Zero()); });
  INFO("flat: path " << flat.max_path_error << " m, sway " << flat.residual_sway << " m; plumb sway " << plumb.residual_sway);
  CHECK(flat.max_path_error < 1e-6);
  CHECK(flat.residual_sway < 1e-6);
  CHECK(plumb.residual_sway > 0.5);
  CHECK(plumb.max_path_error > 0.1);
}

TEST_CASE("Flat map through the static map: the resting point's static controls carry the load", "[planning][flatness]") {
  // crane-opt (method flatness) knows the crane only by its static map: the controls that hang the
  // load at rest at a point. On the rigid pendulum the map is closed-form — the tip on the boom's
  // circle straight above the point, the rope down to it — and its controls at the resting point
  // p + ℓ (e − ẑ), with ℓ the rope those controls set (a fixed point), are the flat controls.
  const auto staticControls = [](const Eigen::Vector2d& resting) {
    PendulumControls c;
    const double dx = resting.x() - kJib.foot.x();
    c.tip = Eigen::Vector2d(resting.x(), kJib.foot.y() + std::sqrt(kJib.boom_length * kJib.boom_length - dx * dx));
    c.rope_length = c.tip.y() - resting.y();
    c.boom_angle = std::asin((c.tip.y() - kJib.foot.y()) / kJib.boom_length);
    return c;
  };
  const auto throughRestingPoint = [&](double t) {
    const Eigen::Vector2d p = loadPath(t, 0), a = loadPath(t, 2);
    PendulumControls c = staticControls(p);
    for (int iteration = 0; iteration < 30; ++iteration) {
      const Vec3 resting = restingPoint(Vec3(p.x(), 0.0, p.y()), Vec3(a.x(), 0.0, a.y()), c.rope_length, c.rope_length,
                                        Vec3::UnitX(), kJib.gravity);
      c = staticControls(Eigen::Vector2d(resting.x(), resting.z()));
    }
    return c;
  };
  for (double t : {1.0, 2.5, 4.0, 6.3}) {
    const PendulumControls flat = flatPendulumControls(kJib, loadPath(t, 0), loadPath(t, 2)), mapped = throughRestingPoint(t);
    CHECK((mapped.tip - flat.tip).norm() < 1e-12);
    CHECK(mapped.rope_length == Approx(flat.rope_length).epsilon(1e-13));
  }
  const Swing swung = swing(throughRestingPoint);  // measured: as the direct flat map's, 1.9e-7 / 1.2e-7 m
  INFO("path " << swung.max_path_error << " m, sway " << swung.residual_sway << " m");
  CHECK(swung.max_path_error < 1e-6);
  CHECK(swung.residual_sway < 1e-6);
}
