#pragma once
// Posing a drawn state at its drives' values. A scene is drawn once, usually with its joints at
// rest (the crane unslewed); a driven revolute or prismatic joint may start anywhere. The part
// of the mechanism behind the joint — everything connected to its second joint by elements and
// constraints, once the joint itself is cut — is turned about the joint's axis (revolute) or
// moved along it (prismatic) as a rigid whole, until the joint stands at its drive's value at t:
// the ropes, beams and trusses on that side keep their drawn shape. A joint whose two sides stay
// connected (a closed loop, or both sides on the ground) cannot be posed rigidly and is left for
// the statics' path (solvers/equilibrium_path.hpp) or the constraint projection.

#include "cranesim/model/model.hpp"

namespace cranesim {

/// q (and v, when given: translational velocities turn with the part, body-frame angular
/// velocities stay) with every posable driven revolute and prismatic joint moved to its drive's
/// value at t, in the order of the scene's constraints. Returns the number of joints posed.
int poseAtDrives(const Model& model, double t, VecX& q, VecX* v = nullptr);

}  // namespace cranesim
