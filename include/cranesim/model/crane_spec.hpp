#pragma once
// What makes a mechanism a crane to its engineer (a scene's `crane:`): the slewing axis, the
// boom from its foot hinge to its head, the hook and the load, and the ropes whose tensions count.

#include <optional>
#include <string>
#include <vector>

#include "cranesim/model/source_location.hpp"

namespace cranesim {

/// The boom's backstop: a rotational penalty law about the foot hinge that engages at a boom
/// angle, pushing the boom at a joint up from its foot (model/contact_elements.hpp: BackstopElement).
struct BackstopSpec {
  double angle_deg = 0.0;      // the boom angle at which it engages
  double stiffness = 0.0;      // N·m/rad
  double damping = 0.0;        // N·m·s/rad
  double smoothing_deg = 0.2;  // ε of the penalty law, deg
  std::string joint;           // where it pushes the boom (empty: the boom head joint)
  SourceLocation where, where_joint;
};

struct CraneSpec {
  std::string slewing;    // a revolute constraint: the slewing axis is its axis through its joint
  std::string boom_foot;  // a revolute constraint: the boom's foot hinge
  std::string boom_head;  // a joint at the boom's head (the boom's axis ends there)
  std::string hook;       // the joint the load hangs from
  std::string load;       // the load's body, if any: its centre of mass gives the load's radius
  std::vector<std::string> ropes;  // the ropes reported (empty: every rope of the scene)
  std::optional<BackstopSpec> backstop;
  /// The largest boom angle of the crane's envelope, deg: a run that passes it is reported.
  double boom_angle_limit_deg = 90.0;
  SourceLocation where_slewing, where_boom_foot, where_boom_head, where_hook;
};

}  // namespace cranesim
