#pragma once
// The elements that carry a member's internal forces: a beam member's or truss' beams that report
// section forces (a truss' end plates do not), or a rope's elements that report its tension.

#include <string>
#include <vector>

#include "cranesim/model/model.hpp"

namespace cranesim {

/// The elements on `member`'s own nodes that report section forces (Element::sectionForces) or,
/// for a rope, tensions (Element::tensions), in element order.
std::vector<int> memberForceElements(const Model& model, const std::string& member, bool rope);

}  // namespace cranesim
