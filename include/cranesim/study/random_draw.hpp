#pragma once
// Random draws that depend only on (seed, case, parameter): a counter-based generator (the
// SplitMix64 finaliser over the combined key) instead of a stream, so that a case's values do
// not depend on which worker draws them or in which order. Normal deviates by Box–Muller,
// truncated normals by rejection; the same build gives the same bits on every machine.

#include <cstdint>

#include "cranesim/study/study.hpp"

namespace cranesim {

/// The draw of `parameter` for case `index` of a study seeded with `seed`.
double randomDraw(const RandomDistribution& distribution, std::uint64_t seed, std::uint64_t index,
                  std::uint64_t parameter);

/// The probability a normal(mean, std_dev) deviate falls in [low, high]: a truncated normal is
/// refused when it is too small for rejection to be quick (kMinTruncatedMass).
double normalMassWithin(const RandomDistribution& distribution);
inline constexpr double kMinTruncatedMass = 0.01;

}  // namespace cranesim
