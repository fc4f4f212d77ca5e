// The dual number of autodiff.hpp against closed-form derivatives: every elementary function,
// the arithmetic with plain numbers on either side, second derivatives by nesting, and
// derivatives through Eigen's matrix products.

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <functional>

#include "cranesim/math/autodiff.hpp"

using namespace cranesim;

namespace {

using D1 = Dual<double, 1>;
using D2 = Dual<double, 2>;
using DD = Dual<Dual<double, 2>, 2>;

D1 variable(double x) { return seeded<double, 1>(x, 0); }

/// x and y seeded in two directions at both levels: f(x, y) carries its gradient at the inner
/// level and its Hessian in the outer level's derivatives of the inner derivatives.
std::array<DD, 2> nestedVariables(double x, double y) {
  std::array<DD, 2> v;
  for (int k = 0; k < 2; ++k) v[k] = seeded<D2, 2>(seeded<double, 2>(k == 0 ? x : y, k), k);
  return v;
}

}  // namespace

TEST_CASE("Dual numbers give the derivative of every elementary function", "[autodiff]") {
  struct Case {
    const char* name;
    std::function<D1(const D1&)> f;
    std::function<double(double)> value, slope;
    double x;
  };
  using std::sqrt, std::sin, std::cos, std::tan, std::asin, std::acos, std::atan, std::exp, std::log, std::tanh;
  const std::vector<Case> cases = {
      {"sqrt", [](const D1& x) { return sqrt(x); }, [](double x) { return sqrt(x); }, [](double x) { return 0.5 / sqrt(x); }, 2.3},
      {"sin", [](const D1& x) { return sin(x); }, [](double x) { return sin(x); }, [](double x) { return cos(x); }, 0.7},
      {"cos", [](const D1& x) { return cos(x); }, [](double x) { return cos(x); }, [](double x) { return -sin(x); }, 0.7},
      {"tan", [](const D1& x) { return tan(x); }, [](double x) { return tan(x); }, [](double x) { return 1.0 / (cos(x) * cos(x)); }, 0.4},
      {"asin", [](const D1& x) { return asin(x); }, [](double x) { return asin(x); }, [](double x) { return 1.0 / sqrt(1.0 - x * x); }, 0.3},
      {"acos", [](const D1& x) { return acos(x); }, [](double x) { return acos(x); }, [](double x) { return -1.0 / sqrt(1.0 - x * x); }, -0.6},
      {"atan", [](const D1& x) { return atan(x); }, [](double x) { return atan(x); }, [](double x) { return 1.0 / (1.0 + x * x); }, 1.7},
      {"exp", [](const D1& x) { return exp(x); }, [](double x) { return exp(x); }, [](double x) { return exp(x); }, -0.8},
      {"log", [](const D1& x) { return log(x); }, [](double x) { return log(x); }, [](double x) { return 1.0 / x; }, 3.1},
      {"tanh", [](const D1& x) { return tanh(x); }, [](double x) { return tanh(x); }, [](double x) { return 1.0 - tanh(x) * tanh(x); }, 0.9},
      {"abs", [](const D1& x) { return abs(x); }, [](double x) { return std::abs(x); }, [](double x) { return x < 0 ? -1.0 : 1.0; }, -1.3},
      {"pow", [](const D1& x) { return pow(x, 2.5); }, [](double x) { return std::pow(x, 2.5); }, [](double x) { return 2.5 * std::pow(x, 1.5); }, 1.9},
      {"atan2(y, 0.4)", [](const D1& y) { return atan2(y, D1(0.4)); }, [](double y) { return std::atan2(y, 0.4); },
       [](double y) { return 0.4 / (0.16 + y * y); }, -0.7},
      {"atan2(1.1, x)", [](const D1& x) { return atan2(D1(1.1), x); }, [](double x) { return std::atan2(1.1, x); },
       [](double x) { return -1.1 / (1.21 + x * x); }, -0.7},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    const D1 y = c.f(variable(c.x));
    CHECK(y.value() == Approx(c.value(c.x)).epsilon(1e-15));
    CHECK(y.derivatives()(0) == Approx(c.slope(c.x)).epsilon(1e-14));
  }
}

TEST_CASE("Dual arithmetic with plain numbers on either side follows the rules of calculus", "[autodiff]") {
  const double x = 1.3;
  const D1 X = variable(x);
  // f = (2 + 3x − x/4) · (5 − x) / (1 + x²) + 1/x − 7/x², f' in closed form.
  const D1 f = (2.0 + 3 * X - X / 4.0) * (5 - X) / (1.0 + X * X) + 1.0 / X - 7 / (X * X);
  const double p = 2.0 + 2.75 * x, q = 5.0 - x, r = 1.0 + x * x;
  const double value = p * q / r + 1.0 / x - 7.0 / (x * x);
  const double slope = (2.75 * q - p) / r - p * q * 2.0 * x / (r * r) - 1.0 / (x * x) + 14.0 / (x * x * x);
  CHECK(f.value() == Approx(value).epsilon(1e-15));
  CHECK(f.derivatives()(0) == Approx(slope).epsilon(1e-12));  // a difference of terms 100 times larger

  D1 g = X;
  g += 2.0, g *= 3, g -= X, g /= 2.0, g *= X, g /= (X + 1.0);  // ((3(x + 2) − x)/2) x / (x + 1)
  const double h = (2.0 * x + 6.0) / 2.0;                      // = x + 3
  CHECK(g.value() == Approx(h * x / (x + 1.0)).epsilon(1e-15));
  CHECK(g.derivatives()(0) == Approx(((2.0 * x + 3.0) * (x + 1.0) - (h * x)) / ((x + 1.0) * (x + 1.0))).epsilon(1e-14));

  CHECK(X < 2.0);
  CHECK(2.0 > X);
  CHECK(X == 1.3);
  CHECK_FALSE(X > X + 1e-12);
}

TEST_CASE("Nested dual numbers give exact Hessians", "[autodiff]") {
  // f(x, y) = sin(x y) / (1 + x²) + y³ exp(−x).
  const double x = 0.8, y = -1.4;
  const auto [X, Y] = nestedVariables(x, y);
  const DD f = sin(X * Y) / (1.0 + X * X) + Y * Y * Y * exp(-X);
  const double s = std::sin(x * y), c = std::cos(x * y), r = 1.0 + x * x, e = std::exp(-x);
  // a = sin(xy), b = 1/r: f = a b + y³ e.
  const double a_x = y * c, a_y = x * c, a_xx = -y * y * s, a_xy = c - x * y * s, a_yy = -x * x * s;
  const double b = 1.0 / r, b_x = -2.0 * x / (r * r), b_xx = (6.0 * x * x - 2.0) / (r * r * r);
  const double fx = a_x * b + s * b_x - y * y * y * e, fy = a_y * b + 3.0 * y * y * e;
  const double fxx = a_xx * b + 2.0 * a_x * b_x + s * b_xx + y * y * y * e;
  const double fxy = a_xy * b + a_y * b_x - 3.0 * y * y * e;
  const double fyy = a_yy * b + 6.0 * y * e;
  CHECK(f.value().value() == Approx(s * b + y * y * y * e).epsilon(1e-15));
  CHECK(f.value().derivatives()(0) == Approx(fx).epsilon(1e-14));
  CHECK(f.value().derivatives()(1) == Approx(fy).epsilon(1e-14));
  CHECK(f.derivatives()(0).value() == Approx(fx).epsilon(1e-14));  // outer gradient = inner
  CHECK(f.derivatives()(0).derivatives()(0) == Approx(fxx).epsilon(1e-13));
  CHECK(f.derivatives()(0).derivatives()(1) == Approx(fxy).epsilon(1e-13));
  CHECK(f.derivatives()(1).derivatives()(0) == Approx(fxy).epsilon(1e-13));
  CHECK(f.derivatives()(1).derivatives()(1) == Approx(fyy).epsilon(1e-13));
  CHECK(valueOf(f) == f.value().value());
}

TEST_CASE("Dual numbers pass through Eigen's matrix products and norms", "[autodiff]") {
  // d/dt ‖A(t) b‖ with A(t) = A₀ + t A₁: (A b)·(A₁ b) / ‖A b‖.
  Mat3 A0, A1;
  A0 << 1, 2, 0, -1, 3, 1, 0.5, 0, 2;
  A1 << 0, 1, 1, 2, 0, -1, 1, 1, 0;
  const Vec3 b(0.3, -0.2, 0.9);
  const double t = 0.6;
  const Mat3T<D1> A = A0.cast<D1>() + variable(t) * A1.cast<D1>();
  const Vec3T<D1> Ab = A * b.cast<D1>();
  const D1 n = Ab.norm();
  const Vec3 Abv = (A0 + t * A1) * b;
  CHECK(n.value() == Approx(Abv.norm()).epsilon(1e-15));
  CHECK(n.derivatives()(0) == Approx(Abv.dot(A1 * b) / Abv.norm()).epsilon(1e-14));
  const Vec3T<D1> unit = Ab.normalized();
  CHECK(unit(0).derivatives()(0) == Approx(((A1 * b)(0) - Abv(0) * Abv.dot(A1 * b) / Abv.squaredNorm()) / Abv.norm()).epsilon(1e-13));
}
