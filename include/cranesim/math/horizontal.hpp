#pragma once
// A vector's reach in the horizontal plane (z is up): the sway of a load under its sheave, the
// radius of a point from the slewing axis.

#include <cmath>

#include "cranesim/math/types.hpp"

namespace cranesim {

/// |(r_x, r_y)|.
inline double horizontal(const Vec3& r) { return std::hypot(r.x(), r.y()); }

}  // namespace cranesim
