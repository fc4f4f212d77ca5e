#include "scene_composition.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <vector>

#include "bounded_yaml.hpp"
#include "cranesim/model/source_location.hpp"
#include "scene_list_edits.hpp"
#include "scene_path.hpp"
#include "yaml_field.hpp"

namespace cranesim {
namespace {

constexpr int kMaxBaseDepth = 8;

std::string keysOf(const YAML::Node& mapping) {
  std::string keys;
  for (const auto& kv : mapping) keys += (keys.empty() ? "" : ", ") + kv.first.as<std::string>();
  return keys;
}

/// The mapping that holds the last part of `key` in `base`, and that part.
std::pair<YAML::Node, std::string> fieldParent(YAML::Node base, const YamlField& entry, const std::string& key) {
  std::vector<std::string> parts = scenePathParts(entry, key);
  if (parts.size() < 2) entry.fail("expected <list>.<item name>.<field> or <mapping>.<field>");
  const std::string field = parts.back();
  parts.pop_back();
  const YAML::Node parent = sceneNode(base, entry, parts);
  if (parent.IsSequence())
    entry.fail(fmt::format("name the item of '{}' and the field to set: {}.<name>.<field>", parts.back(), parts.back()));
  if (!parent.IsMap()) entry.fail(fmt::format("'{}' is not a mapping in the base scene", parts.back()));
  return {parent, field};
}

}  // namespace

void modifyScene(YAML::Node base, const YamlField& entry, const std::string& key, const YAML::Node& value,
                 bool require_field) {
  auto [parent, field] = fieldParent(base, entry, key);
  if (require_field && !static_cast<const YAML::Node&>(parent)[field])
    entry.fail(fmt::format("the base scene has no field '{}' here (known: {})", field, keysOf(parent)));
  parent[field] = value;
}

YAML::Node sceneField(YAML::Node base, const YamlField& entry, const std::string& key) {
  const auto [parent, field] = fieldParent(base, entry, key);
  const YAML::Node value = static_cast<const YAML::Node&>(parent)[field];
  if (!value) entry.fail(fmt::format("the base scene has no field '{}' here (known: {})", field, keysOf(parent)));
  return value;
}

namespace {

bool isCompositionKey(const std::string& key) {
  return key == "base" || key == "modify" ||
         std::find(kListEditKeys.begin(), kListEditKeys.end(), key) != kListEditKeys.end();
}

ComposedScene compose(const std::string& text, const std::string& path, const BaseValidator& validate, int depth) {
  ComposedScene out;
  out.text = text;
  out.root = loadBoundedYaml(text);
  try {
    applyMergeKeys(out.root);
  } catch (const YAML::Exception& e) {
    throw SceneError({"<document>", e.mark.line + 1, e.mark.column + 1}, "not valid YAML: " + e.msg);
  }
  if (!out.root.IsMap()) return out;  // the scene reader reports it
  if (!out.root["base"]) {
    for (const std::string key : {"modify", "remove", "add", "insert_before", "insert_after"})
      if (out.root[key]) YamlField(out.root[key], key).fail(fmt::format("'{}' needs a 'base' scene", key));
    return out;
  }
  // The base takes this file's keys one by one, so a duplicate key would win silently.
  YamlField(out.root, "").rejectDuplicateKeys();
  const YamlField base_field(out.root["base"], "base");
  if (depth >= kMaxBaseDepth) base_field.fail(fmt::format("more than {} nested base scenes (a cycle?)", kMaxBaseDepth));
  const std::filesystem::path base_path = std::filesystem::path(path).parent_path() / base_field.text();
  const std::string base_text = readInputFile(base_path.string(), "base scene", base_field.where());
  const auto composeBase = [&] {
    try {
      ComposedScene composed = compose(base_text, base_path.string(), validate, depth + 1);
      validate(composed, base_path.string());  // the base alone: its errors name its file
      return composed;
    } catch (const SceneError& e) {
      throw SceneError(base_field.where(), fmt::format("in the base scene {}: {}", base_path.string(), e.what()));
    }
  };
  ComposedScene base = composeBase();
  for (const auto& kv : out.root) {
    const std::string key = kv.first.as<std::string>();
    if (!isCompositionKey(key)) base.root[key] = kv.second;
  }
  const std::vector<RemovedItem> removed = applyListEdits(base.root, out.root);
  if (const YAML::Node modify = out.root["modify"]) {
    const YamlField field(modify, "modify");
    if (!modify.IsMap()) field.fail("expected a mapping of <path>: <value>");
    field.rejectDuplicateKeys();
    for (const auto& kv : modify) {
      const std::string key = kv.first.as<std::string>();
      modifyScene(base.root, YamlField(kv.second, "modify." + key), key, kv.second);
    }
  }
  rejectDanglingReferences(base.root, removed);
  out.root.reset(base.root);
  out.text = fmt::format("{}\n# ---- base scene: {} ----\n{}", text, base_path.string(), base.text);
  return out;
}

}  // namespace

ComposedScene composeScene(const std::string& text, const std::string& path, const BaseValidator& validate_base) {
  return compose(text, path, validate_base, 0);
}

}  // namespace cranesim
