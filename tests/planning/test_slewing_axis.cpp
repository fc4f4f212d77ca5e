// Radii from a vertical slewing axis and the map plane's x, both ways, on a plane offset from
// the axis (a 3-4-5 triangle) and through it.

#include <catch2/catch.hpp>

#include <stdexcept>

#include "cranesim/planning/slewing_axis.hpp"

using namespace cranesim;

TEST_CASE("slewing axis: radius and plane x are inverse, the plane's offset counted", "[planning]") {
  SlewingAxis axis;
  axis.point = Eigen::Vector2d(1.0, 2.0);
  axis.plane_y = 5.0;  // 3 m beside the axis
  axis.side = -1.0;
  CHECK(axis.radiusAt(-3.0) == Approx(5.0).epsilon(1e-15));
  CHECK(axis.xAtRadius(5.0) == Approx(-3.0).epsilon(1e-15));
  CHECK(axis.xAtRadius(3.0) == Approx(1.0).epsilon(1e-15));  // where the plane passes the axis closest
  for (const double r : {3.5, 10.0, 87.25}) CHECK(axis.radiusAt(axis.xAtRadius(r)) == Approx(r).epsilon(1e-14));
  axis.side = 1.0;
  CHECK(axis.xAtRadius(5.0) == Approx(5.0).epsilon(1e-15));
  CHECK_THROWS_AS(axis.xAtRadius(2.99), std::domain_error);

  axis.plane_y = axis.point.y();  // the plane through the axis: the radius is |x − c_x|
  CHECK(axis.xAtRadius(12.5) == Approx(13.5).epsilon(1e-15));
  CHECK(axis.radiusAt(-11.5) == Approx(12.5).epsilon(1e-15));
}
