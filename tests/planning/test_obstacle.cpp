// Signed distances between the crane's parts and obstacles (planning/obstacle.hpp), against
// distances worked by hand: outside a face, an edge and a corner, touching, and inside.

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "cranesim/planning/obstacle.hpp"

using namespace cranesim;

namespace {

constexpr double kExact = 1e-9;  // closed forms; the segment search lands within 1e-12 × its length

double at(const ObstacleShape& shape, double x, double y, double z) { return signedDistance(shape, Vec3(x, y, z)); }

double segment(const ObstacleShape& shape, const Vec3& a, const Vec3& b, double radius = 0.0) {
  return signedDistance(shape, Capsule{a, b, radius});
}

/// The triangle (0, 0), (4, 0), (0, 3) from z = 0 to 2; its hypotenuse lies on 3x + 4y = 12.
PrismShape triangle() { return PrismShape{{{0, 0}, {4, 0}, {0, 3}}, 0.0, 2.0}; }

}  // namespace

TEST_CASE("Box: point distances outside a face, edge and corner, touching and inside", "[planning][obstacles]") {
  const ObstacleShape box = BoxShape{Vec3(0, 0, 0), Vec3(2, 4, 6), 0.0};  // half sizes 1, 2, 3
  CHECK(at(box, 3, 0, 0) == Approx(2.0).margin(kExact));
  CHECK(at(box, 2, 3, 0) == Approx(std::sqrt(2.0)).margin(kExact));  // beyond the edge x = 1, y = 2
  CHECK(at(box, 2, 3, 4) == Approx(std::sqrt(3.0)).margin(kExact));  // beyond the corner
  CHECK(at(box, 1, 0.5, -2) == Approx(0.0).margin(kExact));         // on the face
  CHECK(at(box, 0.5, 0, 0) == Approx(-0.5).margin(kExact));         // half a metre in from x = 1
  CHECK(at(box, 0, 0, 0) == Approx(-1.0).margin(kExact));           // centre: 1 m from the nearest face
  const ObstacleShape moved = BoxShape{Vec3(10, -5, 2), Vec3(2, 4, 6), 0.0};
  CHECK(at(moved, 13, -5, 2) == Approx(2.0).margin(kExact));
}

TEST_CASE("Box turned about the vertical: yaw swaps and tilts its faces", "[planning][obstacles]") {
  const ObstacleShape quarter = BoxShape{Vec3(0, 0, 0), Vec3(2, 4, 6), std::numbers::pi / 2};  // now ±2 in x, ±1 in y
  CHECK(at(quarter, 3, 0, 0) == Approx(1.0).margin(kExact));
  CHECK(at(quarter, 0, 3, 0) == Approx(2.0).margin(kExact));
  // A 2 m cube turned by 45°: its vertical edge points along x at √2 from the axis.
  const ObstacleShape diamond = BoxShape{Vec3(0, 0, 0), Vec3(2, 2, 2), std::numbers::pi / 4};
  CHECK(at(diamond, 3, 0, 0) == Approx(3.0 - std::sqrt(2.0)).margin(kExact));
  CHECK(at(diamond, 3, 0, 2) == Approx(std::hypot(3.0 - std::sqrt(2.0), 1.0)).margin(kExact));
  CHECK(at(diamond, 1, 1, 0) == Approx(std::sqrt(2.0) - 1.0).margin(kExact));  // off the face x + y = √2
}

TEST_CASE("Vertical cylinder: point distances off the side, the top, the rim and inside", "[planning][obstacles]") {
  const ObstacleShape cylinder = CylinderShape{Vec3(1, 1, 0), 2.0, 3.0};
  CHECK(at(cylinder, 1, 1, 5) == Approx(2.0).margin(kExact));          // above the top
  CHECK(at(cylinder, 5, 1, 1.5) == Approx(2.0).margin(kExact));        // beside the side
  CHECK(at(cylinder, 6, 1, 7) == Approx(5.0).margin(kExact));          // off the rim: 3 out, 4 up
  CHECK(at(cylinder, 1 + 3 / std::sqrt(2.0), 1 + 3 / std::sqrt(2.0), -1) == Approx(std::sqrt(2.0)).margin(kExact));
  CHECK(at(cylinder, 3, 1, 1) == Approx(0.0).margin(kExact));          // on the side
  CHECK(at(cylinder, 1, 1, 1.5) == Approx(-1.5).margin(kExact));       // on the axis, mid-height
  CHECK(at(cylinder, 2.5, 1, 1.5) == Approx(-0.5).margin(kExact));     // 0.5 m in from the side
}

TEST_CASE("Convex prism: point distances off an edge, a corner, the top and inside", "[planning][obstacles]") {
  const ObstacleShape prism = triangle();
  CHECK(at(prism, 4, 3, 1) == Approx(2.4).margin(kExact));             // off the hypotenuse: (12 + 12 − 12) / 5
  CHECK(at(prism, -3, -4, 1) == Approx(5.0).margin(kExact));           // off the corner at the origin
  CHECK(at(prism, -3, -4, 6) == Approx(std::sqrt(41.0)).margin(kExact));  // and 4 m above the top
  CHECK(at(prism, 1, 1, 4) == Approx(2.0).margin(kExact));             // over the footprint
  CHECK(at(prism, 2, 0, 1) == Approx(0.0).margin(kExact));             // on a side face
  CHECK(at(prism, 1, 1, 1) == Approx(-1.0).margin(kExact));            // 1 m from three faces at once
  CHECK(at(prism, 1, 1, 0.5) == Approx(-0.5).margin(kExact));          // nearer the bottom
}

TEST_CASE("Footprints: either orientation is taken, non-convex ones refused", "[planning][obstacles]") {
  std::vector<Eigen::Vector2d> clockwise{{0, 0}, {0, 3}, {4, 0}};
  REQUIRE(makeConvexCounterClockwise(clockwise));
  const ObstacleShape prism = PrismShape{clockwise, 0.0, 2.0};
  CHECK(at(prism, 4, 3, 1) == Approx(2.4).margin(kExact));
  CHECK(at(prism, 1, 1, 1) == Approx(-1.0).margin(kExact));
  std::vector<Eigen::Vector2d> ell{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  CHECK_FALSE(makeConvexCounterClockwise(ell));
  std::vector<Eigen::Vector2d> star;
  for (int k = 0; k < 5; ++k) star.emplace_back(std::cos(4 * std::numbers::pi * k / 5), std::sin(4 * std::numbers::pi * k / 5));
  CHECK_FALSE(makeConvexCounterClockwise(star));  // every turn the same way, but it winds twice
  std::vector<Eigen::Vector2d> collinear{{0, 0}, {1, 0}, {2, 0}, {1, 1}};
  CHECK_FALSE(makeConvexCounterClockwise(collinear));
  std::vector<Eigen::Vector2d> two{{0, 0}, {1, 0}};
  CHECK_FALSE(makeConvexCounterClockwise(two));
}

TEST_CASE("Segments and capsules against a box: face, edge, end point, touching, through", "[planning][obstacles]") {
  const ObstacleShape box = BoxShape{Vec3(0, 0, 0), Vec3(2, 2, 2), 0.0};
  CHECK(segment(box, Vec3(-5, 0, 3), Vec3(5, 0, 3)) == Approx(2.0).margin(kExact));       // over the top face
  CHECK(segment(box, Vec3(2, -5, 2), Vec3(2, 5, 2)) == Approx(std::sqrt(2.0)).margin(kExact));  // along an edge
  CHECK(segment(box, Vec3(4, 0, 0), Vec3(0, 4, 0)) == Approx(std::sqrt(2.0)).margin(kExact));   // skew past the edge x = y = 1
  CHECK(segment(box, Vec3(3, 0, 0), Vec3(10, 0, 0)) == Approx(2.0).margin(kExact));       // nearest at its end
  CHECK(segment(box, Vec3(10, 0, 0), Vec3(3, 0, 0), 0.5) == Approx(1.5).margin(kExact));  // a capsule, ends swapped
  CHECK(segment(box, Vec3(1, -5, 0), Vec3(1, 5, 0)) == Approx(0.0).margin(kExact));       // touching a face
  CHECK(segment(box, Vec3(-5, 0, 0), Vec3(5, 0, 0)) == Approx(-1.0).margin(kExact));      // through the centre
  CHECK(segment(box, Vec3(-5, 0, 0.5), Vec3(5, 0, 0.5), 0.25) == Approx(-0.75).margin(kExact));
  CHECK(segment(box, Vec3(3, 0, 0), Vec3(3, 0, 0), 0.5) == Approx(1.5).margin(kExact));   // a sphere
}

TEST_CASE("Segments and capsules against a cylinder and a prism", "[planning][obstacles]") {
  const ObstacleShape cylinder = CylinderShape{Vec3(0, 0, 0), 1.0, 2.0};
  CHECK(segment(cylinder, Vec3(-5, 0, 3), Vec3(5, 0, 3)) == Approx(1.0).margin(kExact));
  CHECK(segment(cylinder, Vec3(-5, 3, 1), Vec3(5, 3, 1)) == Approx(2.0).margin(kExact));
  CHECK(segment(cylinder, Vec3(3, 0, -10), Vec3(3, 0, 10), 0.5) == Approx(1.5).margin(kExact));
  CHECK(segment(cylinder, Vec3(-5, 0, 1), Vec3(5, 0, 1)) == Approx(-1.0).margin(kExact));
  CHECK(segment(cylinder, Vec3(3, 0, 4), Vec3(5, 0, 6)) == Approx(2.0 * std::sqrt(2.0)).margin(kExact));  // off the rim
  CHECK(segment(cylinder, Vec3(-5, 1, 1), Vec3(5, 1, 1)) == Approx(0.0).margin(kExact));  // grazing the side
  const ObstacleShape prism = triangle();
  CHECK(segment(prism, Vec3(-1, -1, 1), Vec3(-1, 5, 1)) == Approx(1.0).margin(kExact));
  CHECK(segment(prism, Vec3(1, 1, 5), Vec3(10, 10, 5)) == Approx(3.0).margin(kExact));
  CHECK(segment(prism, Vec3(1, 1, -5), Vec3(1, 1, 5)) == Approx(-1.0).margin(kExact));
  // Parallel to the hypotenuse, 1 m out: (4, 0) + (3, 4)/5 to (0, 3) + (3, 4)/5.
  CHECK(segment(prism, Vec3(4.6, 0.8, 1), Vec3(0.6, 3.8, 1), 0.25) == Approx(0.75).margin(kExact));
}

TEST_CASE("Point distances' gradients: central differences outside and inside every shape", "[planning][obstacles]") {
  const std::vector<ObstacleShape> shapes = {BoxShape{Vec3(1, -2, 3), Vec3(2, 4, 6), 0.3}, CylinderShape{Vec3(1, 1, 0), 2.0, 3.0},
                                             triangle()};
  // Off faces, edges and corners, and inside off-centre (one face nearest, so the gradient exists).
  const std::vector<Vec3> points = {{4.1, -1.3, 3.2}, {3.7, 1.9, 7.4}, {-2.2, -6.1, -1.3}, {1.2, -1.6, 3.4},
                                    {5.3, 1.2, 1.1}, {2.6, 1.3, 1.6}, {1.4, 0.8, 2.6}, {4.5, 3.5, 1.2}, {0.8, 0.9, 0.6}};
  const double h = 1e-6;
  int checked = 0;
  for (const ObstacleShape& shape : shapes)
    for (const Vec3& p : points) {
      const DistanceWithGradient d = signedDistanceWithGradient(shape, p);
      CHECK(d.distance == signedDistance(shape, p));
      CHECK(d.gradient.norm() == Approx(1.0).margin(1e-12));  // a distance grows at unit rate, in or out
      Vec3 difference;
      for (int i = 0; i < 3; ++i)
        difference(i) = (signedDistance(shape, Vec3(p + h * Vec3::Unit(i))) - signedDistance(shape, Vec3(p - h * Vec3::Unit(i)))) / (2 * h);
      CHECK((d.gradient - difference).norm() < 1e-6);
      ++checked;
    }
  CHECK(checked == 27);
}
