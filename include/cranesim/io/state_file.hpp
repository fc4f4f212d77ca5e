#pragma once
// A run's saved state in a file (docs/session.md#saving-and-restoring): what Simulation::save
// returns, written as HDF5 with the model it belongs to, so that a run can go on in another
// process from the same scene.

#include <string>

#include "cranesim/model/model.hpp"
#include "cranesim/solvers/simulation.hpp"

namespace cranesim {

/// Writes `state` of a run of `model` to `path` (under a temporary name, then renamed: an older
/// file stays whole if the write fails).
void writeStateFile(const std::string& path, const Model& model, const SimulationState& state);

/// The state saved in `path`; std::runtime_error naming the file when it cannot be read, is not
/// a state file, or belongs to another model (other coordinates or inputs).
SimulationState readStateFile(const std::string& path, const Model& model);

}  // namespace cranesim
