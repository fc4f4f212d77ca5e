#include "cranesim/study/random_draw.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace cranesim {
namespace {

std::uint64_t splitMix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// The `counter`-th uniform deviate in (0, 1) of the key, from 53 random bits.
double uniform(std::uint64_t seed, std::uint64_t index, std::uint64_t parameter, std::uint64_t counter) {
  const std::uint64_t bits = splitMix(splitMix(splitMix(splitMix(seed) ^ index) ^ parameter) ^ counter);
  return (static_cast<double>(bits >> 11) + 0.5) * 0x1.0p-53;
}

/// Box–Muller from the deviates `counter` and `counter + 1`.
double standardNormal(std::uint64_t seed, std::uint64_t index, std::uint64_t parameter, std::uint64_t counter) {
  const double u1 = uniform(seed, index, parameter, counter), u2 = uniform(seed, index, parameter, counter + 1);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

/// Rejection gives up after this many tries: with at least kMinTruncatedMass of the
/// probability inside, the chance of that is below 0.99¹⁰⁰⁰⁰ ≈ 1e-44.
constexpr std::uint64_t kMaxRejections = 10000;

}  // namespace

double normalMassWithin(const RandomDistribution& d) {
  const auto cdf = [&](double x) { return 0.5 * std::erfc(-(x - d.mean) / (d.std_dev * std::numbers::sqrt2)); };
  return cdf(d.high) - cdf(d.low);
}

double randomDraw(const RandomDistribution& d, std::uint64_t seed, std::uint64_t index, std::uint64_t parameter) {
  switch (d.kind) {
    case RandomDistribution::Kind::Uniform:
      return d.low + (d.high - d.low) * uniform(seed, index, parameter, 0);
    case RandomDistribution::Kind::Normal:
      return d.mean + d.std_dev * standardNormal(seed, index, parameter, 0);
    case RandomDistribution::Kind::TruncatedNormal:
      for (std::uint64_t k = 0; k < kMaxRejections; ++k) {
        const double x = d.mean + d.std_dev * standardNormal(seed, index, parameter, 2 * k);
        if (x >= d.low && x <= d.high) return x;
      }
      throw std::runtime_error("truncated normal: no draw inside the interval");
  }
  return 0.0;
}

}  // namespace cranesim
