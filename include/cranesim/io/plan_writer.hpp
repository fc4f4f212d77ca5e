#pragma once
// Writes crane-opt's results as one HDF5 file (docs/plan-format.md): the static map, its
// fitted surfaces, the QR trajectory, the control trajectory, the inversion checks and the
// verification run.

#include <string>

#include "cranesim/planning/quasi_static_plan.hpp"

namespace cranesim {

/// Writes under `path`.partial and renames to `path`. With `map_only`, only the map and the
/// target are written (crane-opt map).
void writePlan(const std::string& path, const TargetSpec& target, const QuasiStaticPlan& plan, bool map_only = false);

}  // namespace cranesim
