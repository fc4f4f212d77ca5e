#pragma once

#include <string>

#include "cranesim/assembly/assembler.hpp"

namespace cranesim {

/// Human-readable model summary for `crane-sim check`: bodies, coordinates, constraints,
/// degrees of freedom (nv − rank G at the initial state), drives, loads, solver settings.
std::string modelSummary(const Assembler& assembler);

}  // namespace cranesim
