#pragma once
// Helpers shared by the tests: load scenes from configs/ or inline YAML, and run them in-process.

#include <string>

#include "cranesim/io/results_writer.hpp"
#include "cranesim/io/scene_reader.hpp"
#include "cranesim/model/compile.hpp"

namespace cranesim::test {

inline std::string configPath(const std::string& name) { return std::string(CRANESIM_SOURCE_DIR) + "/configs/" + name; }

inline Scene loadScene(const std::string& name) { return readScene(configPath(name)); }

inline Model loadYaml(const std::string& yaml) { return compileModel(parseScene(yaml, "<test>")); }

/// A scene simulated from its consistent initial state, with every sample recorded.
struct SimulationRun {
  explicit SimulationRun(const Scene& scene)
      : model(compileModel(scene)), assembler(model), recorder(assembler) {
    const DynamicState initial = consistentInitialState(assembler, model.solver.t_start, model.q0, model.v0,
                                                        model.solver.initial_tolerance);
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
