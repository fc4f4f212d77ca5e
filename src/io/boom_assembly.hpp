#pragma once
// A boom assembled from its sections (`booms:`, docs/scene-format.md "Booms assembled from
// sections"): the tool places a foot piece, inserts and a top piece of the scene's truss types
// end to end along the boom axis at the boom angle (or the angle a luffing rope's length gives),
// carries the head body with its joints along, draws the luffing line and the hoist rope with
// its load, and writes them as the members, bodies and constraints a scene would draw by hand.
// The scene reader then reads the expanded scene as any other.

#include <yaml-cpp/yaml.h>

#include <optional>

#include "cranesim/model/stated_equilibrium.hpp"

namespace cranesim {

/// The scene's booms expanded, and the figures a boom's `equilibrium` states
/// (its `drawn_at` left to the scene reader, which knows how to read the scene again).
struct ExpandedBooms {
  YAML::Node root;
  std::optional<StatedEquilibrium> stated;
};

/// `root` with every boom under `booms:` expanded into `members` (one truss member per section,
/// the ties and ropes), `bodies` (its head; the load placed at the hook), `constraints` (the foot
/// pin, the splices, the head, the rigging's joints) and `trusses` (a type used at another length
/// than its own). `root` is left as it is, so a scene composed on this
/// one still edits its `booms:`; without `booms:` the result is `root`. The expanded items keep
/// the nodes the scene wrote (names, types, the head's fields), so errors found in them later
/// name their lines. A boom whose equilibrium is stated is drawn at a first angle and hoist rope
/// length from its rigid geometry: its stated boom angle, or the angle that hangs the hook at the
/// stated radius from the boom's foot; the rope that hangs the hook at the stated height. Throws
/// SceneError naming the boom's field.
ExpandedBooms expandBooms(const YAML::Node& root);

}  // namespace cranesim
