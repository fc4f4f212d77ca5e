#pragma once
// Helpers shared by the tests: load scenes from configs/ or from inline YAML.

#include <string>

#include "cranesim/io/scene_reader.hpp"
#include "cranesim/model/compile.hpp"

namespace cranesim::test {

inline std::string configPath(const std::string& name) { return std::string(CRANESIM_SOURCE_DIR) + "/configs/" + name; }

inline Model loadConfig(const std::string& name) { return compileModel(readScene(configPath(name))); }

inline Model loadYaml(const std::string& yaml) { return compileModel(parseScene(yaml, "<test>")); }

}  // namespace cranesim::test
