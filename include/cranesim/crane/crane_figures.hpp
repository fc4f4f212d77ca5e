#pragma once
// A crane's state in its engineer's terms, from the scene's `crane:` (docs/scene-format.md#crane):
//
// - boom angle: the angle of the line from the boom's foot hinge to its head joint above the
//   horizontal plane (the plane normal to gravity), in degrees; 90° is a vertical boom;
// - heights: along −gravity above the inertial origin (the ground's datum);
// - radii: distances from the slewing axis (the slewing joint's axis through its joint);
// - rope tensions at each rope's start and end (a hoist rope's start at the head sheave carries
//   the load and the rope's weight; a reeved rope's start is its winch's part, its end its dead
//   end's).

#include <optional>
#include <string>
#include <vector>

#include "cranesim/model/model.hpp"
#include "cranesim/model/scene.hpp"

namespace cranesim {

struct RopeTension {
  std::string rope;
  double at_start = 0.0, at_end = 0.0;  // N
};

struct BoomFigures {
  double boom_angle_deg = 0.0;
  double head_height = 0.0;                  // m
  double hook_radius = 0.0, hook_height = 0.0;  // m
  std::optional<double> load_radius, load_height;  // m: the load's centre of mass, with crane.load
};

struct CraneFigures {
  std::optional<BoomFigures> boom;  // with a `crane:` block
  std::vector<RopeTension> ropes;   // crane.ropes, or every rope of the scene
};

/// Checks that the joints `crane:` names exist in `model`; throws SceneError at the name.
void locateCrane(const Scene& scene, const Model& model);

/// The figures at coordinates `q` and time `t` (rope lengths are profiles of t).
CraneFigures craneFigures(const Scene& scene, const Model& model, const double* q, double t);

/// The figures as lines of text, each stating what it measures.
std::string describeCraneFigures(const CraneFigures& figures);

}  // namespace cranesim
