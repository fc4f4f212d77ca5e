// Drive profiles of Appendix E and tabulated splines: values at known points, and the
// derivatives that drives obtain by automatic differentiation against finite differences.

#include <catch2/catch.hpp>

#include <numbers>

#include "cranesim/math/autodiff.hpp"
#include "cranesim/math/profile.hpp"

using namespace cranesim;

namespace {

using D2 = Dual<Dual<double, 1>, 1>;

/// Value, first and second time derivative by nested automatic differentiation.
std::array<double, 3> jet(const Profile& p, double t) {
  const D2 x(Dual<double, 1>(t, Eigen::Matrix<double, 1, 1>::Ones()), Eigen::Matrix<Dual<double, 1>, 1, 1>::Constant(
                                                                       Dual<double, 1>(1.0, Eigen::Matrix<double, 1, 1>::Zero())));
  const D2 y = p(x);
  return {y.value().value(), y.derivatives()(0).value(), y.derivatives()(0).derivatives()(0)};
}

void checkDerivatives(const Profile& p, const std::vector<double>& times) {
  for (double t : times) {
    const double h = 1e-5;
    const auto j = jet(p, t);
    const double d1 = (p(t + h) - p(t - h)) / (2 * h);
    const double d2 = (p(t + h) - 2 * p(t) + p(t - h)) / (h * h);
    INFO("t = " << t);
    CHECK(j[0] == Approx(p(t)));
    CHECK(j[1] == Approx(d1).margin(1e-7));
    CHECK(j[2] == Approx(d2).margin(1e-4));
  }
}

}  // namespace

TEST_CASE("Trapezoidal three-stage profile (E-1..E-5): thesis example s0 = 10 m in 40 s", "[profiles]") {
  const Profile p(TrapezoidProfile{0.0, 10.0, 0.0, 40.0, 5.0, 5.0});
  const double a1 = 2.0 * 10.0 / (5.0 * (80.0 - 10.0));  // (E-5)
  CHECK(p(0.0) == 0.0);
  CHECK(p(5.0) == Approx(0.5 * a1 * 25.0));
  CHECK(p(20.0) == Approx(5.0));  // symmetric: half way at half time
  CHECK(p(40.0) == Approx(10.0));
  CHECK(p(50.0) == Approx(10.0));
  CHECK(jet(p, 20.0)[1] == Approx(a1 * 5.0));  // v_max = a1 t1
  checkDerivatives(p, {1.0, 4.0, 12.0, 30.0, 37.0});
  CHECK(p.breakpoints() == std::vector<double>{0.0, 5.0, 35.0, 40.0});
}

TEST_CASE("Cosine step and full cosine (E-6..E-11)", "[profiles]") {
  const Profile step(CosineStepProfile{10.0, 20.0, 5.0, 15.0});
  CHECK(step(0.0) == 10.0);
  CHECK(step(10.0) == Approx(15.0));
  CHECK(step(20.0) == 20.0);
  CHECK(jet(step, 10.0)[1] == Approx(std::numbers::pi / 2.0 * 10.0 / 10.0));  // (E-7) at the midpoint
  checkDerivatives(step, {6.0, 9.0, 14.0});
  const Profile full(CosineFullProfile{10.0, 20.0, 5.0, 15.0});
  CHECK(full(10.0) == Approx(20.0));
  CHECK(full(15.0) == Approx(10.0));
  CHECK(full(30.0) == 10.0);
  checkDerivatives(full, {6.0, 9.0, 14.0});
}

TEST_CASE("Hyperbolic tangent profile (E-13..E-15) reaches its confidence interval", "[profiles]") {
  // λ(c) = atanh(c): at t_start the value sits (1 − c)/2 of the step above y1. Table E-1 prints
  // 2.6476 and 1.4765, off from atanh in the 3rd–4th digit (see the profile reader).
  CHECK(tanhConfidenceCoefficient(0.99) == Approx(2.6467).margin(1e-3));
  CHECK(tanhConfidenceCoefficient(0.9) == Approx(1.4722).margin(1e-3));
  const Profile p(TanhProfile{10.0, 20.0, 5.0, 15.0, tanhConfidenceCoefficient(0.99)});
  CHECK(p(5.0) == Approx(10.0 + 10.0 * 0.005).epsilon(1e-3));
  CHECK(p(15.0) == Approx(20.0 - 10.0 * 0.005).epsilon(1e-3));
  CHECK(p(10.0) == Approx(15.0));
  checkDerivatives(p, {3.0, 7.0, 10.0, 13.0});
}

TEST_CASE("Tabulated spline interpolates, has continuous second derivatives and zero end slopes", "[profiles]") {
  TableProfile table{{0.0, 1.0, 2.5, 4.0}, {0.0, 1.0, -0.5, 2.0}, {}};
  table.slopes = splineSlopes(table.t, table.y, true);
  const Profile p(table);
  for (std::size_t k = 0; k < table.t.size(); ++k) CHECK(p(table.t[k]) == Approx(table.y[k]));
  CHECK(jet(p, 1e-9)[1] == Approx(0.0).margin(1e-6));
  CHECK(jet(p, 4.0 - 1e-9)[1] == Approx(0.0).margin(1e-6));
  for (double knot : {1.0, 2.5}) {  // C² at interior knots
    CHECK(jet(p, knot - 1e-9)[2] == Approx(jet(p, knot + 1e-9)[2]).margin(1e-5));
  }
  checkDerivatives(p, {0.5, 1.7, 3.2});
}

TEST_CASE("Natural spline has zero curvature at its ends", "[profiles]") {
  TableProfile table{{0.0, 1.0, 2.0, 3.0}, {0.0, 2.0, 1.0, 3.0}, {}};
  table.slopes = splineSlopes(table.t, table.y, false);
  const Profile p(table);
  CHECK(jet(p, 1e-9)[2] == Approx(0.0).margin(1e-6));
  CHECK(jet(p, 3.0 - 1e-9)[2] == Approx(0.0).margin(1e-6));
}

TEST_CASE("Linear and step tables: values, one-sided limits at the knots, a breakpoint at every knot", "[profiles]") {
  TableProfile table{{0.0, 1.0, 2.5, 4.0}, {0.0, 1.0, -0.5, 2.0}, {}, Interpolation::Linear};
  const Profile linear(table);
  CHECK(linear(0.5) == Approx(0.5));
  CHECK(linear(1.75) == Approx(0.25));
  CHECK(linear(5.0) == Approx(2.0));
  // Slopes: 1 on (0, 1), −1 on (1, 2.5); at the knot the left and the right limit's.
  Dual<double, 1> at_knot(1.0, Eigen::Matrix<double, 1, 1>::Ones());
  CHECK(linear(at_knot, Limit::Left).derivatives()(0) == Approx(1.0));
  CHECK(linear(at_knot, Limit::Right).derivatives()(0) == Approx(-1.0));
  CHECK(linear.breakpoints() == table.t);
  // Its integral is the trapezoid rule's, exactly (2-point Gauss per interval integrates lines).
  double integral = 0.0;
  for (std::size_t k = 0; k + 1 < table.t.size(); ++k) {
    const double a = table.t[k], h = table.t[k + 1] - a, c = 0.5 / std::sqrt(3.0);
    integral += 0.5 * h * (linear(a + (0.5 - c) * h) + linear(a + (0.5 + c) * h));
  }
  CHECK(integral == Approx(0.5 * 1.0 + 0.25 * 1.5 + 0.75 * 1.5).epsilon(1e-14));

  table.interpolation = Interpolation::Step;
  const Profile step(table);
  CHECK(step(0.5) == 0.0);
  CHECK(step(1.0, Limit::Left) == 0.0);
  CHECK(step(1.0, Limit::Right) == 1.0);
  CHECK(step(3.0) == -0.5);
  CHECK(step(4.0, Limit::Left) == -0.5);
  CHECK(step(4.0, Limit::Right) == 2.0);
  CHECK(step(9.0) == 2.0);
  CHECK(step(at_knot, Limit::Right).derivatives()(0) == 0.0);
  CHECK(step.jumps());
  CHECK_FALSE(linear.jumps());
}
