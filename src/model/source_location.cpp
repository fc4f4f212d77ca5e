#include "cranesim/model/source_location.hpp"

#include <fmt/format.h>

namespace cranesim {

std::string SourceLocation::describe() const {
  if (line > 0) return fmt::format("{} (line {}, column {})", path.empty() ? "<document>" : path, line, column);
  return path.empty() ? "<document>" : path;
}

SceneError::SceneError(SourceLocation where, const std::string& message)
    : std::runtime_error(fmt::format("{}: {}", where.describe(), message)), where_(std::move(where)) {}

}  // namespace cranesim
