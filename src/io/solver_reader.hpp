#pragma once
// The `solver:` block of a scene, and its absolute tolerances (also read by target files for
// their verification run).

#include "cranesim/model/scene.hpp"
#include "yaml_field.hpp"

namespace cranesim {

/// `atol`: one value for every coordinate, or one per kind (all four keys).
AbsoluteTolerance readAbsoluteTolerance(const YamlField& f);

/// `rtol`: a positive relative tolerance below 0.1.
double readRelativeTolerance(const YamlField& f);

SolverSpec readSolver(const YamlField& f);

}  // namespace cranesim
