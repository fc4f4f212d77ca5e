#include "scene_path.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <sstream>

#include "cranesim/model/closest_name.hpp"
#include "yaml_field.hpp"

namespace cranesim {

std::vector<std::string> scenePathParts(const YamlField& entry, const std::string& path) {
  std::vector<std::string> parts;
  std::stringstream in(path);
  for (std::string part; std::getline(in, part, '.');) parts.push_back(part);
  if (parts.empty() || path.back() == '.' ||
      std::any_of(parts.begin(), parts.end(), [](const std::string& p) { return p.empty(); }))
    entry.fail(fmt::format("'{}' is not a path of names separated by dots", path));
  return parts;
}

std::vector<std::string> itemNames(const YAML::Node& list) {
  std::vector<std::string> names;
  for (const YAML::Node& item : list)
    names.push_back(item.IsMap() && item["name"] && item["name"].IsScalar() ? item["name"].as<std::string>() : "");
  return names;
}

int itemIndex(const YAML::Node& list, const std::string& name) {
  const std::vector<std::string> names = itemNames(list);
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : static_cast<int>(it - names.begin());
}

std::string noItemMessage(const std::string& list, const std::string& name, const YAML::Node& items) {
  const std::vector<std::string> names = itemNames(items);
  const std::string closest = closestName(name, names);
  return fmt::format("the base scene's {} have no item named '{}' ({}known: {})", list, name,
                     closest.empty() ? "" : fmt::format("did you mean '{}'?; ", closest), listedNames(names));
}

YAML::Node sceneNode(YAML::Node base, const YamlField& entry, const std::vector<std::string>& parts) {
  YAML::Node target = base;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    YAML::Node child;
    if (target.IsSequence()) {
      const int index = itemIndex(target, parts[k]);
      if (index < 0) entry.fail(noItemMessage(parts[k - 1], parts[k], target));
      child.reset(target[index]);
    } else if (target.IsMap()) {
      const YAML::Node& mapping = target;  // a const lookup adds no key
      if (!mapping[parts[k]])
        entry.fail(k == 0 ? fmt::format("the base scene has no '{}'", parts[k])
                          : fmt::format("the base scene has no field '{}' here", parts[k]));
      child.reset(mapping[parts[k]]);
    } else {
      entry.fail(fmt::format("'{}' is not a mapping in the base scene", parts[k - 1]));
    }
    target.reset(child);  // rebind: assigning a Node would overwrite what it refers to
  }
  return target;
}

}  // namespace cranesim
