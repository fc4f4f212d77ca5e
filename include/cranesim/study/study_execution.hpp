#pragma once
// How a study's cases are computed: each case is a task of the task farm
// (parallel/task_farm.hpp: threads, and MPI ranks when built with MPI), its row goes to one sink.

#include <atomic>
#include <functional>
#include <string>

#include "cranesim/study/case_runner.hpp"

namespace cranesim {

/// What every worker needs besides the study and the case number.
struct StudyExecution {
  const std::atomic<bool>* stop = nullptr;
  std::string cases_dir;  // where each case's full results go (keep_results); empty: nowhere
};

/// Computes case `index` (case_runner.hpp) with its results file in `execution.cases_dir`:
/// case_00017.h5, numbered with at least five digits.
CaseRow computeCase(const Study& study, long index, const StudyExecution& execution);

/// Receives each finished row; must be thread-safe.
using RowSink = std::function<void(CaseRow)>;

}  // namespace cranesim
