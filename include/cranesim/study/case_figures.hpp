#pragma once
// A study case's figures (study.hpp: FigureSpec) from what its analysis recorded.

#include <vector>

#include "cranesim/io/results_writer.hpp"
#include "cranesim/solvers/modes.hpp"
#include "cranesim/study/study.hpp"

namespace cranesim {

/// The figures of one case, in the study's order, from its recorded samples (one for an
/// equilibrium) and, for analysis: modes, its modes. NaN where no sample lies at t ≥ after or the
/// mode was not computed. `scene` is the case's (a tipping load's body and its mass).
std::vector<double> caseFigures(const Study& study, const Scene& scene, const Model& model, const ResultsRecorder& recorder,
                                const ModalResult* modes);

}  // namespace cranesim
