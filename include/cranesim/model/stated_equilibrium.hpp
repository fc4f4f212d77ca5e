#pragma once
// A boom drawn where its static equilibrium meets stated figures (`booms: equilibrium`,
// docs/scene-format.md "Booms assembled from sections"): the hook's radius from the slewing axis
// or the boom angle the loaded structure takes, met by the boom angle the boom is drawn at
// (`angle_deg: from_equilibrium`); the hook's height, met by the hoist rope's unstretched length
// (`hoist.hanging_length: from_equilibrium`). The scene reader draws the boom at a first angle
// and length and says how to draw it at any other; the search itself needs the statics
// (crane/stated_equilibrium_search.hpp).

#include <functional>
#include <optional>
#include <string>

#include "cranesim/model/source_location.hpp"

namespace cranesim {

struct Scene;

/// The two things a stated equilibrium draws a boom by.
struct BoomDrawing {
  double angle_deg = 0.0;       // the boom angle above the horizontal
  double hanging_length = 0.0;  // m: the hoist rope's unstretched length
};

struct StatedEquilibrium {
  enum class Figure { HookRadius, BoomAngle };
  struct Stated {
    double value = 0.0;     // m or deg
    SourceLocation where;   // its field
  };
  /// The figure the boom angle is found for, with which of the two it is.
  std::optional<Stated> angle_figure;
  Figure figure = Figure::HookRadius;
  /// The hook's height (m) the hoist rope's length is found for.
  std::optional<Stated> hook_height;
  std::string boom;    // the boom under booms: whose drawing is searched
  BoomDrawing drawn;   // what the scene is drawn at: the search's start
  /// The same scene with the boom drawn at `drawing` (its figures no longer stated); of the two,
  /// only what a figure is stated for changes.
  std::function<Scene(const BoomDrawing& drawing)> drawn_at;
};

}  // namespace cranesim
