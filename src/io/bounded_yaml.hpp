#pragma once
// Input that no valid scene or target comes near is refused before it is read or walked: files
// that are not regular files (a device, a FIFO) or are larger than kMaxInputBytes, YAML whose
// aliases refer to a node that contains them (a cycle: every walk of it recurses forever), whose
// aliases expand to more than kMaxExpandedNodes nodes (an "alias bomb": a few lines that stand
// for 10⁹ nodes), that nests deeper than kMaxNestingDepth, or whose mapping keys are not names
// (a list as a key: every reader takes keys as strings).

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <string>

#include "cranesim/model/source_location.hpp"

namespace cranesim {

inline constexpr std::size_t kMaxInputBytes = 16u << 20;   // the thesis crane's scene: 23 kB
inline constexpr std::size_t kMaxExpandedNodes = 1u << 20;  // the crane with its bases: ~5000
inline constexpr int kMaxNestingDepth = 64;                 // the crane: 7

/// The text of the file at `path` (a scene, base scene or target: `what`). Throws SceneError
/// at `location` when it cannot be read, is not a regular file or is too large: the `base` field
/// naming it, or an empty location for the file itself (the error's reporter names that file).
std::string readInputFile(const std::string& path, const std::string& what, const SourceLocation& location);

/// YAML::Load of `text`, then the node graph checked as above. Throws SceneError naming the
/// line of the offending node.
YAML::Node loadBoundedYaml(const std::string& text);

}  // namespace cranesim
