#pragma once
// Members' ends drawn at named joints (`start: head.sheave` instead of coordinates).

#include "cranesim/model/scene.hpp"

namespace cranesim {

/// Places every member end that names a joint at that joint's drawn position, following
/// chains of members in any order (a cycle is an error naming its members), then checks what
/// needs both ends: distinct points, and a truss's drawn length against its type's length
/// (within solver.assembly_tolerance; the truss is built to its type's length along the drawn
/// direction, and assembly closes the rest). Errors name the member's `start` or `end`.
void placeMemberEnds(Scene& scene);

}  // namespace cranesim
