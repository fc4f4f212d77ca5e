#pragma once
// Writes the result of a modal analysis (solvers/modes.hpp) as an HDF5 file: frequencies, mode
// shapes in velocity coordinates and as joint displacements, and the equilibrium they belong to.

#include <string>
#include <vector>

#include "cranesim/solvers/modes.hpp"

namespace cranesim {

struct ModesMetadata {
  std::string scene_path, scene_text;
  double t = 0.0;  // time of the equilibrium (drives evaluated there)
  std::vector<std::string> labels;  // what each mode moves (crane/mode_labels.hpp); empty: none
};

/// Writes under `path`.partial and renames to `path`.
void writeModes(const std::string& path, const Model& model, const VecX& q_eq, const ModalResult& modes,
                const ModesMetadata& meta);

}  // namespace cranesim
