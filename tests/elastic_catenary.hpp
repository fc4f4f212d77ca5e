#pragma once
// Irvine's elastic catenary for a cable hanging between two supports at equal height: the
// reference of the rope statics tests.

#include <cmath>

namespace cranesim::test {

struct ElasticCatenary {
  double H = 0.0;    // horizontal tension, N
  double sag = 0.0;  // mid-span sag, m
};

/// span, unstretched length L0, weight per unstretched length w (N/m), axial stiffness EA (N):
///   span = H L0/EA + (H/w)[asinh(V/H) − asinh((V − W)/H)],  V = W/2, W = w L0,
///   sag = W L0/(8 EA) + (H/w)(√(1 + (V/H)²) − 1).
inline ElasticCatenary elasticCatenary(double span, double L0, double w, double EA) {
  const double W = w * L0, V = W / 2.0;
  const auto spanOf = [&](double H) { return H * L0 / EA + H / w * (std::asinh(V / H) - std::asinh((V - W) / H)); };
  double H = 100.0;
  for (int it = 0; it < 100; ++it) {
    const double dH = 1e-6 * H;
    H -= (spanOf(H) - span) / ((spanOf(H + dH) - spanOf(H - dH)) / (2 * dH));
  }
  return {H, W * L0 / (8.0 * EA) + H / w * (std::sqrt(1.0 + (V / H) * (V / H)) - 1.0)};
}

}  // namespace cranesim::test
