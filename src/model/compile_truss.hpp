#pragma once
// Compilation of truss members (`type: truss`), either fidelity; see compile_truss.cpp.

#include "cranesim/model/model.hpp"

namespace cranesim {

/// Adds the truss member `member` of type `truss` to the model: its nodes, elements, the
/// joints <name>.start / <name>.end on its end sections, and the constraints it needs inside.
void compileTrussMember(Model& model, const MemberSpec& member, const TrussDescription& truss);

}  // namespace cranesim
