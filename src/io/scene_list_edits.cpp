#include "scene_list_edits.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <set>

#include "cranesim/model/closest_name.hpp"
#include "scene_path.hpp"

namespace cranesim {
namespace {

/// Lists an `add` may create when the base has none.
const std::set<std::string> kNamedLists = {"bodies", "trusses", "members", "constraints", "loads", "joints"};

/// Keys whose values are words of the format (`type: rope`, `axis: y`), never references.
const std::set<std::string> kKeywordKeys = {"name",  "type", "interpolation", "unit",    "fidelity", "lacing",
                                            "element", "axis", "formulation", "integrator", "frame", "pose", "command"};

/// The list at `parts` of `base`; `create` makes a missing named list in a mapping.
YAML::Node listAt(YAML::Node base, const YamlField& entry, const std::vector<std::string>& parts, bool create) {
  const std::vector<std::string> parent_parts(parts.begin(), parts.end() - 1);
  YAML::Node parent = sceneNode(base, entry, parent_parts);
  const std::string& key = parts.back();
  if (parent.IsMap() && !static_cast<const YAML::Node&>(parent)[key]) {
    if (!create || !kNamedLists.count(key)) {
      const std::string closest = closestName(key, std::vector<std::string>(kNamedLists.begin(), kNamedLists.end()));
      entry.fail(fmt::format("the base scene has no list '{}' here{}", key,
                             closest.empty() ? "" : fmt::format(" (did you mean '{}'?)", closest)));
    }
    parent[key] = YAML::Node(YAML::NodeType::Sequence);
  }
  YAML::Node list = sceneNode(base, entry, parts);
  if (!list.IsSequence()) entry.fail(fmt::format("'{}' is not a list in the base scene", key));
  return list;
}

/// Places `items` (this scene's list at `field`) into `list` at `position`, after checking that
/// each is a named mapping whose name the list does not have yet.
void insertItems(YAML::Node list, std::size_t position, const YamlField& field, const std::string& list_name) {
  if (!field.isSequence()) field.fail("expected a list of items");
  std::vector<YAML::Node> tail;
  while (list.size() > position) {
    tail.push_back(list[list.size() - 1]);
    list.remove(list.size() - 1);
  }
  for (const YamlField& item : field.items()) {
    const std::string name = item.at("name").text();
    if (itemIndex(list, name) >= 0 || std::any_of(tail.begin(), tail.end(), [&](const YAML::Node& n) {
          return n["name"] && n["name"].IsScalar() && n["name"].as<std::string>() == name;
        }))
      item.at("name").fail(fmt::format("the base scene's {} already have an item named '{}': change it with modify, "
                                       "or remove it first", list_name, name));
    list.push_back(item.node());
  }
  for (auto it = tail.rbegin(); it != tail.rend(); ++it) list.push_back(*it);
}

std::vector<std::string> pathOf(const YamlField& entry, const std::string& path, std::size_t at_least,
                                const char* form) {
  std::vector<std::string> parts = scenePathParts(entry, path);
  if (parts.size() < at_least) entry.fail(fmt::format("expected {}", form));
  return parts;
}

/// The first scalar of `node` (at `path`) that refers to `item`, as "path ('value')", or "".
std::string referrer(const YAML::Node& node, const std::string& path, const RemovedItem& item) {
  if (node.IsScalar()) {
    const std::string value = node.Scalar();
    const bool refers = value == item.reference || (item.parts_refer && value.rfind(item.reference + ".", 0) == 0);
    return refers ? fmt::format("{} ('{}')", path, value) : "";
  }
  if (node.IsSequence())
    for (std::size_t k = 0; k < node.size(); ++k)
      if (std::string found = referrer(node[k], fmt::format("{}[{}]", path, k), item); !found.empty()) return found;
  if (node.IsMap())
    for (const auto& kv : node) {
      const std::string key = kv.first.as<std::string>();
      if (kKeywordKeys.count(key)) continue;
      if (std::string found = referrer(kv.second, path.empty() ? key : path + "." + key, item); !found.empty())
        return found;
    }
  return "";
}

}  // namespace

std::vector<RemovedItem> applyListEdits(YAML::Node base, const YAML::Node& scene) {
  std::vector<RemovedItem> removed;
  if (const YAML::Node remove = scene["remove"]) {
    const YamlField field(remove, "remove");
    if (!field.isSequence()) field.fail("expected a list of <list>.<item name>");
    for (const YamlField& entry : field.items()) {
      const std::vector<std::string> parts = pathOf(entry, entry.text(), 2, "<list>.<item name>");
      const std::vector<std::string> list_parts(parts.begin(), parts.end() - 1);
      YAML::Node list = listAt(base, entry, list_parts, false);
      const int index = itemIndex(list, parts.back());
      if (index < 0) entry.fail(noItemMessage(list_parts.back(), parts.back(), list));
      list.remove(index);
      RemovedItem item{entry, list_parts, list_parts.back(), parts.back(), parts.back()};
      if (item.list == "joints") item.reference = list_parts[list_parts.size() - 2] + "." + parts.back();
      item.parts_refer = item.list == "bodies" || item.list == "members";
      removed.push_back(std::move(item));
    }
  }
  if (const YAML::Node add = scene["add"]) {
    const YamlField field(add, "add");
    if (!field.isMap()) field.fail("expected a mapping of <list>: [items]");
    field.rejectDuplicateKeys();
    for (const std::string& path : field.keys()) {
      const YamlField items = field.at(path);
      const std::vector<std::string> parts = pathOf(items, path, 1, "<list>");
      YAML::Node list = listAt(base, items, parts, true);
      insertItems(list, list.size(), items, parts.back());
    }
  }
  for (const char* key : {"insert_before", "insert_after"}) {
    const YAML::Node insert = scene[key];
    if (!insert) continue;
    const YamlField field(insert, key);
    if (!field.isMap()) field.fail("expected a mapping of <list>.<item name>: [items]");
    field.rejectDuplicateKeys();
    for (const std::string& path : field.keys()) {
      const YamlField items = field.at(path);
      const std::vector<std::string> parts = pathOf(items, path, 2, "<list>.<item name> of the item to insert next to");
      const std::vector<std::string> list_parts(parts.begin(), parts.end() - 1);
      YAML::Node list = listAt(base, items, list_parts, false);
      const int index = itemIndex(list, parts.back());
      if (index < 0) items.fail(noItemMessage(list_parts.back(), parts.back(), list));
      insertItems(list, index + (std::string(key) == "insert_after" ? 1 : 0), items, list_parts.back());
    }
  }
  return removed;
}

void rejectDanglingReferences(const YAML::Node& root, const std::vector<RemovedItem>& removed) {
  for (const RemovedItem& item : removed) {
    if (itemIndex(sceneNode(root, item.entry, item.list_path), item.name) >= 0) continue;  // replaced
    const std::string found = referrer(root, "", item);
    if (!found.empty())
      item.entry.fail(fmt::format("cannot remove '{}' from the {}: {} refers to it; remove or change that too",
                                  item.name, item.list, found));
  }
}

}  // namespace cranesim
