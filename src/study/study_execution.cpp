#include "cranesim/study/study_execution.hpp"

#include <fmt/format.h>

#include <filesystem>

namespace cranesim {

CaseRow computeCase(const Study& study, long index, const StudyExecution& execution) {
  CaseOptions options;
  options.stop = execution.stop;
  if (!execution.cases_dir.empty())
    options.results_path = (std::filesystem::path(execution.cases_dir) / fmt::format("case_{:05d}.h5", index)).string();
  return runCase(study, index, options);
}

}  // namespace cranesim
