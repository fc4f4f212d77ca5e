#include "cranesim/io/command_line.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "cranesim/model/source_location.hpp"
#include "hdf5_file.hpp"

namespace cranesim {

std::string outputPath(const std::string& input_path, std::string out, const char* suffix) {
  namespace fs = std::filesystem;
  if (out.empty()) out = fs::path(input_path).stem().string() + suffix;
  const auto out_dir = fs::absolute(out).parent_path();
  if (!fs::is_directory(out_dir))
    throw SceneError({"-o", 0, 0}, fmt::format("the output directory '{}' does not exist", out_dir.string()));
  if (fs::is_directory(out))
    throw SceneError({"-o", 0, 0}, fmt::format("'{}' is a directory; name the results file", out));
  std::error_code ignored;
  if (fs::equivalent(out, input_path, ignored))
    throw SceneError({"-o", 0, 0}, fmt::format("'{}' is the input file itself; the results would overwrite it", out));
  // Before any work: can the results be written where they will be (hdf5_file.hpp)?
  const std::string partial = partialPath(out);
  const bool existed = fs::exists(partial, ignored);
  const int fd = ::open(partial.c_str(), O_WRONLY | O_CREAT, 0644);
  if (fd < 0)
    throw SceneError({"-o", 0, 0}, fmt::format("cannot write the results next to '{}': {}", out, std::strerror(errno)));
  ::close(fd);
  if (!existed) fs::remove(partial, ignored);
  return out;
}

}  // namespace cranesim

namespace cranesim {

int inputVerdict(const std::string& path, bool report, const std::function<void()>& read) {
  try {
    read();
  } catch (const SceneError& e) {
    if (report) fmt::print(stderr, "error: {}: {}\n", path, e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    if (report) fmt::print(stderr, "error: {}\n", e.what());
    return kExitSolverFailure;
  }
  return 0;
}

}  // namespace cranesim
