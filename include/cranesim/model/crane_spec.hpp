#pragma once
// What makes a mechanism a crane to its engineer (a scene's `crane:`): the slewing axis, the
// boom from its foot hinge to its head, the hook and the load, and the ropes whose tensions count.

#include <string>
#include <vector>

#include "cranesim/model/source_location.hpp"

namespace cranesim {

struct CraneSpec {
  std::string slewing;    // a revolute constraint: the slewing axis is its axis through its joint
  std::string boom_foot;  // a revolute constraint: the boom's foot hinge
  std::string boom_head;  // a joint at the boom's head (the boom's axis ends there)
  std::string hook;       // the joint the load hangs from
  std::string load;       // the load's body, if any: its centre of mass gives the load's radius
  std::vector<std::string> ropes;  // the ropes reported (empty: every rope of the scene)
  SourceLocation where_slewing, where_boom_foot, where_boom_head, where_hook;
};

}  // namespace cranesim
