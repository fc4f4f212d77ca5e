// Support statics of a rigid carriage: four pads under a carriage with a counterweight and a
// slewing load against the linear distribution of a rigid plate on springs, the lift-off angle
// against that distribution's sign change and the three pads left against statically
// determinate statics; a track on a Winkler bed of discrete springs against the trapezoid and
// the triangle; the tipping line and margin against the distance to the nearest edge.

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include <Eigen/Dense>

#include "cranesim/crane/support_statics.hpp"

using namespace cranesim;
using Eigen::Vector2d;

namespace {

constexpr double kHalfX = 4.0, kHalfY = 3.0;  // m, pads at (±4, ±3)
constexpr double kCarriage = 600e3, kCounterweight = 900e3, kLoad = 500e3;  // N
constexpr double kCounterweightArm = 3.0, kLoadRadius = 8.0;               // m

std::vector<PadSpring> fourPads() {
  return {{{kHalfX, kHalfY}, 5e8}, {{-kHalfX, kHalfY}, 5e8}, {{-kHalfX, -kHalfY}, 5e8},
          {{kHalfX, -kHalfY}, 5e8}};
}

/// The vertical resultant's point with the upper carriage slewed by `angle`.
Vector2d resultantAt(double angle) {
  const Vector2d direction(std::cos(angle), std::sin(angle));
  return (kLoad * kLoadRadius - kCounterweight * kCounterweightArm) * direction /
         (kCarriage + kCounterweight + kLoad);
}

/// A rigid plate on four equal springs at (±a, ±b): F_i = W/4·(1 + x_c·x_i/a² + y_c·y_i/b²).
double linearPadForce(const Vector2d& pad, double weight, const Vector2d& resultant) {
  return weight / 4.0 *
         (1.0 + resultant.x() * pad.x() / (kHalfX * kHalfX) + resultant.y() * pad.y() / (kHalfY * kHalfY));
}

}  // namespace

TEST_CASE("four pads carry the linear distribution of a rigid plate", "[supports]") {
  const double weight = kCarriage + kCounterweight + kLoad;
  const auto pads = fourPads();
  for (const double degrees : {0.0, 30.0, 90.0, 150.0, 180.0, 270.0}) {
    const Vector2d resultant = resultantAt(degrees * std::numbers::pi / 180.0);
    const auto forces = rigidPlatePadForces(pads, weight, resultant);
    for (std::size_t i = 0; i < pads.size(); ++i) {
      INFO("slewed " << degrees << "°, pad " << i);
      CHECK(forces[i] == Approx(linearPadForce(pads[i].position, weight, resultant)).epsilon(1e-6));
    }
  }
}

TEST_CASE("a pad lifts off where the linear distribution changes sign", "[supports]") {
  // A resultant further out unloads the rear-left pad when the load swings
  // towards the front-right corner.
  const double weight = kCarriage + kCounterweight + kLoad;
  const auto pads = fourPads();
  const double scale = 4.0;  // the resultant 2.6 m off the middle
  auto resultant = [&](double angle) -> Vector2d { return scale * resultantAt(angle); };
  const Vector2d rear_left = pads[2].position;  // unloads as the load swings towards (+, +)
  // Bisect the sign change of the rear-left pad's linear force between 0° and the corner.
  double lo = 0.0, hi = std::numbers::pi / 2.0;
  REQUIRE(linearPadForce(rear_left, weight, resultant(lo)) > 0.0);
  REQUIRE(linearPadForce(rear_left, weight, resultant(hi)) > 0.0);
  const double corner = std::atan2(kHalfY, kHalfX);
  REQUIRE(linearPadForce(rear_left, weight, resultant(corner)) < 0.0);
  hi = corner;
  for (int n = 0; n < 60; ++n) {
    const double mid = 0.5 * (lo + hi);
    (linearPadForce(rear_left, weight, resultant(mid)) > 0.0 ? lo : hi) = mid;
  }
  const double before = lo - 1e-3, after = hi + 1e-3;
  CHECK(rigidPlatePadForces(pads, weight, resultant(before))[2] > 0.0);
  const auto lifted = rigidPlatePadForces(pads, weight, resultant(after));
  CHECK(lifted[2] == 0.0);

  // Three pads left: statically determinate, the resultant's barycentric coordinates.
  const Vector2d r = resultant(after);
  const Vector2d a = pads[0].position, b = pads[1].position, c = pads[3].position;
  Eigen::Matrix3d statics;
  statics << 1, 1, 1, a.x(), b.x(), c.x(), a.y(), b.y(), c.y();
  const Eigen::Vector3d determinate =
      statics.partialPivLu().solve(Eigen::Vector3d(weight, weight * r.x(), weight * r.y()));
  CHECK(lifted[0] == Approx(determinate[0]).epsilon(1e-9));
  CHECK(lifted[1] == Approx(determinate[1]).epsilon(1e-9));
  CHECK(lifted[3] == Approx(determinate[2]).epsilon(1e-9));
}

TEST_CASE("a resultant outside the pads tips the carriage", "[supports]") {
  CHECK_THROWS_WITH(rigidPlatePadForces(fourPads(), 1e6, Vector2d(kHalfX + 0.5, 0.0)),
                    Catch::Contains("tips"));
}

TEST_CASE("a track on a Winkler bed carries the trapezoid, then the triangle", "[supports]") {
  constexpr double length = 8.0, width = 1.2, force = 2e6;
  constexpr int segments = 400;
  const double ds = length / segments;
  std::vector<PadSpring> springs;
  for (int n = 0; n < segments; ++n)
    springs.push_back({{-length / 2.0 + (n + 0.5) * ds, 0.0}, 5e7 * width * ds});
  for (const double e : {0.0, 0.5, length / 6.0, 2.0, 3.0}) {
    INFO("eccentricity " << e << " m");
    const auto forces = rigidPlatePadForces(springs, force, Vector2d(e, 0.0));
    const TrackPressure formula = rigidTrackPressure(force, e, length, width);
    double peak = 0.0, carried = 0.0, moment = 0.0, contact = 0.0;
    for (int n = 0; n < segments; ++n) {
      const double s = springs[n].position.x();
      const double pressure = forces[n] / (width * ds);
      CHECK(pressure == Approx(rigidTrackPressureAt(force, e, length, width, s))
                            .margin(2.0 * formula.peak / segments));
      peak = std::max(peak, pressure);
      carried += rigidTrackPressureAt(force, e, length, width, s) * width * ds;
      moment += rigidTrackPressureAt(force, e, length, width, s) * width * ds * s;
      if (forces[n] > 0.0) contact += ds;
    }
    CHECK(peak == Approx(formula.peak).epsilon(2.0 / segments));
    CHECK(contact == Approx(formula.contact_length).margin(ds));
    CHECK(formula.peak_position == Approx(length / 2.0));
    // The formula itself: it carries the force at its eccentricity.
    CHECK(carried == Approx(force).epsilon(1e-4));
    CHECK(moment == Approx(force * e).margin(1e-4 * force * length));
  }
}

TEST_CASE("the tipping line is the polygon's edge nearest the resultant", "[supports]") {
  std::vector<Vector2d> corners;
  for (const auto& pad : fourPads()) corners.push_back(pad.position);
  const double weight = 2e6;
  const TippingLine inside = tippingLine(corners, weight, Vector2d(3.0, 0.5));
  CHECK(inside.from.x() == Approx(kHalfX));
  CHECK(inside.to.x() == Approx(kHalfX));
  CHECK(inside.margin == Approx(weight * (kHalfX - 3.0)));
  const TippingLine side = tippingLine(corners, weight, Vector2d(-1.0, -2.5));
  CHECK(side.from.y() == Approx(-kHalfY));
  CHECK(side.to.y() == Approx(-kHalfY));
  CHECK(side.margin == Approx(weight * 0.5));
  const TippingLine outside = tippingLine(corners, weight, Vector2d(4.5, 0.0));
  CHECK(outside.margin == Approx(-weight * 0.5));
}

TEST_CASE("the tipping force brings the resultant onto the edge it crosses first", "[supports]") {
  // The load at kLoadRadius straight ahead: with ΔF added there the resultant of W at x_c and ΔF
  // at 8 m lies on the front edge x = 4 m when (W·x_c + ΔF·8) / (W + ΔF) = 4.
  std::vector<Vector2d> corners;
  for (const auto& pad : fourPads()) corners.push_back(pad.position);
  const double weight = kCarriage + kCounterweight + kLoad;
  const Vector2d resultant = resultantAt(0.0);
  const double ahead = tippingForce(corners, weight, resultant, {kLoadRadius, 0.0});
  CHECK(ahead == Approx(weight * (kHalfX - resultant.x()) / (kLoadRadius - kHalfX)).epsilon(1e-12));
  CHECK((weight * resultant.x() + ahead * kLoadRadius) / (weight + ahead) == Approx(kHalfX).epsilon(1e-12));
  // Over a corner two edges face the load: the resultant, moving straight towards it, leaves
  // through the side edge y = 3 m (ΔF = 0.2 W: 1 m inside it, the load 5 m beyond) before it
  // reaches the front edge x = 4 m (ΔF = W: 2 m inside it, the load 2 m beyond).
  const Vector2d corner_load(6.0, 8.0), start(2.0, 2.0);
  const double over_corner = tippingForce(corners, weight, start, corner_load);
  const double side = weight * (kHalfY - start.y()) / (corner_load.y() - kHalfY);
  const double front = weight * (kHalfX - start.x()) / (corner_load.x() - kHalfX);
  REQUIRE(side < front);
  CHECK(over_corner == Approx(side).epsilon(1e-12));
  const Vector2d on_edge = (weight * start + over_corner * corner_load) / (weight + over_corner);
  CHECK(on_edge.y() == Approx(kHalfY).epsilon(1e-12));
  CHECK(on_edge.x() < kHalfX);
  // A load inside the polygon never tips it; a resultant outside it tips it already, even over
  // an edge the load lies inside of.
  CHECK(std::isinf(tippingForce(corners, weight, resultant, {1.0, 1.0})));
  CHECK(tippingForce(corners, weight, {-kHalfX - 0.5, 0.0}, {kLoadRadius, 0.0}) == 0.0);
}
