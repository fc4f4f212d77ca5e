#pragma once

#include "cranesim/math/profile.hpp"
#include "yaml_field.hpp"

namespace cranesim {

/// A number (constant) or a mapping with `type:` one of constant, ramp, trapezoid,
/// cosine_step, cosine_full, tanh, table; optional `unit: deg` scales values to radians.
Profile readProfile(const YamlField& field);

}  // namespace cranesim
