#include "cranesim/math/profile.hpp"

namespace cranesim {

std::vector<double> splineSlopes(const std::vector<double>& t, const std::vector<double>& y,
                                 bool zero_end_slopes) {
  // Continuity of the second derivative at interior knots gives a tridiagonal system for the
  // knot slopes s_i: h_i s_{i-1} + 2(h_{i-1} + h_i) s_i + h_{i-1} s_{i+1} = 3(h_i d_{i-1} + h_{i-1} d_i),
  // with d_i the secant slopes. Ends: s = 0 (clamped) or 2 s_0 + s_1 = 3 d_0 (natural).
  const std::size_t n = t.size();
  std::vector<double> h(n - 1), d(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    h[i] = t[i + 1] - t[i];
    d[i] = (y[i + 1] - y[i]) / h[i];
  }
  std::vector<double> lower(n, 0.0), diag(n, 1.0), upper(n, 0.0), rhs(n, 0.0);
  if (!zero_end_slopes) {
    diag[0] = 2.0, upper[0] = 1.0, rhs[0] = 3.0 * d[0];
    lower[n - 1] = 1.0, diag[n - 1] = 2.0, rhs[n - 1] = 3.0 * d[n - 2];
  }
  for (std::size_t i = 1; i + 1 < n; ++i) {
    lower[i] = h[i];
    diag[i] = 2.0 * (h[i - 1] + h[i]);
    upper[i] = h[i - 1];
    rhs[i] = 3.0 * (h[i] * d[i - 1] + h[i - 1] * d[i]);
  }
  for (std::size_t i = 1; i < n; ++i) {  // Thomas algorithm
    const double w = lower[i] / diag[i - 1];
    diag[i] -= w * upper[i - 1];
    rhs[i] -= w * rhs[i - 1];
  }
  std::vector<double> s(n);
  s[n - 1] = rhs[n - 1] / diag[n - 1];
  for (std::size_t i = n - 1; i-- > 0;) s[i] = (rhs[i] - upper[i] * s[i + 1]) / diag[i];
  return s;
}

std::vector<double> Profile::breakpoints() const {
  struct Visitor {
    std::vector<double> operator()(const ConstantProfile&) const { return {}; }
    std::vector<double> operator()(const RampProfile& p) const { return {p.t_start}; }
    std::vector<double> operator()(const TrapezoidProfile& p) const {
      return {p.t_start, p.t_start + p.t_accel, p.t_start + p.duration - p.t_decel, p.t_start + p.duration};
    }
    std::vector<double> operator()(const CosineStepProfile& p) const { return {p.t_start, p.t_end}; }
    std::vector<double> operator()(const CosineFullProfile& p) const { return {p.t_start, p.t_end}; }
    std::vector<double> operator()(const TanhProfile&) const { return {}; }
    std::vector<double> operator()(const InputProfile&) const { return {}; }  // commands stop the integrator, never restart it
    std::vector<double> operator()(const TableProfile& p) const {
      if (p.interpolation == Interpolation::Cubic) return {p.t.front(), p.t.back()};
      return p.t;  // a linear table's slope, a step table's value jumps at every knot
    }
  };
  return std::visit(Visitor{}, kind_);
}

}  // namespace cranesim
