#include "bounded_yaml.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <vector>

namespace cranesim {
namespace {

SourceLocation locationOf(const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  return {"<document>", mark.line >= 0 ? mark.line + 1 : 0, mark.column >= 0 ? mark.column + 1 : 0};
}

/// Walks the node graph as every reader of it will (aliases expanded), within the limits.
class GraphCheck {
 public:
  void visit(const YAML::Node& node) {
    if (++visited_ > kMaxExpandedNodes)
      throw SceneError(locationOf(node), fmt::format("the YAML's aliases expand to more than {} nodes (an alias bomb?); "
                                                     "write the repeated parts out or use fewer aliases", kMaxExpandedNodes));
    for (const YAML::Node& ancestor : ancestors_)
      if (node.is(ancestor))
        throw SceneError(locationOf(node), "an alias refers to a node that contains it (a cycle): nothing can read it");
    if (ancestors_.size() >= static_cast<std::size_t>(kMaxNestingDepth))
      throw SceneError(locationOf(node), fmt::format("the YAML nests deeper than {} levels", kMaxNestingDepth));
    if (!node.IsSequence() && !node.IsMap()) return;
    ancestors_.push_back(node);
    for (const auto& item : node) {
      if (node.IsSequence()) {
        visit(item);
      } else {
        if (!item.first.IsScalar())  // every reader takes keys as names
          throw SceneError(locationOf(item.first), "a mapping key must be a name, not a list or mapping");
        visit(item.first);
        visit(item.second);
      }
    }
    ancestors_.pop_back();
  }

 private:
  std::size_t visited_ = 0;
  std::vector<YAML::Node> ancestors_;
};

/// Where flow collections ('[', '{') first nest deeper than the limit, outside quotes and comments;
/// empty when they do not. yaml-cpp refuses very deep flow nesting itself, with a message ("bad
/// file") that gives a reader nothing to act on.
std::optional<SourceLocation> flowNestingBeyondLimit(const std::string& text) {
  int depth = 0, line = 1, column = 0;
  char quote = 0;
  bool comment = false;
  char previous = '\n';
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    ++column;
    if (c == '\n') {
      ++line, column = 0, comment = false;
    } else if (comment) {
      continue;
    } else if (quote) {
      if (c == '\\' && quote == '"') ++i, ++column;
      else if (c == quote) quote = 0;
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '#' && std::isspace(static_cast<unsigned char>(previous))) {
      comment = true;
    } else if ((c == '[' || c == '{') && (depth > 0 || (previous != '\0' && std::strchr(" \t\n:-,", previous)))) {
      if (++depth > kMaxNestingDepth) return SourceLocation{"<document>", line, column};
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
    previous = c;
  }
  return std::nullopt;
}

}  // namespace

std::string readInputFile(const std::string& path, const std::string& what, const SourceLocation& location) {
  // The file itself (an empty location) is named by whoever reports the error; a file another
  // names (a base scene) is named here.
  const std::string file = location.path.empty() && location.line == 0 ? what : fmt::format("{} '{}'", what, path);
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (error || !std::filesystem::exists(status)) throw SceneError(location, fmt::format("cannot open the {}", file));
  if (!std::filesystem::is_regular_file(status))
    throw SceneError(location, fmt::format("the {} is not a regular file", file));
  const auto size = std::filesystem::file_size(path, error);
  if (!error && size > kMaxInputBytes)
    throw SceneError(location, fmt::format("the {} has {} bytes, more than the {} any {} needs", file, size,
                                           kMaxInputBytes, what));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(location, fmt::format("cannot open the {}", file));
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

YAML::Node loadBoundedYaml(const std::string& text) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    if (const auto deep = flowNestingBeyondLimit(text))
      throw SceneError(*deep, fmt::format("the YAML nests deeper than {} levels", kMaxNestingDepth));
    throw SceneError({"<document>", e.mark.line + 1, e.mark.column + 1}, "not valid YAML: " + e.msg);
  }
  GraphCheck().visit(root);
  return root;
}

}  // namespace cranesim
