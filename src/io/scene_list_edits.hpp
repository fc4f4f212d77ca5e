#pragma once
// List edits of a scene that starts from another (`base:`): items added to, inserted into and
// removed from the base's lists, named by the same dotted paths as `modify`.
//
//   remove: [loads.wind_gust, members.stay_2]     # <list>.<item name>
//   add:                                          # <list>: items appended at its end
//     members:
//       - {name: stay_3, type: rope, ...}
//     bodies.head.joints:                         # a list inside a named item
//       - {name: sheave_3, position: [0.4, 0, 0.2]}
//   insert_before:                                # <list>.<item name>: items placed before it
//     members.main_boom_5: [{name: insert_10m, ...}]
//   insert_after:                                 # <list>.<item name>: items placed after it
//     members.main_boom_4: [{name: insert_10m, ...}]
//
// They apply in that order (remove, add, insert_before, insert_after), then `modify`. An added
// item whose name its list already has is refused (change it with `modify`, or remove it first);
// so is a removal while anything in the composed scene still refers to the removed item.

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "yaml_field.hpp"

namespace cranesim {

/// The list-edit keys of a scene, besides `base` and `modify`.
inline const std::vector<std::string> kListEditKeys = {"remove", "add", "insert_before", "insert_after"};

/// An item taken out of the base by `remove`, and how other parts of a scene refer to it.
struct RemovedItem {
  YamlField entry;        // the `remove` entry, where a dangling reference is reported
  std::vector<std::string> list_path;  // where it was: members, bodies.head.joints
  std::string list;       // the list's key: members, joints
  std::string name;       // the item's name
  std::string reference;  // what refers to it: `name`, or `body.joint` for a joint of a body
  bool parts_refer = false;  // bodies and members: `name.joint` refers to it as well
};

/// Applies `scene`'s remove, add, insert_before and insert_after to `base`; fails at the entry.
std::vector<RemovedItem> applyListEdits(YAML::Node base, const YAML::Node& scene);

/// Fails at a removal when the composed scene `root` still refers to the removed item (and no
/// item of that name took its place).
void rejectDanglingReferences(const YAML::Node& root, const std::vector<RemovedItem>& removed);

}  // namespace cranesim
