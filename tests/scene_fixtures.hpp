#pragma once
// Helpers shared by the tests: load scenes from configs/ or inline YAML, and run them in-process.

#include <stdexcept>
#include <string>

#include "cranesim/io/results_writer.hpp"
#include "cranesim/io/scene_reader.hpp"
#include "cranesim/model/compile.hpp"
#include "cranesim/solvers/equilibrium_path.hpp"

namespace cranesim::test {

inline std::string configPath(const std::string& name) { return std::string(CRANESIM_SOURCE_DIR) + "/configs/" + name; }

inline Scene loadScene(const std::string& name) { return readScene(configPath(name)); }

inline Model loadYaml(const std::string& yaml) { return compileModel(parseScene(yaml, "<test>")); }

/// A 1 kg, 1 m rod hung from a hinge at its top (joints rod.top, rod.tip), turned about y by
/// `drive` (a profile in YAML); 5 s at rtol 1e-8, a sample every 10 ms.
inline Scene drivenRod(const std::string& drive) {
  std::string yaml = R"(
name: driven rod
ground:
  joints: [{name: pivot}]
bodies:
  - name: rod
    mass: 1.0
    inertia: [0.08333333333333333, 0.08333333333333333, 1.0e-4]
    position: [0, 0, -0.5]
    joints: [{name: top, position: [0, 0, 0.5]}, {name: tip, position: [0, 0, -0.5]}]
constraints:
  - {name: hinge, type: revolute, joints: [ground.pivot, rod.top], axis: y, drive: DRIVE}
solver: {t_end: 5, rtol: 1.0e-8, atol: 1.0e-10}  # tanh starts 2.5e-5 off 0: posed there
output: {interval: 0.01}
)";
  yaml.replace(yaml.find("DRIVE"), 5, drive);
  return parseScene(yaml, "<test>");
}

/// Where `joint` stands in the static equilibrium of the scene `yaml` at t = 0 (solveEquilibrium);
/// throws with the solver's message when none is found.
inline Vec3 equilibriumJointPosition(const std::string& yaml, const std::string& joint) {
  const Scene scene = parseScene(yaml, "<test>");
  const Model model = compileModel(scene);
  const StaticResult eq = solveEquilibrium(scene, model, 0.0);
  if (!eq.converged) throw std::runtime_error("no equilibrium: " + eq.message);
  return model.jointFrame(eq.q.data(), model.findJoint(joint)).r;
}

/// The scene without gravity, with a force and a torque (inertial axes) on the joint boom.end.
/// The thesis crane with its controls as inputs (crane_inputs.yaml) and a gust on its 390 t load:
/// 50 kN across the boom, rising and falling from 2 s to 5 s (breakpoints at both).
inline Scene craneInputsWithGust() {
  Scene scene = loadScene("crane_inputs.yaml");
  LoadSpec gust;
  gust.name = "gust";
  gust.joint = "load.origin";
  gust.force = Vec3(0.0, 5e4, 0.0);
  gust.scale = Profile(CosineFullProfile{0.0, 1.0, 2.0, 5.0});
  scene.loads.push_back(gust);
  return scene;
}

inline Scene withEndLoad(Scene scene, const Vec3& force, const Vec3& torque = Vec3::Zero()) {
  scene.gravity = Vec3::Zero();
  LoadSpec load;
  load.name = "tip";
  load.joint = "boom.end";
  load.force = force;
  load.torque = torque;
  scene.loads.push_back(load);
  return scene;
}

/// Displacement of a joint from its place in the model's initial state q0 to its place in q.
inline Vec3 jointOffset(const Model& model, const VecX& q, const std::string& joint) {
  const int j = model.findJoint(joint);
  return model.jointFrame(q.data(), j).r - model.jointFrame(model.q0.data(), j).r;
}

/// Rotation vector turning a joint's frame in q0 into its frame in q, in the q0 frame's axes.
inline Vec3 jointTurn(const Model& model, const VecX& q, const std::string& joint) {
  const int j = model.findJoint(joint);
  const Eigen::AngleAxisd turn(Mat3(model.jointFrame(model.q0.data(), j).R.transpose() * model.jointFrame(q.data(), j).R));
  return turn.angle() * turn.axis();
}

/// A scene simulated from its consistent initial state, with every sample recorded.
struct SimulationRun {
  explicit SimulationRun(const Scene& scene)
      : model(compileModel(scene)), assembler(model), recorder(assembler) {
    const DynamicState initial = consistentInitialState(assembler, model.solver.t_start, model.q0, model.v0,
                                                        model.solver.assembly_tolerance);
    outcome = simulate(assembler, initial, recorder);
  }
  const std::vector<double>& jointPositions(const std::string& joint) const {
    return recorder.jointPositions(model.findJoint(joint));
  }
  double maxSampleResidual() const {
    const auto& r = recorder.positionResidual();
    return *std::max_element(r.begin(), r.end());
  }

  Model model;
  Assembler assembler;
  ResultsRecorder recorder;
  SimulationOutcome outcome;
};

}  // namespace cranesim::test
