#pragma once
// The reeving tests' hook (tests/test_reeving.cpp, tests/test_capstan.cpp): a 10 t hook guided
// by a vertical prismatic joint 10 m under a head fixed at 20 m, its reeved rope `hoist` (a steel
// rope, r = 1 cm, E = 1e11 Pa) from a winch on the ground 8 m beside the head.

#include <fmt/format.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "cranesim/io/scene_reader.hpp"
#include "cranesim/model/model.hpp"
#include "cranesim/model/reeved_rope_element.hpp"

namespace cranesim::test {

inline constexpr double kHookMass = 1.0e4, kHookWeight = kHookMass * 9.81;
inline constexpr double kHookRopeArea = 3.14159265358979e-4;  // radius 1 cm

/// The guided hook; `reeving` holds the rope's own fields as YAML lines indented by four spaces
/// (its `path`, or `falls` with `winch: ground.winch`, `head: {joint: ground.head, …}` and
/// `hook: {joint: hook.sheaves, …}`; `efficiency`, `length`), the hook's sheaves at its centre of
/// mass (joint hook.sheaves); Kelvin–Voigt damping `damping` s; from equilibrium to `t_end` at
/// rtol 1e-9, a sample every 0.05 s.
inline Scene guidedHook(const std::string& reeving, double damping, double t_end) {
  return parseScene(fmt::format(R"(
name: guided hook
ground:
  joints:
    - {{name: winch, position: [-8, 0, 20]}}
    - {{name: head, position: [0, 0, 20]}}
    - {{name: guide, position: [0, 0, 10]}}
bodies:
  - name: hook
    mass: {}
    inertia: [1000, 1000, 1000]
    position: [0, 0, 10]
    joints: [{{name: sheaves, position: [0, 0, 0]}}]
members:
  - name: hoist
    type: rope
    element: reeved
{}
    section: {{radius: 0.01}}
    material: {{density: 7800, youngs_modulus: 1.0e11, poisson_ratio: 0.3}}
    damping: {}
constraints:
  - {{name: guide, type: prismatic, joints: [ground.guide, hook.origin], axis: z}}
solver: {{t_end: {}, rtol: 1.0e-9, atol: 1.0e-11, initial_state: equilibrium}}
output: {{interval: 0.05}}
)",
                                kHookMass, reeving, damping, t_end),
                    "<test>");
}

/// The model's reeved rope named `name`; std::runtime_error when it has none.
inline const ReevedRopeElement& reevedRopeNamed(const Model& model, const std::string& name = "hoist") {
  const int index = findReevedRope(model, name);
  if (index < 0) throw std::runtime_error("no reeved rope " + name);
  return reevedRope(model, index);
}

/// The part tensions of the reeved rope `name`, winch to dead end, at (q, v, t).
inline std::vector<double> partTensions(const Model& model, const double* q, const double* v, double t,
                                        const std::string& name = "hoist") {
  const ReevedRopeElement& rope = reevedRopeNamed(model, name);
  std::vector<double> tensions(static_cast<std::size_t>(rope.kernel().parts()));
  rope.partTensions(ElementInput{q, v, nullptr, t, model.gravity}, tensions.data());
  return tensions;
}

}  // namespace cranesim::test
