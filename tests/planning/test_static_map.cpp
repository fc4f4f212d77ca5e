// The static map of crane-opt (thesis 6.2) on the miniature luffing jib, whose equilibria are
// known in closed form: a rigid boom, a straight luffing rope, a load hanging plumb under the tip.

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <numbers>

#include "cranesim/planning/static_map.hpp"
#include "cranesim/solvers/statics.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

constexpr double kG = 9.81, kBoom = 20.0, kBoomMass = 2000.0, kLoad = 1000.0, kRopeArea = std::numbers::pi * 1e-4;
constexpr double kEA = 1e11 * kRopeArea, kHoistLength = 10.0;
const Vec3 kMastTop(4.0, 0.0, 12.0);

const CraneControls kJib{"luffing_rope", "hoist_rope", "ground.foot", "boom.tip", "load.hook"};

/// The jib with a weightless luffing rope (a straight line, uniform tension).
Scene jibScene() {
  Scene scene = test::loadScene("luffing_jib.yaml");
  for (MemberSpec& m : scene.members)
    if (m.name == "luffing_rope") m.material.density = 1e-9;
  return scene;
}

struct JibEquilibrium {
  double luffing_length, end_x, end_z;
};

/// Moment balance about the foot pin (y components of r × F), elastic stretch of both ropes.
JibEquilibrium jibEquilibrium(double angle_deg, double hoist_change) {
  const double a = angle_deg * std::numbers::pi / 180.0;
  const Vec3 tip = kBoom * Vec3(-std::cos(a), 0.0, std::sin(a)), centroid = 0.5 * tip;
  const double hoist = kHoistLength - hoist_change, w = 7800.0 * kRopeArea * kG;
  const double hoist_pull = kLoad * kG + w * hoist;  // at the tip, downwards
  const Vec3 along = (kMastTop - tip).normalized();
  const auto momentY = [](const Vec3& r, const Vec3& f) { return r.z() * f.x() - r.x() * f.z(); };
  const double tension = -(momentY(tip, Vec3(0, 0, -hoist_pull)) + momentY(centroid, Vec3(0, 0, -kBoomMass * kG))) /
                         momentY(tip, along);
  const double stretched_hoist = hoist + (kLoad * kG * hoist + 0.5 * w * hoist * hoist) / kEA;
  return {(kMastTop - tip).norm() / (1.0 + tension / kEA), tip.x(), tip.z() - stretched_hoist};
}

StaticMapSpec jibMap(int threads) {
  StaticMapSpec spec;
  spec.boom_angles_deg = {40, 55, 70};
  spec.hoist_changes = {0, 3, 6};
  spec.threads = threads;
  return spec;
}

}  // namespace

TEST_CASE("Static map: the luffing jib's equilibria against the closed form", "[planning][map]") {
  const StaticMap map = computeStaticMap(jibScene(), kJib, jibMap(2));
  REQUIRE(map.failures.empty());
  CHECK(map.hoist_length == kHoistLength);
  for (int i = 0; i < map.rows(); ++i)
    for (int j = 0; j < map.columns(); ++j) {
      const JibEquilibrium exact = jibEquilibrium(map.boom_angles_deg[i], map.hoist_changes[j]);
      INFO("boom angle " << map.boom_angles_deg[i] << "°, hoist change " << map.hoist_changes[j] << " m");
      CHECK(map.luffing_length(i, j) == Approx(exact.luffing_length).epsilon(1e-9));
      CHECK(map.hoist_rope_length(i, j) == kHoistLength - map.hoist_changes[j]);
      CHECK(map.end_x(i, j) == Approx(exact.end_x).epsilon(1e-9));
      CHECK(map.end_z(i, j) == Approx(exact.end_z).epsilon(1e-9));
      CHECK(std::abs(map.end_y(i, j)) < 1e-9);
      // Along a row (3 m of hoist rope) the chord iteration converges fast; the 15° steps of the
      // first column are taken in halves when they must.
      if (j > 0) CHECK(map.iterations(i, j) <= 8);
    }
}

TEST_CASE("Static map: the parallel sweep equals the serial one", "[planning][map]") {
  const Scene scene = jibScene();
  const StaticMap serial = computeStaticMap(scene, kJib, jibMap(1));
  const StaticMap parallel = computeStaticMap(scene, kJib, jibMap(2));
  CHECK(serial.threads == 1);
  CHECK(parallel.threads == 2);
  CHECK(parallel.execution == "2 threads");
  // Each row starts from its spine point alone: the same bits whichever thread computes it.
  for (auto field : {&StaticMap::luffing_length, &StaticMap::end_x, &StaticMap::end_y, &StaticMap::end_z}) {
    const Eigen::MatrixXd &a = serial.*field, &b = parallel.*field;
    CHECK(std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0);
  }
  CHECK((serial.iterations.array() == parallel.iterations.array()).all());
  CHECK(serial.jacobians == parallel.jacobians);
}

TEST_CASE("Static map: controls must name ropes and joints of the scene", "[planning][map]") {
  const Scene scene = jibScene();
  CraneControls wrong = kJib;
  wrong.hoist_rope = "boom";
  CHECK_THROWS_WITH(checkControls(scene, wrong, {"crane", 3, 1}), Catch::Contains("no member 'boom'"));
  wrong = kJib;
  wrong.end_point = "load.bottom";
  CHECK_THROWS_WITH(checkControls(scene, wrong, {"crane", 3, 1}), Catch::Contains("no joint 'load.bottom'"));
  wrong = kJib;
  wrong.hoist_rope = "luffing_rope";
  CHECK_THROWS_WITH(checkControls(scene, wrong, {"crane", 3, 1}), Catch::Contains("different members"));
}

TEST_CASE("Static map on the thesis crane: its bordered equilibria are the crane's equilibria", "[planning][map][crane]") {
  const Scene scene = test::loadScene("crane.yaml");
  const CraneControls crane{"luffing_rope", "hoist_rope", "pedestal.boom_foot", "head.origin", "load.origin"};
  StaticMapSpec spec;
  spec.boom_angles_deg = {81, 82};
  spec.hoist_changes = {0, 1};
  spec.hoist_length = 53.9937;  // the thesis' initial hoist rope (8.3.1)
  const StaticMap map = computeStaticMap(scene, crane, spec);
  REQUIRE(map.failures.empty());
  // The thesis' initial luffing rope, 7.0608 m, holds the boom at 81.60°: between the two rows.
  CHECK(map.luffing_length(0, 0) > 7.0608);
  CHECK(map.luffing_length(1, 0) < 7.0608);

  // The crane under the map's controls at (82°, 1 m), solved as any scene: same boom angle,
  // same end point.
  const Scene fixed = withControls(scene, crane, Profile(ConstantProfile{map.luffing_length(1, 1)}),
                                   Profile(ConstantProfile{map.hoist_rope_length(1, 1)}));
  const Model model = compileModel(fixed);
  const StaticResult eq = solveStatics(model, map.equilibria[1 * 2 + 1].head(model.nq), fixed.solver.t_start);
  REQUIRE(eq.converged);
  const Vec3 head = model.jointFrame(eq.q.data(), model.findJoint("head.origin")).r;
  const Vec3 foot = model.jointFrame(eq.q.data(), model.findJoint("pedestal.boom_foot")).r;
  const Vec3 load = model.jointFrame(eq.q.data(), model.findJoint("load.origin")).r;
  CHECK(std::atan2(head.z() - foot.z(), std::hypot(head.x() - foot.x(), head.y() - foot.y())) * 180.0 / std::numbers::pi ==
        Approx(82.0).epsilon(1e-10));
  CHECK((load - Vec3(map.end_x(1, 1), map.end_y(1, 1), map.end_z(1, 1))).norm() < 1e-8);

  // Taking in 1 m of hoist rope lifts the 390 t load by the metre and the stretch it carried
  // at the top of the rope (the boom barely moves: its load changes by 1 m of rope).
  const double area = std::numbers::pi * 0.05 * 0.05, EA = 1e11 * area, w = 7800 * area * 9.8;
  const double top_strain = (390000.6 * 9.8 + w * (53.9937 - 0.5)) / EA;
  for (int i = 0; i < 2; ++i) CHECK(map.end_z(i, 1) - map.end_z(i, 0) == Approx(1.0 + top_strain).margin(2e-4));
}
