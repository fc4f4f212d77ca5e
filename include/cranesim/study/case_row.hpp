#pragma once
// One row of a study's case table: the case's status, message, work and figures. Rows travel as
// one line of text (the checkpoint's lines, the messages between MPI ranks) with every double
// written by its bits, so that a row read back is the row computed.

#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace cranesim {

/// A case's status: `complete`; `failed` (the solver failed, or a static equilibrium is
/// unstable: the message says which); `bad_input` (the case's parameter values make a scene
/// the reader refuses); `interrupted` (stopped by a signal; never recorded, so a resumed study
/// computes it again); `not_run` (in the results of a stopped study).
inline constexpr const char* kCaseComplete = "complete";
inline constexpr const char* kCaseFailed = "failed";
inline constexpr const char* kCaseBadInput = "bad_input";
inline constexpr const char* kCaseInterrupted = "interrupted";
inline constexpr const char* kCaseNotRun = "not_run";

struct CaseRow {
  long index = 0;
  std::string status = kCaseNotRun;
  std::string message;
  double steps = 0.0;        // time steps of a run, Newton iterations of an equilibrium
  double wall_time_s = 0.0;
  std::string worker;           // who computed it: "thread 0", "rank 3"; not part of the results proper
  std::vector<double> figures;  // in the study's order; NaN unless the case is complete
  /// A study with `capacity` (study/capacity_search.hpp): the heaviest load found admissible
  /// (NaN when the bracket's lightest is not), the lightest found inadmissible (NaN when the
  /// heaviest is admissible), and what that one violates.
  double capacity = std::numeric_limits<double>::quiet_NaN();
  double inadmissible_load = std::numeric_limits<double>::quiet_NaN();
  std::string limited_by;
  /// A study with `least_stable_angle` (study/least_stable_angle.hpp): the angle found, the grid
  /// angle that was worst, and the searched figure's value at the angle found (NaN without it).
  double least_stable_angle = std::numeric_limits<double>::quiet_NaN();
  double worst_grid_angle = std::numeric_limits<double>::quiet_NaN();
  double least_stable_value = std::numeric_limits<double>::quiet_NaN();
};

std::string encodeRow(const CaseRow& row);
/// The row of a line encodeRow wrote with `figures` figures; nothing for a line that is not one
/// (cut short by a crash, or from another study).
std::optional<CaseRow> decodeRow(const std::string& line, std::size_t figures);

}  // namespace cranesim
