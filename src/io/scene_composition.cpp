#include "scene_composition.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <vector>

#include "bounded_yaml.hpp"
#include "cranesim/model/source_location.hpp"
#include "yaml_field.hpp"

namespace cranesim {
namespace {

constexpr int kMaxBaseDepth = 8;

std::string keysOf(const YAML::Node& mapping) {
  std::string keys;
  for (const auto& kv : mapping) keys += (keys.empty() ? "" : ", ") + kv.first.as<std::string>();
  return keys;
}

std::vector<std::string> splitDots(const std::string& key) {
  std::vector<std::string> parts;
  std::stringstream in(key);
  for (std::string part; std::getline(in, part, '.');) parts.push_back(part);
  return parts;
}

/// The mapping that holds the last part of `key` in `base`, and that part.
std::pair<YAML::Node, std::string> fieldParent(YAML::Node base, const YamlField& entry, const std::string& key) {
  const std::vector<std::string> parts = splitDots(key);
  if (parts.size() < 2 || std::any_of(parts.begin(), parts.end(), [](const std::string& p) { return p.empty(); }))
    entry.fail("expected <list>.<item name>.<field> or <mapping>.<field>");
  YAML::Node target = base[parts[0]];
  if (!target) entry.fail(fmt::format("the base scene has no '{}'", parts[0]));
  std::size_t next = 1;
  if (target.IsSequence()) {
    if (parts.size() < 3) entry.fail(fmt::format("name the item of '{}' and the field to set: {}.<name>.<field>", parts[0], parts[0]));
    YAML::Node item;
    bool found = false;
    std::string known;
    for (YAML::Node candidate : target) {
      const std::string name = candidate.IsMap() && candidate["name"] ? candidate["name"].as<std::string>() : "";
      known += (known.empty() ? "" : ", ") + name;
      if (name == parts[1] && !found) item.reset(candidate), found = true;
    }
    if (!found) entry.fail(fmt::format("the base scene's {} have no item named '{}' (known: {})", parts[0], parts[1], known));
    target.reset(item);  // rebind: assigning a Node would overwrite the list with the item
    next = 2;
  }
  for (; next + 1 < parts.size(); ++next) {
    if (!target.IsMap()) entry.fail(fmt::format("'{}' is not a mapping in the base scene", parts[next - 1]));
    YAML::Node child = target[parts[next]];
    if (!child) entry.fail(fmt::format("the base scene has no field '{}' here", parts[next]));
    target.reset(child);
  }
  if (!target.IsMap()) entry.fail(fmt::format("'{}' is not a mapping in the base scene", parts[next - 1]));
  return {target, parts.back()};
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
    if (out.root["modify"]) YamlField(out.root["modify"], "modify").fail("'modify' needs a 'base' scene");
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
    if (key != "base" && key != "modify") base.root[key] = kv.second;
  }
  if (const YAML::Node modify = out.root["modify"]) {
    const YamlField field(modify, "modify");
    if (!modify.IsMap()) field.fail("expected a mapping of <path>: <value>");
    field.rejectDuplicateKeys();
    for (const auto& kv : modify) {
      const std::string key = kv.first.as<std::string>();
      modifyScene(base.root, YamlField(kv.second, "modify." + key), key, kv.second);
    }
  }
  out.root.reset(base.root);
  out.text = fmt::format("{}\n# ---- base scene: {} ----\n{}", text, base_path.string(), base.text);
  return out;
}

}  // namespace

ComposedScene composeScene(const std::string& text, const std::string& path, const BaseValidator& validate_base) {
  return compose(text, path, validate_base, 0);
}

}  // namespace cranesim
