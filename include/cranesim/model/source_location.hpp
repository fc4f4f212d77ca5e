#pragma once

#include <stdexcept>
#include <string>

namespace cranesim {

/// Where a value came from in the scene file: its YAML path (e.g. `bodies[2].mass`) and line.
struct SourceLocation {
  std::string path;
  int line = 0;    // 1-based; 0 when unknown
  int column = 0;  // 1-based; 0 when unknown
  std::string describe() const;
};

/// Bad input: a scene that cannot be loaded or compiled. The CLI reports it with exit code 2.
class SceneError : public std::runtime_error {
 public:
  SceneError(SourceLocation where, const std::string& message);
  const SourceLocation& where() const { return where_; }

 private:
  SourceLocation where_;
};

}  // namespace cranesim
