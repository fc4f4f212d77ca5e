#pragma once
// Collects the samples of a run and writes the HDF5 results file (docs/results-format.md).

#include <string>
#include <vector>

#include "cranesim/assembly/assembler.hpp"
#include "cranesim/crane/crane_figures.hpp"
#include "cranesim/crane/envelope_monitor.hpp"
#include "cranesim/solvers/dynamics.hpp"
#include "cranesim/solvers/statics.hpp"

namespace cranesim {

/// Multipliers are recomputed at each sample from the saddle-point system (4-3) for the
/// sampled (q, dq): the integrator's index-2 λ is converged only to Newton accuracy, while the
/// recorded constraint forces should be as accurate as the recorded state.
class ResultsRecorder final : public SampleSink {
 public:
  explicit ResultsRecorder(const Assembler& assembler);
  void sample(double t, const double* y, const WorkTerms& work) override;

  std::size_t samples() const { return time_.size(); }
  /// Forgets the samples at t and after (a run that goes on from an earlier state).
  void keepBefore(double t);
  const std::vector<double>& time() const { return time_; }
  /// Column k of the recorded DAE state over time.
  std::vector<double> stateColumn(int k) const;
  /// Position of a joint over time (3 per sample).
  const std::vector<double>& jointPositions(int joint) const { return joint_position_[joint]; }
  /// T + V − drive − load − winch + dissipated (WorkTerms): constant for an exact solution.
  const std::vector<double>& energyBalance() const { return balance_; }
  /// The energy the run moves about: max over the samples of T + |V − V(t0)| + |drive| + |load|
  /// + |winch| + dissipated, J. The balance's drift is measured against it.
  double energyScale() const;
  /// max |balance − balance(t0)| / energyScale() over the samples (0 for a run at rest).
  double relativeBalanceDrift() const;
  const std::vector<double>& driveWork() const { return drive_work_; }
  const std::vector<double>& winchWork() const { return winch_work_; }
  const std::vector<double>& dissipated() const { return dissipated_; }
  const std::vector<double>& kineticEnergy() const { return kinetic_; }
  const std::vector<double>& potentialEnergy() const { return potential_; }
  /// Body rotation matrices over time (9 per sample, row-major).
  const std::vector<double>& bodyRotations(int node) const { return body_rotation_[node]; }
  /// Body angular velocities over time (3 per sample, body frame).
  const std::vector<double>& bodyAngularVelocities(int node) const { return body_omega_[node]; }
  const std::vector<double>& positionResidual() const { return residual_position_; }
  const std::vector<double>& velocityResidual() const { return residual_velocity_; }
  /// The resultant wind force on Model::wind_parts[part] over time (3 per sample, N, inertial).
  const std::vector<double>& windForces(int part) const { return wind_forces_[part]; }
  /// The part tensions of Model::reeved_ropes[rope] over time (its parts per sample, N, from the
  /// winch to the dead end).
  const std::vector<double>& partTensions(int rope) const { return part_tensions_[rope]; }
  /// The crane's envelope over the samples: what left it, when, how far (/envelope).
  const EnvelopeMonitor& envelope() const { return envelope_; }

  /// Memory a run's results take while they are recorded and written (the samples and the
  /// file's image), estimated from the model's size and the number of output samples.
  static double estimatedBytes(const Model& model, double samples);

  struct Metadata {
    std::string scene_path, scene_text, formulation;
    double t_end_requested = 0.0;
    const CraneFigures* crane = nullptr;  // an equilibrium's figures (`crane-sim static`): /crane
  };
  /// Writes the samples so far to `path` as a checkpoint of a run that is still going: status
  /// incomplete, a message saying so. A run killed outright (SIGKILL, power loss) leaves this.
  void writeCheckpoint(const std::string& path, const Metadata& meta, double wall_time_s) const;

  /// Writes under `path`.partial and renames to `path`; marks the file incomplete when the
  /// run did not finish.
  void write(const std::string& path, const Metadata& meta, const SimulationOutcome& outcome) const;

 private:
  /// The consistent accelerations and multipliers at a sample (the saddle-point system (4-3));
  /// IDAS' multipliers and NaN accelerations where it is singular.
  DynamicState motionAt(double t, const double* y, const ConstraintState& constraints,
                        const Eigen::SparseMatrix<double>& mass) const;

  const Assembler& assembler_;
  mutable AccelerationSolver accelerations_;  // the multipliers at every sample
  std::vector<double> time_, state_;
  std::vector<std::vector<double>> body_position_, body_rotation_, body_velocity_, body_omega_;
  std::vector<std::vector<double>> joint_position_, joint_rotation_;
  std::vector<double> kinetic_, potential_, drive_work_, load_work_, winch_work_, dissipated_, balance_;
  std::vector<double> residual_position_, residual_velocity_;
  std::vector<std::vector<double>> section_forces_;  // per Model::section_force_groups: 12 per element and sample
  std::vector<int> load_constraints_;                 // output.constraint_loads, as indices into Model::constraints
  std::vector<std::vector<double>> constraint_loads_;  // per recorded constraint: force and moment, 6 per sample
  std::vector<std::vector<int>> tipping_supports_;     // per output.tipping_lines: its supports, as constraint indices
  std::vector<std::vector<double>> tipping_moments_;   // per tipping line: 1 per sample
  std::vector<std::vector<double>> wind_forces_;       // per Model::wind_parts: the resultant wind force, 3 per sample
  std::vector<std::vector<double>> part_tensions_;     // per Model::reeved_ropes: its parts' tensions, one each per sample
  EnvelopeMonitor envelope_;
};

/// Writes an equilibrium as a one-sample results file (`crane-sim static`, formulation "static"):
/// complete, or incomplete with `unstable` as its message when that says why it is unstable.
void writeEquilibriumResults(const std::string& path, const Assembler& assembler, const StaticResult& eq,
                             const std::string& scene_path, const std::string& scene_text, const std::string& unstable,
                             const CraneFigures* crane = nullptr);

/// Refuses, before any work, a run whose results would not fit in memory (more than 4 GiB):
/// throws SceneError at output.interval with the estimate.
void requireResultsFit(const Scene& scene, const Model& model);

}  // namespace cranesim
