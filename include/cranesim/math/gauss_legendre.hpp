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

namespace detail {

/// The n-point rule on [0, 1]: Newton iteration on the Legendre polynomial P_n from the
/// Chebyshev-like initial guesses.
inline GaussRule computeGaussLegendre(int n) {
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

}  // namespace detail

/// The n-point rule on [0, 1], 1 ≤ n ≤ kMaxGaussPoints, computed once per program: element
/// kernels ask for their rule at every evaluation.
inline const GaussRule& gaussLegendre(int n) {
  static const std::array<GaussRule, kMaxGaussPoints> rules = [] {
    std::array<GaussRule, kMaxGaussPoints> all;
    for (int k = 1; k <= kMaxGaussPoints; ++k) all[k - 1] = detail::computeGaussLegendre(k);
    return all;
  }();
  if (n < 1 || n > kMaxGaussPoints) throw std::invalid_argument("Gauss rule order must be 1…10");
  return rules[n - 1];
}

}  // namespace cranesim
