#pragma once
// A case's capacity (a study's `capacity:`, docs/studies.md "Capacity by bisection"): the
// heaviest load at which every criterion holds, found by bisection on the load between a bracket
// [from, to] until it is narrower than the tolerance. Every evaluation is the case's analysis at
// one load; the row returned is the one at the capacity, with the bracket's ends and what the
// inadmissible end violates.

#include <functional>

#include "cranesim/study/case_row.hpp"
#include "cranesim/study/study.hpp"

namespace cranesim {

/// The analysis of the case at a load: its row (status, figures) as runCase would give it.
using LoadedCase = std::function<CaseRow(double load)>;

/// Whether every criterion of `study` holds for a complete `row`.
bool admissible(const Study& study, const CaseRow& row);

/// Bisection on `evaluate` over `study.capacity`'s bracket. The row of the heaviest admissible
/// load, with `capacity` and `inadmissible_load` the final bracket's ends and `limited_by` the
/// figures of the criteria violated at its inadmissible end (or that case's status and message);
/// `steps` summed over the evaluations. A bracket whose lightest load is not admissible gives
/// that load's row, capacity NaN; one whose heaviest is admissible, that row, capacity `to`.
/// A load the analysis cannot compute counts as inadmissible, unless it is the lightest: then
/// its row is returned as it is (failed, bad_input or interrupted).
CaseRow searchCapacity(const Study& study, const LoadedCase& evaluate);

}  // namespace cranesim
