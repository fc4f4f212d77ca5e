#pragma once
// The path of a reeved rope (`element: reeved`, docs/scene-format.md#reeved-ropes): a `path`
// from the winch over sheaves to the dead end, or `falls: n` between a head and a hook block.

#include "cranesim/elements/reeved_rope.hpp"
#include "cranesim/model/scene.hpp"
#include "yaml_field.hpp"

namespace cranesim {

/// The keys of a reeved rope member besides name, type, element, section, material, length
/// and damping.
inline constexpr const char* kReevingKeys[] = {"path", "falls", "winch", "head", "hook", "efficiency", "speed_band",
                                                  "pre_sliding", "fidelity", "elements_per_part"};

/// Reads the path of the rope member `f` (its joints are resolved when the scene is placed).
ReevingSpec readReeving(const YamlField& f);

}  // namespace cranesim
