#pragma once
// Surfaces fitted to the static map (6.2): each quantity of the map (luffing and hoist rope
// lengths, the load's end point x and z) is known on a regular grid of boom angle u × hoist
// rope change v and is fitted by a surface s(u, v). The planner inverts the end point
// surfaces to find the controls that place the load at a given point (8.4).

#include <Eigen/Dense>

#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "cranesim/math/autodiff.hpp"

namespace cranesim {

/// Values on a regular grid: values(i, j) at (u[i], v[j]); u, v strictly increasing.
struct GridData {
  std::vector<double> u, v;
  Eigen::MatrixXd values;
};

enum class SurfaceKind { Polynomial, Spline };

/// Polynomial orders 1..5 per variable (6.2: "below 5th order"; 2-2 recommended). The
/// orders are not used by the spline.
struct SurfaceSpec {
  SurfaceKind kind = SurfaceKind::Polynomial;
  int order_u = 2, order_v = 2;
};

/// A fitted surface s(u, v): the least-squares tensor-product polynomial
/// Σ_{a ≤ order_u, b ≤ order_v} c_ab ũ^a ṽ^b in variables scaled to [−1, 1] over the grid's
/// range, or the interpolating bicubic spline (natural cubic splines along u and along v,
/// tensor product; linear along a direction with only two grid points). Both are stored as
/// piecewise tensor-product polynomials; outside the grid the edge pieces are extended.
class FittedSurface {
 public:
  /// Throws std::invalid_argument on bad orders, too few grid points for the order, axes
  /// that are not strictly increasing, or non-finite values (a failed map point).
  static FittedSurface fit(const GridData& data, const SurfaceSpec& spec);

  double operator()(double u, double v) const;
  /// (∂s/∂u, ∂s/∂v).
  Eigen::Vector2d gradient(double u, double v) const;
  /// s(u, v) in any scalar with a value (double, or math/autodiff.hpp's Dual, nested for higher
  /// derivatives); the piece is chosen by the values.
  template <class S> S evaluate(const S& u, const S& v) const;

  /// Largest and root-mean-square |s(u_i, v_j) − values(i, j)| over the grid.
  double maxResidual() const { return max_residual_; }
  double rmsResidual() const { return rms_residual_; }

  SurfaceKind kind() const { return kind_; }

 private:
  /// One direction of the piecewise polynomial: piece k covers [breaks[k], breaks[k+1]] and
  /// is a polynomial of `degree` in the local coordinate (x − origin[k]) / scale[k].
  struct Axis {
    std::vector<double> breaks, origin, scale;
    int degree = 0;
    /// The piece holding x (the edge pieces extended outward) and x's local coordinate.
    std::pair<std::size_t, double> locate(double x) const;
  };

  /// Coefficients c_ab of piece (k_u, k_v), row-major over a = 0..degree_u, b = 0..degree_v.
  const double* piece(std::size_t k_u, std::size_t k_v) const;

  SurfaceKind kind_ = SurfaceKind::Polynomial;
  Axis u_axis_, v_axis_;
  std::vector<double> coefficients_;
  double max_residual_ = 0.0, rms_residual_ = 0.0;
};

template <class S> S FittedSurface::evaluate(const S& u, const S& v) const {
  const std::size_t k_u = u_axis_.locate(valueOf(u)).first, k_v = v_axis_.locate(valueOf(v)).first;
  const S s = (u - u_axis_.origin[k_u]) / u_axis_.scale[k_u], t = (v - v_axis_.origin[k_v]) / v_axis_.scale[k_v];
  const double* c = piece(k_u, k_v);
  const int terms_v = v_axis_.degree + 1;
  S value(0.0);
  for (int a = u_axis_.degree; a >= 0; --a) {
    S p(0.0);
    for (int b = v_axis_.degree; b >= 0; --b) p = p * t + c[a * terms_v + b];
    value = value * s + p;
  }
  return value;
}

/// An end point the fitted surfaces do not reach inside the grid's rectangle: where the
/// inversion ended (the rectangle's point whose end point came nearest) and how far it missed.
struct OutsideMap : std::domain_error {
  OutsideMap(const std::string& message, Eigen::Vector2d nearest_uv, Eigen::Vector2d nearest_xz)
      : std::domain_error(message), uv(nearest_uv), xz(nearest_xz) {}
  Eigen::Vector2d uv;  // (u, v) where the inversion ended
  Eigen::Vector2d xz;  // the surfaces' end point there
};

/// Inverts two fitted surfaces (8.4): finds (u, v) in the grid's rectangle with
/// (fx(u, v), fz(u, v)) = (x, z) by damped Newton iterations on the 2×2 system, started from
/// the grid point whose data (data_x, data_z) is nearest to (x, z) and clamped to the
/// rectangle (enlarged by 1e-9 of its size, so end points on the map's edge are found).
/// Throws std::invalid_argument when data_x and data_z do not share a grid, and OutsideMap
/// ("... lies outside the static map ...") when |residual| < tolerance is not reached inside the
/// rectangle.
Eigen::Vector2d invertSurfaces(const FittedSurface& fx, const FittedSurface& fz, const GridData& data_x,
                               const GridData& data_z, double x, double z, double tolerance = 1e-10);

}  // namespace cranesim
