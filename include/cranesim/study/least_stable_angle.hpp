#pragma once
// A case's least stable slewing angle (a study's `least_stable_angle`, docs/studies.md "The least
// stable angle"): the angle at which a figure is worst (largest for worst: max, smallest for
// worst: min). Every case computes its analysis at each angle of the grid, takes the worst, and
// refines between that angle's two neighbours (between the end and its one neighbour at an end of
// the grid) by golden-section search until the bracket is narrower than the tolerance. The search
// finds the worst angle of that bracket when the figure has one extreme in it; a grid too coarse to
// put the worst direction's bracket around the right extreme is the study's to refine. An angle
// whose analysis does not complete (the carriage tips there) counts as worse than any that does.

#include <functional>

#include "cranesim/study/case_row.hpp"
#include "cranesim/study/study.hpp"

namespace cranesim {

/// The analysis of the case at an angle: its row (status, figures) as runCase would give it.
using AngledCase = std::function<CaseRow(double angle)>;

/// Golden-section search on `evaluate` over `study.least_stable`. The row at the worst angle
/// found, with `least_stable_angle` that angle, `worst_grid_angle` the grid's worst and
/// `least_stable_value` the figure there; `steps` summed over the evaluations. A grid angle whose
/// analysis fails ends the search there: its row is returned, the angle set. An interrupted
/// evaluation's row is returned as it is.
CaseRow searchLeastStableAngle(const Study& study, const AngledCase& evaluate);

}  // namespace cranesim
