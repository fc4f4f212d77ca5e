#pragma once
// Thesis 8.1.1: a cantilever bent by an end moment M = K·2πEI/L (8-1). The exact static
// shape (Euler elastica under a pure end moment; no axial force, so extension and shear do
// not enter) is a circular arc of curvature κ = 2πK/L. Shared by tests/test_end_moment.cpp
// and benchmarks/element_bending.cpp, which run configs/end_moment_<type>.yaml with the
// member's segment count and the load's scale (= K) replaced.

#include <cmath>
#include <numbers>
#include <string>

#include "cranesim/io/scene_reader.hpp"
#include "cranesim/math/rotation.hpp"
#include "cranesim/model/compile.hpp"

namespace cranesim::test {

/// The scene file's clamped beam along +x, curled towards +z by a torque about −y.
struct EndMomentArc {
  double L = 15.0;
  double K = 1.0;

  double curvature() const { return 2.0 * std::numbers::pi * K / L; }
  /// Tip position: x = sin(κL)/κ, z = (1 − cos(κL))/κ.
  Vec3 tip() const {
    const double k = curvature();
    if (k == 0.0) return {L, 0.0, 0.0};
    return {std::sin(k * L) / k, 0.0, (1.0 - std::cos(k * L)) / k};
  }
  /// Tip section frame: turned by κL about −y.
  Mat3 tipRotation() const { return axisAngle(-Vec3::UnitY(), curvature() * L); }
};

/// configs/end_moment_<type>.yaml ("timoshenko" or "spline_beam") with `segments` elements and K.
inline Scene endMomentScene(const std::string& scene_file, int segments, double K) {
  Scene scene = readScene(scene_file);
  scene.members.at(0).segments = segments;
  scene.loads.at(0).scale = Profile(ConstantProfile{K});
  return scene;
}

/// The exact arc of such a scene: L of its member, K the load's scale at t_start.
inline EndMomentArc endMomentArc(const Scene& scene) {
  const MemberSpec& beam = scene.members.at(0);
  return {(beam.end - beam.start).norm(), scene.loads.at(0).scale(scene.solver.t_start)};
}

struct ArcError {
  double tip = 0.0;       // ‖r_tip − r_exact‖ / L
  double rotation = 0.0;  // angle of R_exactᵀ R_tip, rad
};

/// Errors of the tip joint `beam.end` at coordinates q against the arc.
inline ArcError arcError(const Model& model, const VecX& q, const EndMomentArc& arc) {
  const Frame tip = model.jointFrame(q.data(), model.findJoint("beam.end"));
  return {(tip.r - arc.tip()).norm() / arc.L, rotationVector(arc.tipRotation().transpose() * tip.R).norm()};
}

}  // namespace cranesim::test
