#include "cranesim/io/command_line.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "cranesim/model/source_location.hpp"

namespace cranesim {

std::string outputPath(const std::string& input_path, std::string out, const char* suffix) {
  if (out.empty()) out = std::filesystem::path(input_path).stem().string() + suffix;
  const auto out_dir = std::filesystem::absolute(out).parent_path();
  if (!std::filesystem::is_directory(out_dir))
    throw SceneError({"-o", 0, 0}, fmt::format("the output directory '{}' does not exist", out_dir.string()));
  return out;
}

}  // namespace cranesim
