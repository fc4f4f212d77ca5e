#pragma once
// A boom drawn at the angle whose static equilibrium meets a stated figure
// (`booms: angle_deg: from_equilibrium`, docs/scene-format.md "Booms assembled from sections"):
// the hook's radius from the slewing axis, or the boom angle the loaded structure takes. The
// scene reader draws the boom at a first angle and says how to draw it at any other; the search
// for the angle itself needs the statics (crane/stated_equilibrium_search.hpp).

#include <functional>
#include <string>

#include "cranesim/model/source_location.hpp"

namespace cranesim {

struct Scene;

struct StatedEquilibrium {
  enum class Figure { HookRadius, BoomAngle };
  Figure figure = Figure::HookRadius;
  double value = 0.0;      // m (hook radius) or deg (boom angle)
  std::string boom;        // the boom under booms: whose angle is searched
  double drawn_angle_deg = 0.0;  // the angle the scene is drawn at: the search's start
  SourceLocation where;    // the stated figure's field
  /// The same scene with the boom drawn at `angle_deg` (its figure no longer stated).
  std::function<Scene(double angle_deg)> drawn_at;
};

}  // namespace cranesim
