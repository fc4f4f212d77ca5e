#pragma once
// A member drawn along a circular arc (docs/scene-format.md): from its start to its end about a
// centre, turning about an axis (by default the normal of the plane of start, centre and end,
// the shorter way round). Its nodes lie on the arc at equal angles; each node frame has its x
// axis along the arc's tangent, its z axis along the arc's axis and its y axis towards the
// centre, so an arc bends about its sections' z axes in its plane. Straight elements join the
// nodes (their chords); their section frames differ from the node frames by half a segment's
// turn (elements/rotated_ends.hpp), so a polygon of straight Timoshenko elements converges to the
// curved beam as the segments shrink (second order in the segment's angle).

#include <vector>

#include "cranesim/math/types.hpp"
#include "cranesim/model/source_location.hpp"

namespace cranesim {

struct ArcSpec {
  Vec3 centre = Vec3::Zero();
  Vec3 axis = Vec3::Zero();  // zero: the normal of start, centre and end (the shorter arc)
  SourceLocation where;
};

struct ArcNodes {
  std::vector<Vec3> positions;
  std::vector<Mat3> frames;  // node axes: x tangent, y towards the centre, z the arc's axis
  double radius = 0.0, angle = 0.0;  // m, rad (0 < angle < 2π)
};

/// The `segments` + 1 nodes of the arc from `start` to `end`. Throws SceneError at arc.where when
/// the ends lie at different distances from the centre (beyond 1e-6 of the radius) or off the
/// plane normal to the axis, or when start, centre and end lie in one line and no axis is given.
ArcNodes arcNodes(const Vec3& start, const Vec3& end, const ArcSpec& arc, int segments);

}  // namespace cranesim
