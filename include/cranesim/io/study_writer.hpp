#pragma once
// The results file of a study (docs/study-format.md): the case table, one dataset per parameter and
// per figure indexed by case, with the study's text. Written as `<path>.partial` and renamed, as
// every results file.

#include <string>
#include <vector>

#include "cranesim/study/case_row.hpp"
#include "cranesim/study/study.hpp"

namespace cranesim {

/// `rows` holds one row per case, in case order (rows of cases not computed: status not_run).
/// `message` is empty for a finished study, and says why it stopped otherwise; `execution` says
/// who computed it (e.g. "2 threads"), which the table does not depend on.
void writeStudyResults(const std::string& path, const Study& study, const std::vector<CaseRow>& rows,
                       const std::string& message, const std::string& execution);

}  // namespace cranesim
