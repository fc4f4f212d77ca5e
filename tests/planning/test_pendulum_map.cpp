// The load's pendulum over the static map (planning/pendulum_map.hpp) on the miniature luffing
// jib, whose sway is known in closed form: its boom is rigid and pinned, so across its plane the
// hook block swings as a compound pendulum — a rope of the hoist rope's length from a fixed point,
// and the block, a rigid body hung by its top.

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "cranesim/planning/pendulum_map.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

constexpr double kG = 9.81, kLoad = 1000.0, kHookToCentroid = 0.5, kInertia = 200.0;  // luffing_jib.yaml's block
constexpr double kEA = 1e11 * std::numbers::pi * 1e-4;

const CraneControls kJib{"luffing_rope", "hoist_rope", "ground.foot", "boom.tip", "load.hook"};

/// g / ω² of the lowest mode of a massless rope of length L from a fixed point with a rigid body
/// (mass m, centroid d below the hook, inertia I about it) at its end: with the angles of rope and
/// body, M = [[m L², m L d], [m L d, m d² + I]], K = diag(m g L, m g d), det(K − ω² M) = 0.
double compoundPendulum(double L) {
  const double m = kLoad, d = kHookToCentroid;
  const double a = m * L * L * kInertia;
  const double b = m * kG * L * (m * d * d + kInertia) + m * kG * d * m * L * L;
  const double c = m * kG * L * m * kG * d;
  const double omega_squared = (b - std::sqrt(b * b - 4.0 * a * c)) / (2.0 * a);
  return kG / omega_squared;
}

}  // namespace

TEST_CASE("Pendulum map: the luffing jib's hook block is a compound pendulum over the map", "[planning][map]") {
  Scene scene = test::loadScene("luffing_jib.yaml");
  for (MemberSpec& m : scene.members) m.material.density = 1.0;  // ropes of negligible mass (a mode needs some)
  StaticMapSpec spec;
  spec.boom_angles_deg = {40, 50, 60, 70};
  spec.hoist_changes = {0, 2, 4, 6};
  spec.threads = 2;
  const StaticMap map = computeStaticMap(scene, kJib, spec);
  REQUIRE(map.failures.empty());
  const PendulumMap pendulum = measurePendulumMap(scene, kJib, map, true, kG, {3, 3, 2, 2}, 2);

  CHECK(pendulum.modal_analyses == 9);
  CHECK(pendulum.across.u == std::vector<double>{40, 60, 70});  // spread over the map, its edges included
  CHECK(pendulum.across.v == std::vector<double>{0, 4, 6});
  for (std::size_t a = 0; a < pendulum.across.u.size(); ++a)
    for (std::size_t b = 0; b < pendulum.across.v.size(); ++b) {
      const double hoist = map.hoist_length - pendulum.across.v[b];
      const double expected = compoundPendulum(hoist * (1.0 + kLoad * kG / kEA));
      const double across = pendulum.across.values(a, b), along = pendulum.along.values(a, b);
      INFO("boom angle " << pendulum.across.u[a] << "°, hoist change " << pendulum.across.v[b] << " m: ℓ_c " << across
                         << " m, ℓ_a " << along << " m, compound pendulum " << expected << " m");
      CHECK(across == Approx(expected).epsilon(1e-5));  // measured ≤ 2e-6
      // In the plane the boom head gives a little on the luffing rope: a pendulum up to 9 mm longer.
      CHECK(along > across);
      CHECK(along == Approx(expected).epsilon(5e-3));
      // Order 2 through 3 × 3 points interpolates them.
      CHECK(pendulum.across_fit(pendulum.across.u[a], pendulum.across.v[b]) == Approx(across).epsilon(1e-9));
    }
}
