#pragma once
// What the command-line tools (crane-sim, crane-opt) share: exit codes and result paths.

#include <functional>
#include <string>

namespace cranesim {

inline constexpr int kExitSolverFailure = 1;  // results kept, marked incomplete
inline constexpr int kExitBadInput = 2;       // nothing written
inline constexpr int kExitClearanceFailure = 3;  // crane-opt plan: the verified motion came too close to an obstacle; plan kept, marked failed

/// `out`, or `<stem of input_path><suffix>` in the working directory when `out` is empty.
/// Throws SceneError (bad input, reported at "-o") before any work when the results could not be
/// written there: its directory does not exist or cannot be written, it is a directory, or it is
/// the input file itself.
std::string outputPath(const std::string& input_path, std::string out, const char* suffix);

/// Runs `read` (a command reading its input) and returns its exit code: 0, kExitBadInput for a
/// SceneError, kExitSolverFailure for another exception; when `report`, the error goes to stderr,
/// a SceneError naming `path`.
int inputVerdict(const std::string& path, bool report, const std::function<void()>& read);

}  // namespace cranesim
