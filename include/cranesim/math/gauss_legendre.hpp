#pragma once
// Gauss–Legendre quadrature on [0, 1]: ∫₀¹ f(ξ) dξ ≈ Σ w_i f(ξ_i), exact for
// polynomials of degree 2n − 1.

#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace cranesim {

inline constexpr int kMaxGaussPoints = 10;

struct GaussRule {
  int points = 0;
  std::array<double, kMaxGaussPoints> xi{}, weight{};
};

/// The n-point rule on [0, 1], 1 ≤ n ≤ kMaxGaussPoints: Newton iteration on the Legendre
/// polynomial P_n from the Chebyshev-like initial guesses.
inline GaussRule gaussLegendre(int n) {
  if (n < 1 || n > kMaxGaussPoints) throw std::invalid_argument("Gauss rule order must be 1…10");
  GaussRule rule;
  rule.points = n;
  for (int i = 0; i < n; ++i) {
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double dp = 0.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      const double pn = n == 1 ? x : p1;
      const double pn1 = n == 1 ? 1.0 : p0;
      dp = n * (x * pn - pn1) / (x * x - 1.0);
      const double dx = pn / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    rule.xi[i] = 0.5 * (1.0 - x);
    rule.weight[i] = 1.0 / ((1.0 - x * x) * dp * dp);  // 2/((1−x²)P'²) on [−1, 1], halved
  }
  return rule;
}

}  // namespace cranesim
