#pragma once
// A reeved rope member (elements/reeved_rope.hpp) compiled onto the nodes of the joints its
// path runs over.

#include "cranesim/model/model.hpp"

namespace cranesim {

/// Adds the element of the reeved rope `m` (its length profile attached as an input already):
/// its path points at the named joints, on their nodes.
void compileReevedRope(Model& model, const MemberSpec& m);

}  // namespace cranesim
