// Surfaces fitted to the static map (6.2) and their inversion (8.4): polynomials of the
// fitted orders are reproduced, the bicubic spline interpolates with fourth-order accuracy,
// and the inverse recovers the grid coordinates of end points inside the map.

#include <catch2/catch.hpp>

#include <algorithm>

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <numbers>
#include <random>

#include "cranesim/planning/surface_fit.hpp"

using namespace cranesim;

namespace {

std::vector<double> grid(double from, double to, double step) {
  const int count = static_cast<int>(std::lround((to - from) / step)) + 1;
  std::vector<double> values(count);
  for (int k = 0; k < count; ++k) values[k] = from + k * step;
  return values;
}

GridData sample(std::vector<double> u, std::vector<double> v, const std::function<double(double, double)>& f) {
  GridData data{std::move(u), std::move(v), {}};
  data.values.resize(data.u.size(), data.v.size());
  for (std::size_t i = 0; i < data.u.size(); ++i)
    for (std::size_t j = 0; j < data.v.size(); ++j) data.values(i, j) = f(data.u[i], data.v[j]);
  return data;
}

/// Boom angle 45..85° by 1°, hoist rope change 0..20 m by 1 m, as in the thesis' example map.
GridData mapGrid(const std::function<double(double, double)>& f) { return sample(grid(45, 85, 1), grid(0, 20, 1), f); }

/// Points off the grid lines, spread over the rectangle.
std::vector<Eigen::Vector2d> offGridPoints() {
  std::vector<Eigen::Vector2d> points;
  for (double u = 45.3; u < 85; u += 3.7)
    for (double v = 0.2; v < 20; v += 2.9) points.emplace_back(u, v);
  return points;
}

SurfaceSpec polynomial(int order_u, int order_v) { return {SurfaceKind::Polynomial, order_u, order_v}; }

const SurfaceSpec kSpline{SurfaceKind::Spline};

}  // namespace

TEST_CASE("A 2-2 polynomial fit reproduces a degree (2, 2) polynomial and its gradient", "[planning][fit]") {
  const auto f = [](double u, double v) {
    return 3 + 0.2 * u - 0.004 * u * u + 0.5 * v - 0.03 * v * v + 0.01 * u * v - 2e-4 * u * u * v + 1e-5 * u * u * v * v;
  };
  const auto gradient = [](double u, double v) {
    return Eigen::Vector2d(0.2 - 0.008 * u + 0.01 * v - 4e-4 * u * v + 2e-5 * u * v * v,
                           0.5 - 0.06 * v + 0.01 * u - 2e-4 * u * u + 2e-5 * u * u * v);
  };
  const GridData data = mapGrid(f);
  const FittedSurface s = FittedSurface::fit(data, polynomial(2, 2));
  const double scale = data.values.cwiseAbs().maxCoeff();
  CHECK(s.maxResidual() < 1e-9 * scale);
  CHECK(s.rmsResidual() <= s.maxResidual());
  for (const Eigen::Vector2d& p : offGridPoints()) {
    INFO("(u, v) = (" << p.x() << ", " << p.y() << ")");
    CHECK(s(p.x(), p.y()) == Approx(f(p.x(), p.y())).epsilon(1e-9).margin(1e-9 * scale));
    const Eigen::Vector2d g = s.gradient(p.x(), p.y()), expected = gradient(p.x(), p.y());
    CHECK(g.x() == Approx(expected.x()).epsilon(1e-9).margin(1e-9));
    CHECK(g.y() == Approx(expected.y()).epsilon(1e-9).margin(1e-9));
  }
}

TEST_CASE("A degree (3, 1) surface needs the 3-1 fit", "[planning][fit]") {
  const auto f = [](double u, double v) {
    const double w = u - 60;
    return 2 + 1e-3 * w * w * w + 0.05 * v + 2e-5 * w * w * w * v - 0.01 * w * v;
  };
  const GridData data = mapGrid(f);
  const double scale = data.values.cwiseAbs().maxCoeff();
  const FittedSurface quadratic = FittedSurface::fit(data, polynomial(2, 2));
  CHECK(quadratic.maxResidual() > 0.1);
  CHECK(quadratic.rmsResidual() > 0.01);
  const FittedSurface cubic = FittedSurface::fit(data, polynomial(3, 1));
  CHECK(cubic.maxResidual() < 1e-9 * scale);
  for (const Eigen::Vector2d& p : offGridPoints())
    CHECK(cubic(p.x(), p.y()) == Approx(f(p.x(), p.y())).epsilon(1e-9).margin(1e-9 * scale));
}

TEST_CASE("Polynomial orders 1..5 reproduce polynomials of their degree, other orders are rejected", "[planning][fit]") {
  for (int order_u = 1; order_u <= 5; ++order_u)
    for (int order_v = 1; order_v <= 5; ++order_v) {
      const auto f = [&](double u, double v) {
        double sum = 0;
        for (int a = 0; a <= order_u; ++a)
          for (int b = 0; b <= order_v; ++b) sum += (a % 2 ? -1.0 : 1.0) / (1 + a + b) * std::pow(u / 50, a) * std::pow(v / 10, b);
        return sum;
      };
      const GridData data = mapGrid(f);
      const double scale = data.values.cwiseAbs().maxCoeff();
      const FittedSurface s = FittedSurface::fit(data, polynomial(order_u, order_v));
      INFO("orders " << order_u << "-" << order_v);
      CHECK(s.maxResidual() < 1e-9 * scale);
      for (const Eigen::Vector2d& p : offGridPoints())
        CHECK(s(p.x(), p.y()) == Approx(f(p.x(), p.y())).epsilon(1e-9).margin(1e-9 * scale));
    }
  const GridData data = mapGrid([](double u, double v) { return u + v; });
  CHECK_THROWS_AS(FittedSurface::fit(data, polynomial(6, 2)), std::invalid_argument);
  CHECK_THROWS_AS(FittedSurface::fit(data, polynomial(2, 6)), std::invalid_argument);
  CHECK_THROWS_AS(FittedSurface::fit(data, polynomial(0, 2)), std::invalid_argument);
  const GridData five_v = sample(grid(45, 85, 1), grid(0, 20, 5), [](double u, double v) { return u * v; });
  CHECK_THROWS_AS(FittedSurface::fit(five_v, polynomial(2, 5)), std::invalid_argument);
  CHECK_NOTHROW(FittedSurface::fit(five_v, polynomial(2, 4)));
}

TEST_CASE("Malformed grids are rejected, a failed map point is reported with its grid index", "[planning][fit]") {
  const auto f = [](double u, double v) { return u - v; };
  GridData data = mapGrid(f);
  data.values(3, 7) = std::numeric_limits<double>::quiet_NaN();
  for (const SurfaceSpec& spec : {polynomial(2, 2), kSpline}) {
    CHECK_THROWS_AS(FittedSurface::fit(data, spec), std::invalid_argument);
    CHECK_THROWS_WITH(FittedSurface::fit(data, spec), Catch::Contains("(3, 7)") && Catch::Contains("failed"));
  }
  GridData decreasing = mapGrid(f);
  std::swap(decreasing.u[4], decreasing.u[5]);
  CHECK_THROWS_AS(FittedSurface::fit(decreasing, kSpline), std::invalid_argument);
  GridData repeated = mapGrid(f);
  repeated.v[3] = repeated.v[2];
  CHECK_THROWS_AS(FittedSurface::fit(repeated, polynomial(2, 2)), std::invalid_argument);
  GridData mismatched = mapGrid(f);
  mismatched.u.pop_back();
  CHECK_THROWS_AS(FittedSurface::fit(mismatched, polynomial(2, 2)), std::invalid_argument);
  const GridData single_v = sample(grid(45, 85, 1), {10.0}, f);
  CHECK_THROWS_AS(FittedSurface::fit(single_v, kSpline), std::invalid_argument);
}

TEST_CASE("The bicubic spline interpolates, converges with fourth order and has exact gradients", "[planning][fit]") {
  const auto f = [](double u, double v) { return std::sin(u / 10) * std::cos(v / 7); };
  const GridData data = mapGrid(f);
  const FittedSurface s = FittedSurface::fit(data, kSpline);
  CHECK(s.maxResidual() < 1e-12);
  for (std::size_t i = 0; i < data.u.size(); ++i)
    for (std::size_t j = 0; j < data.v.size(); ++j) REQUIRE(std::abs(s(data.u[i], data.v[j]) - data.values(i, j)) < 1e-12);

  // Cell centres in u ∈ [55, 75], v ∈ [5, 15], away from the natural end conditions.
  const auto interiorError = [&](double step) {
    const FittedSurface fine = FittedSurface::fit(sample(grid(45, 85, step), grid(0, 20, step), f), kSpline);
    double error = 0;
    for (double u = 55 + step / 2; u < 75; u += step)
      for (double v = 5 + step / 2; v < 15; v += step) error = std::max(error, std::abs(fine(u, v) - f(u, v)));
    return error;
  };
  const double coarse = interiorError(1.0), fine = interiorError(0.5);
  std::printf("bicubic spline interior error: h = 1: %.3e, h = 0.5: %.3e, ratio %.2f\n", coarse, fine, coarse / fine);
  // Spline interpolation bound 5/384 h⁴ max|f''''| in each direction.
  CHECK(coarse < 5.0 / 384 * (std::pow(0.1, 4) + std::pow(1.0 / 7, 4)));
  CHECK(coarse / fine > 10);

  const double h = 1e-5;
  for (const Eigen::Vector2d& p : offGridPoints()) {
    const Eigen::Vector2d g = s.gradient(p.x(), p.y());
    const double du = (s(p.x() + h, p.y()) - s(p.x() - h, p.y())) / (2 * h);
    const double dv = (s(p.x(), p.y() + h) - s(p.x(), p.y() - h)) / (2 * h);
    INFO("(u, v) = (" << p.x() << ", " << p.y() << ")");
    CHECK(g.x() == Approx(du).epsilon(1e-6).margin(1e-9));
    CHECK(g.y() == Approx(dv).epsilon(1e-6).margin(1e-9));
  }
}

TEST_CASE("The spline is linear along a direction with two grid points", "[planning][fit]") {
  const auto f = [](double u, double v) { return std::sin(u / 10) * (1 + 0.1 * v); };
  const FittedSurface two_v = FittedSurface::fit(sample(grid(45, 85, 1), {0.0, 20.0}, f), kSpline);
  const FittedSurface dense_v = FittedSurface::fit(sample(grid(45, 85, 1), grid(0, 20, 1), f), kSpline);
  for (const Eigen::Vector2d& p : offGridPoints()) {
    CHECK(two_v(p.x(), p.y()) == Approx(dense_v(p.x(), p.y())).epsilon(1e-12).margin(1e-12));
    CHECK(two_v.gradient(p.x(), p.y()).y() == Approx(0.1 * two_v(p.x(), 0.0)).epsilon(1e-12));
  }
}

namespace {

constexpr double kBoomLength = 58.0;

/// A synthetic static map: boom tip on a circle, the load hanging 54 − v below it.
Eigen::Vector2d endPoint(double u_degrees, double v) {
  const double u = u_degrees * std::numbers::pi / 180;
  return {-kBoomLength * std::cos(u) * (1 + 0.001 * v), kBoomLength * std::sin(u) - (54 - v)};
}

}  // namespace

TEST_CASE("Inverting the end point surfaces recovers (u, v) inside the map and rejects points outside",
          "[planning][fit]") {
  const GridData data_x = mapGrid([](double u, double v) { return endPoint(u, v).x(); });
  const GridData data_z = mapGrid([](double u, double v) { return endPoint(u, v).y(); });
  for (const SurfaceSpec& spec : {polynomial(2, 2), kSpline}) {
    INFO((spec.kind == SurfaceKind::Spline ? "spline" : "2-2 polynomial"));
    const FittedSurface fx = FittedSurface::fit(data_x, spec), fz = FittedSurface::fit(data_z, spec);

    std::mt19937 random(42);
    std::uniform_real_distribution<double> random_u(45, 85), random_v(0, 20);
    for (int k = 0; k < 300; ++k) {
      const double u = random_u(random), v = random_v(random);
      const double x = fx(u, v), z = fz(u, v);
      const Eigen::Vector2d inverse = invertSurfaces(fx, fz, data_x, data_z, x, z);
      INFO("(u, v) = (" << u << ", " << v << ")");
      CHECK(std::abs(fx(inverse.x(), inverse.y()) - x) < 1e-9);
      CHECK(std::abs(fz(inverse.x(), inverse.y()) - z) < 1e-9);
      CHECK(inverse.x() == Approx(u).epsilon(1e-9));
      CHECK(inverse.y() == Approx(v).margin(1e-8));
    }

    for (const auto& [u, v] : {std::pair{45.0, 0.0}, {45.0, 20.0}, {85.0, 0.0}, {85.0, 20.0}}) {
      const Eigen::Vector2d inverse = invertSurfaces(fx, fz, data_x, data_z, fx(u, v), fz(u, v));
      CHECK(inverse.x() == Approx(u).epsilon(1e-9));
      CHECK(inverse.y() == Approx(v).margin(1e-8));
    }

    for (const auto& [u, v] : {std::pair{88.0, 10.0}, {42.0, 5.0}, {60.0, -2.0}, {60.0, 23.0}}) {
      const Eigen::Vector2d outside = endPoint(u, v);
      INFO("outside (u, v) = (" << u << ", " << v << ")");
      CHECK_THROWS_AS(invertSurfaces(fx, fz, data_x, data_z, outside.x(), outside.y()), std::domain_error);
      CHECK_THROWS_WITH(invertSurfaces(fx, fz, data_x, data_z, outside.x(), outside.y()),
                        Catch::Contains("outside the static map"));
      // The error says where the inversion ended: a point of the rectangle, its end point, and no
      // farther from the asked-for point than the end point of (u, v) clamped to the rectangle.
      try {
        invertSurfaces(fx, fz, data_x, data_z, outside.x(), outside.y());
      } catch (const OutsideMap& e) {
        CHECK(e.uv.x() >= 45.0 - 1e-6);
        CHECK(e.uv.x() <= 85.0 + 1e-6);
        CHECK(e.uv.y() >= -1e-6);
        CHECK(e.uv.y() <= 20.0 + 1e-6);
        CHECK(e.xz.x() == fx(e.uv.x(), e.uv.y()));
        CHECK(e.xz.y() == fz(e.uv.x(), e.uv.y()));
        const Eigen::Vector2d clamped(fx(std::clamp(u, 45.0, 85.0), std::clamp(v, 0.0, 20.0)),
                                      fz(std::clamp(u, 45.0, 85.0), std::clamp(v, 0.0, 20.0)));
        CHECK((e.xz - outside).norm() <= (clamped - outside).norm() + 1e-9);
      }
    }
    CHECK_THROWS_WITH(invertSurfaces(fx, fz, data_x, data_z, 1000.0, 0.0), Catch::Contains("outside the static map"));
  }

  // The exact map's end points are found by the spline to the accuracy of its fit. The natural
  // end conditions at u = 45° and 85° cost 7e-4° next to them, decaying by 2 − √3 per cell.
  const FittedSurface fx = FittedSurface::fit(data_x, kSpline), fz = FittedSurface::fit(data_z, kSpline);
  double max_error = 0;
  for (double u = 50.5; u < 80; u += 2.1)
    for (double v = 0.5; v < 20; v += 3.3) {
      const Eigen::Vector2d p = endPoint(u, v);
      const Eigen::Vector2d error = invertSurfaces(fx, fz, data_x, data_z, p.x(), p.y()) - Eigen::Vector2d(u, v);
      max_error = std::max(max_error, error.cwiseAbs().maxCoeff());
    }
  CHECK(max_error < 3e-6);

  GridData other_grid = data_z;
  other_grid.v.back() += 1;
  CHECK_THROWS_AS(invertSurfaces(fx, fx, data_x, other_grid, 0.0, 0.0), std::invalid_argument);
}
