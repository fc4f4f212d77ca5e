#pragma once
// Cubic Hermite shape functions (A-9..A-11) on ξ ∈ [0, 1] for a segment of length L:
// r(ξ) = N0¹ r¹ + N1¹ r'¹ + N0² r² + N1² r'², with r' = dr/ds, s = ξ L. Derivatives are
// with respect to s.

#include <array>

namespace cranesim {

struct HermiteBasis {
  std::array<double, 4> N, dN, ddN;  // order: N0¹, N1¹, N0², N1²
};

inline HermiteBasis hermiteBasis(double xi, double L) {
  const double x = xi, x2 = x * x, x3 = x2 * x;
  HermiteBasis b;
  b.N = {1.0 - 3.0 * x2 + 2.0 * x3, L * (x - 2.0 * x2 + x3), 3.0 * x2 - 2.0 * x3, L * (x3 - x2)};
  b.dN = {(-6.0 * x + 6.0 * x2) / L, 1.0 - 4.0 * x + 3.0 * x2, (6.0 * x - 6.0 * x2) / L, 3.0 * x2 - 2.0 * x};
  b.ddN = {(-6.0 + 12.0 * x) / (L * L), (-4.0 + 6.0 * x) / L, (6.0 - 12.0 * x) / (L * L), (6.0 * x - 2.0) / L};
  return b;
}

/// ∂/∂L of the functions above at fixed ξ: N1 scale with L, dN0 and dN2 with 1/L, ddN0 and
/// ddN2 with 1/L², ddN1 and ddN3 with 1/L.
inline HermiteBasis hermiteBasisLengthDerivative(double xi, double L) {
  const HermiteBasis b = hermiteBasis(xi, L);
  HermiteBasis d;
  d.N = {0.0, b.N[1] / L, 0.0, b.N[3] / L};
  d.dN = {-b.dN[0] / L, 0.0, -b.dN[2] / L, 0.0};
  d.ddN = {-2.0 * b.ddN[0] / L, -b.ddN[1] / L, -2.0 * b.ddN[2] / L, -b.ddN[3] / L};
  return d;
}

}  // namespace cranesim
