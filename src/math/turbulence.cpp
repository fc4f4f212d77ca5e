#include "cranesim/math/turbulence.hpp"

#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <stdexcept>

namespace cranesim {

double kaimalSpectrum(double frequency, double sigma, double length_scale, double mean_speed) {
  const double time_scale = length_scale / mean_speed;
  return sigma * sigma * 4.0 * time_scale / std::pow(1.0 + 6.0 * frequency * time_scale, 5.0 / 3.0);
}

TurbulenceSeries::TurbulenceSeries(double sigma, double length_scale, double mean_speed, double period,
                                   double frequency_max, std::uint64_t seed)
    : period_(period) {
  const int harmonics = static_cast<int>(std::floor(frequency_max * period));
  if (harmonics < 1) throw std::invalid_argument("turbulence: the period must exceed 1/frequency_max");
  std::mt19937_64 random(seed);
  std::vector<double> phases(harmonics);
  double variance = 0.0;
  for (int k = 1; k <= harmonics; ++k) {
    const double f = k / period;
    frequencies_.push_back(f);
    amplitudes_.push_back(std::sqrt(2.0 * kaimalSpectrum(f, 1.0, length_scale, mean_speed) / period));
    variance += 0.5 * amplitudes_.back() * amplitudes_.back();
    phases[k - 1] = 2.0 * std::numbers::pi * static_cast<double>(random() >> 11) * 0x1.0p-53;
  }
  for (double& a : amplitudes_) a *= sigma / std::sqrt(variance);

  const int samples = static_cast<int>(std::ceil(8.0 * frequency_max * period));
  step_ = period / samples;
  values_.assign(samples, 0.0);
  slopes_.assign(samples, 0.0);
  for (int k = 0; k < harmonics; ++k) {
    const double omega = 2.0 * std::numbers::pi * frequencies_[k];
    // e^{i(ω t_j + θ)} by repeated rotation, renewed every 256 samples against drift.
    const std::complex<double> turn = std::polar(1.0, omega * step_);
    std::complex<double> z;
    for (int j = 0; j < samples; ++j) {
      z = j % 256 == 0 ? std::polar(1.0, omega * j * step_ + phases[k]) : z * turn;
      values_[j] += amplitudes_[k] * z.real();
      slopes_[j] -= amplitudes_[k] * omega * z.imag();
    }
  }
}

double TurbulenceSeries::operator()(double t) const {
  const double tau = t - period_ * std::floor(t / period_);
  const int samples = static_cast<int>(values_.size());
  const int j = std::min(static_cast<int>(tau / step_), samples - 1);
  const int next = (j + 1) % samples;
  const double s = tau / step_ - j, s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * values_[j] + (s3 - 2 * s2 + s) * step_ * slopes_[j] +
         (-2 * s3 + 3 * s2) * values_[next] + (s3 - s2) * step_ * slopes_[next];
}

}  // namespace cranesim
