#pragma once
// The tests' small crane on four pads: a carriage on pads at (±2.5, ±2) m, on its slewing ring
// 1.2 m up an upper carriage (its counterweight puts its centroid 1 m behind the slewing axis)
// slewed by `slewed_deg`, with a load hanging 2 m below the tip of its arm, 8 m out and 4 m up.
// With the default masses (20 t, 6 t, 9 t) the resultant swings 1.886 m about the axis: beyond
// the pads' kern over the corners, inside their rectangle everywhere; a load of 12.909 t puts it
// on the front edge straight ahead (x = (8 m · L − 1 m · 6 t) / (26 t + L) = 2.5 m).

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <string>

namespace cranesim::test {

struct CarriageOnPads {
  double carriage_mass = 20000.0, upper_mass = 6000.0, load_mass = 9000.0;  // kg
  double slewed_deg = 0.0;
  double subgrade_modulus = 1.0e10;  // N/m³
  double pad_area = 0.5;             // m²
  double smoothing = 0.1;            // the springs' smoothing band over the mean settlement
  double gravity = 9.81;             // m/s²
};

inline std::string carriageOnPadsYaml(const CarriageOnPads& c) {
  const double angle = c.slewed_deg * std::numbers::pi / 180.0;
  return fmt::format(R"(
name: carriage on four pads
gravity: [0, 0, -{gravity}]
ground:
  supports:
    body: carriage
    soil: {{subgrade_modulus: {modulus}, allowable_pressure: 1.0e6}}
    smoothing: {smoothing}
    pads:
      - {{name: front_left, joint: carriage.front_left, area: {area}}}
      - {{name: rear_left, joint: carriage.rear_left, area: {area}}}
      - {{name: rear_right, joint: carriage.rear_right, area: {area}}}
      - {{name: front_right, joint: carriage.front_right, area: {area}}}
bodies:
  - name: carriage
    mass: {carriage}
    centroid: [0, 0, 0.6]
    inertia: [30000, 40000, 60000]
    joints:
      - {{name: front_left, position: [2.5, 2, 0]}}
      - {{name: rear_left, position: [-2.5, 2, 0]}}
      - {{name: rear_right, position: [-2.5, -2, 0]}}
      - {{name: front_right, position: [2.5, -2, 0]}}
      - {{name: ring, position: [0, 0, 1.2]}}
  - name: upper
    mass: {upper}
    centroid: [-1, 0, 1]
    inertia: [6000, 10000, 10000]
    position: [0, 0, 1.2]
    rotation: {{axis: [0, 0, 1], angle_deg: {slewed}}}
    joints: [{{name: tip, position: [8, 0, 4]}}]
  - name: load
    mass: {load}
    centroid: [0, 0, -2]
    inertia: [1000, 1000, 1000]
    position: [{x}, {y}, 5.2]
constraints:
  - {{name: slewing, type: revolute, joints: [carriage.ring, upper.origin], axis: z, drive: {{type: constant, value: {slewed}, unit: deg}}}}
  - {{name: hook, type: spherical, joints: [upper.tip, load.origin]}}
solver: {{t_end: 1, rtol: 1.0e-8, atol: 1.0e-10}}
)",
                     fmt::arg("gravity", c.gravity), fmt::arg("modulus", c.subgrade_modulus), fmt::arg("smoothing", c.smoothing),
                     fmt::arg("area", c.pad_area), fmt::arg("carriage", c.carriage_mass), fmt::arg("upper", c.upper_mass),
                     fmt::arg("load", c.load_mass), fmt::arg("slewed", c.slewed_deg), fmt::arg("x", 8.0 * std::cos(angle)),
                     fmt::arg("y", 8.0 * std::sin(angle)));
}

}  // namespace cranesim::test
