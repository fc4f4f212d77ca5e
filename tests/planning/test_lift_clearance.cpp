// The minimum-time lift's clearance constraints (planning/lift_clearance.hpp): the boom, rope
// and sheave where the boom angle and the slewing angle put them (worked by hand), and the
// smoothed segment clearance against the exact one (planning/obstacle.hpp): a lower bound that
// keeps the exact clearance above the margin whenever it is, within its allowance and τ log n,
// with the derivatives of central differences.

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "cranesim/planning/lift_clearance.hpp"

using namespace cranesim;

namespace {

LiftPoint<double> point(const Vec3& x) { return {x.x(), x.y(), x.z()}; }
Vec3 vec(const LiftPoint<double>& x) { return {x[0], x[1], x[2]}; }

}  // namespace

TEST_CASE("Lift body: boom foot, head and sheave at a boom angle and slewing angle", "[planning][obstacles]") {
  LiftBody body;
  body.boom_foot = Vec3(1, 0, 0);
  body.boom_out = -Vec3::UnitX();
  body.boom_length = 10.0;
  body.sheave_along = 1.0, body.sheave_up = 2.0;
  const SlewingPlane plane(Vec3::Zero(), 0.0, -1.0);
  // At 60° the head is 5 m in and 8.66 m up from the foot; the chord's upward normal (sin 60°, 0,
  // cos 60°) points back over the foot. A quarter turn about the z axis takes x to y.
  const BoomPoints<double> p = boomPoints(body, plane, 60.0, std::numbers::pi / 2);
  const double s = std::sqrt(3.0) / 2;
  CHECK((vec(p.foot) - Vec3(0, 1, 0)).norm() < 1e-12);
  CHECK((vec(p.head) - Vec3(0, -4, 10 * s)).norm() < 1e-12);
  CHECK((vec(p.sheave) - Vec3(0, -4 - 0.5 + 2 * s, 10 * s + s + 1)).norm() < 1e-12);
}

TEST_CASE("Segment clearance: a lower bound that keeps the exact one above the margin", "[planning][obstacles]") {
  const double reach = 0.8;  // margin 0.5 and a part of radius 0.3
  struct Case {
    ObstacleShape shape;
    Vec3 a, b, offset;  // the segment, moved by offset · δ across the reach
  };
  const std::vector<Case> cases = {
      // Parallel over a box's top face: every sample equally near.
      {BoxShape{Vec3(0, 0, 0), Vec3(2, 2, 2), 0.0}, Vec3(-20, 0.2, 1), Vec3(20, 0.2, 1), Vec3::UnitZ()},
      // Across a box's edge x = z = 1, nearest to it between samples: the dip case.
      {BoxShape{Vec3(0, 0, 0), Vec3(2, 2, 2), 0.0}, Vec3(-5, 0.3, 7), Vec3(7.37, 0.3, -5.37), Vec3(1, 0, 1).normalized()},
      // Past a cylinder's side and a turned box's vertical edge, skew.
      {CylinderShape{Vec3(0, 0, -5), 1.5, 10.0}, Vec3(1.5, -15, -3), Vec3(1.5, 25, 4), Vec3::UnitX()},
      {BoxShape{Vec3(0, 0, 0), Vec3(2, 2, 2), std::numbers::pi / 4}, Vec3(std::sqrt(2.0), -7, -0.5), Vec3(std::sqrt(2.0), 9, 0.3), Vec3::UnitX()},
      // Along a prism's hypotenuse 3x + 4y = 12.
      {PrismShape{{{0, 0}, {4, 0}, {0, 3}}, 0.0, 2.0}, Vec3(4, 0, 1), Vec3(0, 3, 1), Vec3(0.6, 0.8, 0)}};
  int above = 0, below = 0;
  for (const Case& c : cases)
    for (double delta = reach - 0.05; delta <= reach + 0.05; delta += 0.001) {
      const Vec3 a = c.a + delta * c.offset, b = c.b + delta * c.offset;
      const SegmentSampling sampling((b - a).norm(), reach);
      REQUIRE(sampling.allowance <= kSamplingAllowance);
      const double smooth = segmentDistance(c.shape, point(a), point(b), sampling);
      const double exact = signedDistance(c.shape, Capsule{a, b, 0.0});
      CHECK(smooth >= exact - sampling.allowance - kSoftMinimumWidth * std::log(sampling.points) - 1e-12);
      if (smooth >= reach) {
        CHECK(exact >= reach);
        ++above;
      } else {
        ++below;
      }
    }
  CHECK(above > 100);  // both sides of the reach were tried
  CHECK(below > 100);
}

TEST_CASE("Segment clearance: derivatives in the segment's ends against central differences", "[planning][obstacles]") {
  using D = Dual<double, 6>;
  const ObstacleShape box = BoxShape{Vec3(0.3, -0.2, 0), Vec3(2, 3, 2), 0.4};
  const Vec3 a(-6, 2.1, 2.3), b(7, -0.4, 1.4);
  const SegmentSampling sampling((b - a).norm() * 1.1, 0.6);
  LiftPoint<D> ad, bd;
  for (int i = 0; i < 3; ++i) ad[i] = seeded<double, 6>(a(i), i), bd[i] = seeded<double, 6>(b(i), 3 + i);
  const D value = segmentDistance(box, ad, bd, sampling);
  const double h = 1e-6;
  for (int k = 0; k < 6; ++k) {
    Vec3 ap = a, am = a, bp = b, bm = b;
    (k < 3 ? ap(k) : bp(k - 3)) += h;
    (k < 3 ? am(k) : bm(k - 3)) -= h;
    const double difference =
        (segmentDistance(box, point(ap), point(bp), sampling) - segmentDistance(box, point(am), point(bm), sampling)) / (2 * h);
    CHECK(value.derivatives()(k) == Approx(difference).margin(1e-6));
  }
  CHECK(value.value() == segmentDistance(box, point(a), point(b), sampling));
}
