#pragma once

#include <numbers>

namespace cranesim {

/// Scenes and targets give angles in degrees; the engine computes in radians.
inline constexpr double kRadiansPerDegree = std::numbers::pi / 180.0;

}  // namespace cranesim
