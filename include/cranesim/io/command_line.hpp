#pragma once
// What the command-line tools (crane-sim, crane-opt) share: exit codes and result paths.

#include <string>

namespace cranesim {

inline constexpr int kExitSolverFailure = 1;  // results kept, marked incomplete
inline constexpr int kExitBadInput = 2;       // nothing written

/// `out`, or `<stem of input_path><suffix>` in the working directory when `out` is empty.
/// Throws SceneError (bad input, reported at "-o") before any work when the results could not be
/// written there: its directory does not exist or cannot be written, it is a directory, or it is
/// the input file itself.
std::string outputPath(const std::string& input_path, std::string out, const char* suffix);

}  // namespace cranesim
