#include "cranesim/planning/surface_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "cranesim/math/profile.hpp"

namespace cranesim {
namespace {

constexpr int kMaxPolynomialOrder = 5;

void requireIncreasingAxis(const std::vector<double>& axis, const char* name) {
  for (std::size_t i = 0; i < axis.size(); ++i) {
    if (!std::isfinite(axis[i])) throw std::invalid_argument(std::string("surface fit: non-finite ") + name + " grid value");
    if (i > 0 && !(axis[i] > axis[i - 1]))
      throw std::invalid_argument(std::string("surface fit: the ") + name + " grid must be strictly increasing");
  }
}

void requireEnoughPoints(std::size_t points, std::size_t needed, const char* name, const std::string& why) {
  if (points < needed) {
    std::ostringstream message;
    message << "surface fit: " << points << " grid points along " << name << ", " << why << " needs at least " << needed;
    throw std::invalid_argument(message.str());
  }
}

void validate(const GridData& data, const SurfaceSpec& spec) {
  if (spec.kind == SurfaceKind::Polynomial) {
    for (int order : {spec.order_u, spec.order_v})
      if (order < 1 || order > kMaxPolynomialOrder)
        throw std::invalid_argument("surface fit: polynomial order " + std::to_string(order) + " is outside 1.." +
                                    std::to_string(kMaxPolynomialOrder));
    requireEnoughPoints(data.u.size(), spec.order_u + 1, "u", "order " + std::to_string(spec.order_u));
    requireEnoughPoints(data.v.size(), spec.order_v + 1, "v", "order " + std::to_string(spec.order_v));
  } else {
    requireEnoughPoints(data.u.size(), 2, "u", "a spline");
    requireEnoughPoints(data.v.size(), 2, "v", "a spline");
  }
  requireIncreasingAxis(data.u, "u");
  requireIncreasingAxis(data.v, "v");
  if (data.values.rows() != static_cast<Eigen::Index>(data.u.size()) ||
      data.values.cols() != static_cast<Eigen::Index>(data.v.size()))
    throw std::invalid_argument("surface fit: values must be " + std::to_string(data.u.size()) + " × " +
                                std::to_string(data.v.size()) + " (u × v)");
  for (Eigen::Index i = 0; i < data.values.rows(); ++i)
    for (Eigen::Index j = 0; j < data.values.cols(); ++j)
      if (!std::isfinite(data.values(i, j))) {
        std::ostringstream message;
        message << "surface fit: value " << data.values(i, j) << " at grid point (" << i << ", " << j << ") (u = " << data.u[i]
                << ", v = " << data.v[j] << "): the static map failed at this point";
        throw std::invalid_argument(message.str());
      }
}

/// p(x) = Σ_k c[k] x^k and p'(x), by Horner's scheme.
std::pair<double, double> hornerWithSlope(const double* c, int degree, double x) {
  double value = c[degree], slope = 0.0;
  for (int k = degree - 1; k >= 0; --k) {
    slope = slope * x + value;
    value = value * x + c[k];
  }
  return {value, slope};
}

double horner(const double* c, int degree, double x) {
  double value = c[degree];
  for (int k = degree - 1; k >= 0; --k) value = value * x + c[k];
  return value;
}

std::vector<double> column(const Eigen::MatrixXd& m, Eigen::Index j) {
  return {m.col(j).data(), m.col(j).data() + m.rows()};
}

std::vector<double> row(const Eigen::MatrixXd& m, Eigen::Index i) {
  std::vector<double> r(m.cols());
  for (Eigen::Index j = 0; j < m.cols(); ++j) r[j] = m(i, j);
  return r;
}

/// Knot slopes of the natural cubic splines through every column (along u) of `values`.
Eigen::MatrixXd slopesAlongU(const std::vector<double>& u, const Eigen::MatrixXd& values) {
  Eigen::MatrixXd slopes(values.rows(), values.cols());
  for (Eigen::Index j = 0; j < values.cols(); ++j)
    slopes.col(j) = Eigen::Map<const Eigen::VectorXd>(splineSlopes(u, column(values, j), false).data(), values.rows());
  return slopes;
}

/// Knot slopes of the natural cubic splines through every row (along v) of `values`.
Eigen::MatrixXd slopesAlongV(const std::vector<double>& v, const Eigen::MatrixXd& values) {
  Eigen::MatrixXd slopes(values.rows(), values.cols());
  for (Eigen::Index i = 0; i < values.rows(); ++i)
    slopes.row(i) = Eigen::Map<const Eigen::RowVectorXd>(splineSlopes(v, row(values, i), false).data(), values.cols());
  return slopes;
}

}  // namespace

std::pair<std::size_t, double> FittedSurface::Axis::locate(double x) const {
  const auto next_break = std::upper_bound(breaks.begin() + 1, breaks.end() - 1, x);
  const auto k = static_cast<std::size_t>(next_break - (breaks.begin() + 1));
  return {k, (x - origin[k]) / scale[k]};
}

const double* FittedSurface::piece(std::size_t k_u, std::size_t k_v) const {
  const std::size_t pieces_v = v_axis_.breaks.size() - 1;
  const std::size_t size = static_cast<std::size_t>((u_axis_.degree + 1) * (v_axis_.degree + 1));
  return coefficients_.data() + (k_u * pieces_v + k_v) * size;
}

FittedSurface FittedSurface::fit(const GridData& data, const SurfaceSpec& spec) {
  validate(data, spec);
  const std::size_t nu = data.u.size(), nv = data.v.size();
  FittedSurface surface;
  surface.kind_ = spec.kind;

  if (spec.kind == SurfaceKind::Polynomial) {
    // 6.2: scaling to [−1, 1] keeps the least-squares problem well conditioned up to order 5.
    const auto scaledAxis = [](const std::vector<double>& grid, int degree) {
      const double lo = grid.front(), hi = grid.back();
      return Axis{{lo, hi}, {0.5 * (lo + hi)}, {0.5 * (hi - lo)}, degree};
    };
    surface.u_axis_ = scaledAxis(data.u, spec.order_u);
    surface.v_axis_ = scaledAxis(data.v, spec.order_v);
    const int terms_v = spec.order_v + 1;
    Eigen::MatrixXd design(nu * nv, (spec.order_u + 1) * terms_v);
    Eigen::VectorXd rhs(nu * nv);
    for (std::size_t i = 0; i < nu; ++i) {
      const double su = surface.u_axis_.locate(data.u[i]).second;
      for (std::size_t j = 0; j < nv; ++j) {
        const double sv = surface.v_axis_.locate(data.v[j]).second;
        const Eigen::Index r = static_cast<Eigen::Index>(i * nv + j);
        for (int a = 0; a <= spec.order_u; ++a)
          for (int b = 0; b <= spec.order_v; ++b) design(r, a * terms_v + b) = std::pow(su, a) * std::pow(sv, b);
        rhs(r) = data.values(i, j);
      }
    }
    const Eigen::VectorXd c = design.colPivHouseholderQr().solve(rhs);
    surface.coefficients_.assign(c.data(), c.data() + c.size());
  } else {
    const auto splineAxis = [](const std::vector<double>& grid) {
      Axis axis{grid, {grid.begin(), grid.end() - 1}, std::vector<double>(grid.size() - 1), 3};
      for (std::size_t k = 0; k + 1 < grid.size(); ++k) axis.scale[k] = grid[k + 1] - grid[k];
      return axis;
    };
    surface.u_axis_ = splineAxis(data.u);
    surface.v_axis_ = splineAxis(data.v);
    // The tensor-product spline is bicubic on each cell, hence equal to the bicubic Hermite
    // patch of its corner values, slopes s_u, s_v and twists s_uv, which are the natural
    // spline slopes along u of the values, along v of the values, and along v of s_u.
    const Eigen::MatrixXd& f = data.values;
    const Eigen::MatrixXd f_u = slopesAlongU(data.u, f);
    const Eigen::MatrixXd f_v = slopesAlongV(data.v, f);
    const Eigen::MatrixXd f_uv = slopesAlongV(data.v, f_u);
    Eigen::Matrix4d hermite;  // monomial coefficients of p(s) from (p(0), p(1), p'(0), p'(1))
    hermite << 1, 0, 0, 0, 0, 0, 1, 0, -3, 3, -2, -1, 2, -2, 1, 1;
    surface.coefficients_.reserve((nu - 1) * (nv - 1) * 16);
    for (std::size_t i = 0; i + 1 < nu; ++i) {
      const double hu = data.u[i + 1] - data.u[i];
      for (std::size_t j = 0; j + 1 < nv; ++j) {
        const double hv = data.v[j + 1] - data.v[j];
        const auto block = [&](const Eigen::MatrixXd& m) { return m.block<2, 2>(i, j); };
        Eigen::Matrix4d corners;
        corners << block(f), hv * block(f_v), hu * block(f_u), hu * hv * block(f_uv);
        const Eigen::Matrix<double, 4, 4, Eigen::RowMajor> c = hermite * corners * hermite.transpose();
        surface.coefficients_.insert(surface.coefficients_.end(), c.data(), c.data() + 16);
      }
    }
  }

  double sum_squares = 0.0;
  for (std::size_t i = 0; i < nu; ++i)
    for (std::size_t j = 0; j < nv; ++j) {
      const double r = std::abs(surface(data.u[i], data.v[j]) - data.values(i, j));
      surface.max_residual_ = std::max(surface.max_residual_, r);
      sum_squares += r * r;
    }
  surface.rms_residual_ = std::sqrt(sum_squares / static_cast<double>(nu * nv));
  return surface;
}

double FittedSurface::operator()(double u, double v) const {
  const auto [k_u, s] = u_axis_.locate(u);
  const auto [k_v, t] = v_axis_.locate(v);
  const double* c = piece(k_u, k_v);
  const int terms_v = v_axis_.degree + 1;
  double value = 0.0;
  for (int a = u_axis_.degree; a >= 0; --a) value = value * s + horner(c + a * terms_v, v_axis_.degree, t);
  return value;
}

Eigen::Vector2d FittedSurface::gradient(double u, double v) const {
  const auto [k_u, s] = u_axis_.locate(u);
  const auto [k_v, t] = v_axis_.locate(v);
  const double* c = piece(k_u, k_v);
  const int terms_v = v_axis_.degree + 1;
  // s(·) = Σ_a s^a p_a(t): Horner in s over the p_a(t) with the slope carried along.
  double value = 0.0, d_s = 0.0, d_t = 0.0;
  for (int a = u_axis_.degree; a >= 0; --a) {
    const auto [p, dp] = hornerWithSlope(c + a * terms_v, v_axis_.degree, t);
    d_s = d_s * s + value;
    value = value * s + p;
    d_t = d_t * s + dp;
  }
  return {d_s / u_axis_.scale[k_u], d_t / v_axis_.scale[k_v]};
}

Eigen::Vector2d invertSurfaces(const FittedSurface& fx, const FittedSurface& fz, const GridData& data_x,
                               const GridData& data_z, double x, double z, double tolerance) {
  if (data_x.u != data_z.u || data_x.v != data_z.v || data_x.values.rows() != data_z.values.rows() ||
      data_x.values.cols() != data_z.values.cols() || data_x.u.empty() || data_x.v.empty())
    throw std::invalid_argument("invertSurfaces: the x and z data must share a non-empty grid");
  const Eigen::Vector2d target(x, z);

  Eigen::Index start_i = 0, start_j = 0;
  double nearest = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < data_x.values.rows(); ++i)
    for (Eigen::Index j = 0; j < data_x.values.cols(); ++j) {
      const double d = (Eigen::Vector2d(data_x.values(i, j), data_z.values(i, j)) - target).squaredNorm();
      if (d < nearest) nearest = d, start_i = i, start_j = j;
    }

  const Eigen::Vector2d size(data_x.u.back() - data_x.u.front(), data_x.v.back() - data_x.v.front());
  const Eigen::Vector2d lower = Eigen::Vector2d(data_x.u.front(), data_x.v.front()) - 1e-9 * size;
  const Eigen::Vector2d upper = Eigen::Vector2d(data_x.u.back(), data_x.v.back()) + 1e-9 * size;
  const auto residual = [&](const Eigen::Vector2d& p) {
    return Eigen::Vector2d(fx(p.x(), p.y()) - x, fz(p.x(), p.y()) - z);
  };

  Eigen::Vector2d point(data_x.u[start_i], data_x.v[start_j]);
  Eigen::Vector2d r = residual(point);
  constexpr int kMaxIterations = 100, kMaxHalvings = 40;
  for (int iteration = 0; iteration < kMaxIterations && r.norm() >= tolerance; ++iteration) {
    Eigen::Matrix2d jacobian;
    jacobian.row(0) = fx.gradient(point.x(), point.y()).transpose();
    jacobian.row(1) = fz.gradient(point.x(), point.y()).transpose();
    const Eigen::FullPivLU<Eigen::Matrix2d> lu(jacobian);
    if (!lu.isInvertible()) break;
    const Eigen::Vector2d step = -lu.solve(r);
    bool decreased = false;
    double damping = 1.0;
    for (int halving = 0; halving < kMaxHalvings && !decreased; ++halving, damping *= 0.5) {
      const Eigen::Vector2d trial = (point + damping * step).cwiseMax(lower).cwiseMin(upper);
      const Eigen::Vector2d trial_r = residual(trial);
      if (trial_r.norm() < (1.0 - 1e-4 * damping) * r.norm()) point = trial, r = trial_r, decreased = true;
    }
    if (!decreased) break;
  }
  if (r.norm() < tolerance) return point;

  std::ostringstream message;
  message.precision(10);
  message << "end point (x, z) = (" << x << ", " << z << ") lies outside the static map: the closest (u, v) = ("
          << point.x() << ", " << point.y() << ") in [" << data_x.u.front() << ", " << data_x.u.back() << "] × ["
          << data_x.v.front() << ", " << data_x.v.back() << "] misses it by " << r.norm();
  throw OutsideMap(message.str(), point, Eigen::Vector2d(fx(point.x(), point.y()), fz(point.x(), point.y())));
}

}  // namespace cranesim
