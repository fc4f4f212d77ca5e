#pragma once
// Turbulence of the wind speed at a point: a stationary Gaussian-like series synthesised from
// the Kaimal spectrum as a sum of cosines with seeded random phases (the spectral representation
// method), sampled once and interpolated in time.

#include <cstdint>
#include <vector>

namespace cranesim {

/// The one-sided Kaimal spectrum of the longitudinal wind speed (IEC 61400-1, Annex C),
///   S(f) = σ² (4 L/V) / (1 + 6 f L/V)^(5/3),   m²/s² per Hz,
/// with standard deviation σ, integral length scale L and mean speed V. Its integral over
/// f ∈ [0, ∞) is σ²; above f ≈ V/L it falls as f^(−5/3) (the inertial range).
double kaimalSpectrum(double frequency, double sigma, double length_scale, double mean_speed);

/// u(t) = Σ_k a_k cos(2π f_k t + θ_k) at the harmonics f_k = k/T, k = 1 … ⌊f_max T⌋, of the
/// period T, with a_k ∝ √(2 S(f_k)/T) scaled so that the series' variance over a period is σ²
/// exactly (the spectrum's parts below 1/T and above f_max are left out), and phases θ_k
/// uniform in [0, 2π) from a 64-bit Mersenne twister seeded with `seed` (the same series on
/// every platform). Sampled with its exact derivative at 8 points per period of f_max and
/// interpolated by cubic Hermite polynomials: continuous with its first derivative (C¹), and
/// periodic with period T.
class TurbulenceSeries {
 public:
  TurbulenceSeries(double sigma, double length_scale, double mean_speed, double period, double frequency_max,
                   std::uint64_t seed);

  /// u(t), m/s.
  double operator()(double t) const;
  double period() const { return period_; }
  double sampleInterval() const { return step_; }
  /// The harmonics' frequencies f_k (Hz) and amplitudes a_k (m/s).
  const std::vector<double>& frequencies() const { return frequencies_; }
  const std::vector<double>& amplitudes() const { return amplitudes_; }

 private:
  double period_ = 0.0, step_ = 0.0;
  std::vector<double> frequencies_, amplitudes_;
  std::vector<double> values_, slopes_;  // u and du/dt at t = j · step_, j = 0 … samples − 1
};

}  // namespace cranesim
