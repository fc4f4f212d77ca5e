#pragma once
// A rotation as a scene states it (a body's or a joint's `rotation`).

#include "cranesim/math/types.hpp"

namespace cranesim {

class YamlField;

/// `{axis: [..], angle: rad | angle_deg: deg}`, `{rotation_vector: [..]}` or `{matrix: [[..]x3]}`.
Mat3 readRotation(const YamlField& f);

}  // namespace cranesim
