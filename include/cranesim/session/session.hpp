#pragma once
// A run of a scene that its caller drives step by step (docs/session.md): a controller, an
// operator's commands or a learning agent sets the scene's inputs, advances the crane by its own
// sampling time and reads where it is. The scene, its model and its starting state are those of
// `crane-sim run`; the integration is the Simulation that `crane-sim run` advances in one call.

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "cranesim/assembly/assembler.hpp"
#include "cranesim/assembly/constraint_reaction.hpp"
#include "cranesim/io/results_writer.hpp"
#include "cranesim/model/scene.hpp"
#include "cranesim/solvers/initial_conditions.hpp"
#include "cranesim/solvers/simulation.hpp"

namespace cranesim {

class Session {
 public:
  /// Reads the scene file, drawn where its equilibrium meets the figures it states, compiles it
  /// (SceneError naming the file, key path and line on bad input) and solves its starting state
  /// as `crane-sim run` does (solver.initial_state). With `record`, keeps the run's samples every
  /// output.interval as `crane-sim run` records them (SceneError at output.interval when a run to
  /// solver.t_end would not fit in memory).
  explicit Session(const std::string& scene_path, bool record = false);
  explicit Session(const Scene& scene, bool record = false);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  const Scene& scene() const { return scene_; }
  const Model& model() const { return *model_; }
  const Assembler& assembler() const { return *assembler_; }

  /// Back to the starting state at solver.t_start, every input at rest at its scene value; a
  /// recording starts anew.
  void reset();

  /// Whether the run's samples are kept. A restore keeps the samples before the state's time and
  /// records on from there.
  bool recording() const { return recording_; }
  /// The samples kept so far; nullptr when not recording.
  const ResultsRecorder* recorder() const { return sink_.recorder.get(); }
  /// Writes the samples so far as a results file (docs/results-format.md) through a temporary
  /// file, complete up to time() unless the run failed; std::logic_error when not recording.
  void writeResults(const std::string& path) const;

  /// The index of the input (Model::inputs) named `name`; std::invalid_argument naming the
  /// scene's inputs when there is none.
  int input(const std::string& name) const;
  /// Holds `command` on input `index` from time() on, clipped to its limits (InputSignal::command);
  /// returns the command as held. std::invalid_argument for a command that is not finite.
  double setInput(int index, double command);
  /// The input's drive now: its value and its rate (scene units, per second).
  double inputValue(int index) const;
  double inputRate(int index) const;

  /// Integrates to t; false once the run has stopped: at solver.t_end, or for the reason in
  /// outcome().message. With inputs the integrator stops exactly at t; without, it may step past
  /// t, as `crane-sim run` does, and the observations are interpolated at t. Setting `*stop`
  /// (from another thread) ends the run at its next step, as a signal ends `crane-sim run`.
  bool advanceTo(double t, const std::atomic<bool>* stop = nullptr);
  bool step(double dt) { return advanceTo(time() + dt); }
  /// The time the observations are at: the last advance's t.
  double time() const { return observed_t_; }
  SimulationOutcome outcome() const { return simulation_->outcome(); }

  /// The run's state now, to go on from later in this session or another of the same scene: the
  /// integrator restarts here, so that this run and every restore of the state go on alike, bit
  /// for bit (Simulation::save).
  SimulationState save();
  void restore(const SimulationState& state);
  /// The same through a file (HDF5), for a run that goes on in another process.
  void saveFile(const std::string& path);
  void restoreFile(const std::string& path);

  /// The state at time(): the DAE vector [q, dq, λ(, μ)] (Assembler::vOffset, lambdaOffset),
  /// valid until the next advance.
  const double* state() const { return interpolated_ ? observed_.data() : simulation_->state(); }
  /// The index of the joint named `name`; std::invalid_argument (with "did you mean") otherwise.
  int joint(const std::string& name) const;
  /// A joint's position and velocity in the inertial frame now.
  Vec3 jointPosition(int joint) const;
  Vec3 jointVelocity(int joint) const;

  /// How the line from joint `pivot` down to joint `hanging` (a hook below its sheave) swings: its
  /// angles from the downward vertical (gravity) in the vertical plane through the pivot and the
  /// vertical axis through the origin (radial, > 0 outward) and across that plane (> 0 in the
  /// sense of a positive turn about the upward axis), rad, and their rates, rad/s.
  struct Sway {
    double radial = 0.0, across = 0.0, radial_rate = 0.0, across_rate = 0.0;
  };
  Sway sway(int hanging, int pivot) const;

  /// The index of the constraint named `name`; std::invalid_argument (with "did you mean").
  int constraint(const std::string& name) const;
  /// The load a constraint carries now (constraintReaction): the force its rows carry to its
  /// second joint and the moment about that joint, in the first joint's axes. A rope's tension
  /// at its end is the force of the joint holding it there.
  ConstraintReaction constraintLoad(int constraint) const;
  /// The axial force along a rope member now: kTensionPoints per element, from each element's
  /// first node to its second (N, 0 where slack); std::invalid_argument for no such rope. A
  /// reeved rope's parts, winch to dead end, stand for its elements: kTensionPoints equal values
  /// each (a massless part's tension is one), its sheaves' losses by the direction the rope runs
  /// now, as the results file's /ropes/<rope>/part_tension.
  std::vector<double> ropeTensions(const std::string& rope) const;
  /// The power a driven constraint's drive delivers to the crane now, W: λ·Φ_t of its rows, as
  /// the energy books count drive work (0 for a constraint without a drive). Negative while the
  /// crane drives it (braking, lowering).
  double drivePower(int constraint) const;
  /// The power the winch of a rope delivers to the crane now, W: its elements' power through the
  /// change of their unstretched length, as the energy books count winch work (positive while it
  /// reels a rope under tension in; a reeved rope's includes what its sheaves dissipate);
  /// std::invalid_argument for no such rope.
  double winchPower(const std::string& rope) const;
  /// Kinetic energy ½ dqᵀ M dq, and gravity's potential plus strain energy (J).
  double kineticEnergy() const;
  double potentialEnergy() const;

 private:
  /// Passes the run's samples to the recorder while there is one.
  struct RecordingSink final : SampleSink {
    std::unique_ptr<ResultsRecorder> recorder;
    void sample(double t, const double* y, const WorkTerms& work) override {
      if (recorder) recorder->sample(t, y, work);
    }
  };

  void start();
  void observed(double t);
  /// The scene's rope named `name`; std::invalid_argument for none.
  const MemberSpec& rope(const std::string& name) const;
  /// Accelerations and multipliers consistent with the state at time() (the saddle-point
  /// system (4-3)), solved once per observed time, as the results file's are; with them, the
  /// constraints at that state (motion_constraints_).
  const DynamicState& motion() const;

  Scene scene_;
  bool recording_;
  std::unique_ptr<Model> model_;
  std::unique_ptr<Assembler> assembler_;
  DynamicState initial_;
  RecordingSink sink_;
  std::unique_ptr<Simulation> simulation_;
  double observed_t_ = 0.0;
  bool interpolated_ = false;    // the integrator is past observed_t_: observed_ holds the state there
  std::vector<double> observed_;
  mutable AccelerationSolver accelerations_;
  mutable DynamicState motion_;
  mutable ConstraintState motion_constraints_;
  mutable bool motion_known_ = false;
};

}  // namespace cranesim
