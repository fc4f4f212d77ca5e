#pragma once
// Scene composition: a scene may start from another one.
//
//   base: crane.yaml                 # path relative to this file
//   modify:                          # set single fields of the base scene
//     members.hoist_rope.length: {type: trapezoid, from: 53.9937, distance: -20, ...}
//     constraints.slewing.drive: {type: trapezoid, from: 0, distance: 90, unit: deg, ...}
//     solver.t_end: 60
//   solver: {...}                    # any other top-level key replaces the base's
//
// A `modify` key is `<list>.<item name>.<field>[.<field>…]` for the named items of a top-level
// list (bodies, trusses, members, constraints, loads) or `<mapping>.<field>[.<field>…]` for a
// top-level mapping (solver, output, ground). `add`, `insert_before`, `insert_after` and `remove`
// edit the base's lists first (scene_list_edits.hpp). The base is validated on its own first, so
// an error in it names the base file.

#include <yaml-cpp/yaml.h>

#include <functional>
#include <string>

#include "cranesim/model/scene.hpp"

namespace cranesim {

struct ComposedScene {
  YAML::Node root;   // the scene with `base` and `modify` applied, merge keys expanded
  std::string text;  // this file's text followed by its bases' texts (stored in the results)
};

class YamlField;

/// Sets `base`[key] = value for one `modify` entry `key`; fails at `entry` when the base lacks
/// the item or a field on the way, and with `require_field` also when it lacks the field itself.
void modifyScene(YAML::Node base, const YamlField& entry, const std::string& key, const YAML::Node& value,
                 bool require_field = false);

/// The field `key` (a `modify` key) of `base`; fails at `entry` as modifyScene does, and when the
/// base lacks the field itself.
YAML::Node sceneField(YAML::Node base, const YamlField& entry, const std::string& key);

/// Reads a composed scene, throwing SceneError on bad content (the scene reader).
using BaseValidator = std::function<void(const ComposedScene& base, const std::string& base_path)>;

/// Parses `text` (the scene file at `path`) and applies `base` and `modify`; every base scene is
/// checked by `validate_base` before it is modified. Throws SceneError.
ComposedScene composeScene(const std::string& text, const std::string& path, const BaseValidator& validate_base);

/// Reads and validates a composed scene as readScene does (scene_reader.cpp). Throws SceneError.
Scene sceneFromComposed(const ComposedScene& composed, const std::string& path);

}  // namespace cranesim
