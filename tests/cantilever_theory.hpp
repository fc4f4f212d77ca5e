#pragma once
// Analytic natural frequencies of a uniform clamped–free beam, the references of the modal
// tests: Euler–Bernoulli, and the Timoshenko frequency equation (shear and rotary inertia),
// which with an infinite shear stiffness is the Rayleigh beam (rotary inertia only).

#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <vector>

namespace cranesim::test {

/// β_n L of the clamped–free Euler–Bernoulli beam: roots of 1 + cos βL cosh βL = 0.
inline constexpr double kCantileverBetaL[] = {1.8751040687, 4.6940911330, 7.8547574382};

/// n-th (0-based, n < 3) Euler–Bernoulli bending frequency of a cantilever, Hz.
inline double eulerBernoulliCantileverFrequency(int n, double L, double EI, double rhoA) {
  const double bl = kCantileverBetaL[n];
  return bl * bl / (2.0 * std::numbers::pi * L * L) * std::sqrt(EI / rhoA);
}

/// The lowest `count` roots (Hz) of the Timoshenko clamped–free frequency equation for bending
/// stiffness EI, shear stiffness κGA, mass per length ρA and rotary inertia per length ρI
/// (below the cut-off frequency √(κGA/ρI), where the second wave number is real).
inline std::vector<double> timoshenkoCantileverFrequencies(double L, double EI, double kGA, double rhoA, double rhoI,
                                                           int count) {
  const auto det = [&](double w) {
    const double w2 = w * w;
    const double a4 = EI * kGA, a2 = w2 * (kGA * rhoI + rhoA * EI), a0 = rhoA * w2 * (rhoI * w2 - kGA);
    const double disc = std::sqrt(a2 * a2 - 4 * a4 * a0);
    const double a = std::sqrt((-a2 + disc) / (2 * a4)), b = std::sqrt((a2 + disc) / (2 * a4));
    const double ca = (kGA * a * a + rhoA * w2) / (kGA * a), db = (rhoA * w2 - kGA * b * b) / (kGA * b);
    // Basis (v, θ): (cosh ax, ca sinh ax), (sinh ax, ca cosh ax), (cos bx, db sin bx), (sin bx, −db cos bx)
    const double ch = std::cosh(a * L), sh = std::sinh(a * L), c = std::cos(b * L), s = std::sin(b * L);
    Eigen::Matrix4d D;
    D << 1, 0, 1, 0,                                                 // v(0)
        0, ca, 0, -db,                                               // θ(0)
        ca * a * ch, ca * a * sh, db * b * c, db * b * s,            // θ'(L)
        (a - ca) * sh, (a - ca) * ch, -(b + db) * s, (b + db) * c;   // v'(L) − θ(L)
    return D.determinant();
  };
  const double w_eb = 2.0 * std::numbers::pi * eulerBernoulliCantileverFrequency(0, L, EI, rhoA);
  const double step = 1e-3 * w_eb;
  std::vector<double> roots;
  double lo = 0.2 * w_eb, f_lo = det(lo);
  while (static_cast<int>(roots.size()) < count) {
    const double hi = lo + step, f_hi = det(hi);
    if (!std::isfinite(f_hi)) break;  // past the cut-off frequency
    if ((f_hi > 0) != (f_lo > 0)) {
      double a = lo, b = hi, f_a = f_lo;
      for (int it = 0; it < 100; ++it) {
        const double mid = 0.5 * (a + b), f_mid = det(mid);
        if ((f_mid > 0) == (f_a > 0)) a = mid, f_a = f_mid;
        else b = mid;
      }
      roots.push_back(0.5 * (a + b) / (2.0 * std::numbers::pi));
    }
    lo = hi, f_lo = f_hi;
  }
  return roots;
}

}  // namespace cranesim::test
