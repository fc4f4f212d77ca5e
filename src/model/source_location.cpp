#include "cranesim/model/source_location.hpp"

#include <fmt/format.h>

namespace cranesim {

std::string SourceLocation::describe() const {
  if (line > 0) return fmt::format("{} (line {}, column {})", path.empty() ? "<document>" : path, line, column);
  return path.empty() ? "<document>" : path;
}

// A location with neither a path nor a line is the input file itself, which whoever reports the
// error names.
SceneError::SceneError(SourceLocation where, const std::string& message)
    : std::runtime_error(where.path.empty() && where.line == 0 ? message : fmt::format("{}: {}", where.describe(), message)),
      where_(std::move(where)) {}

}  // namespace cranesim
