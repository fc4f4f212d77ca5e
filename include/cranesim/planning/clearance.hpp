#pragma once
// Clearance of a simulated crane motion from the obstacles (docs/planning.md, "Obstacles and
// clearance"): the crane's parts as chains of capsules through their simulated joints, and their
// smallest signed distance to each obstacle over the run's output samples.

#include <string>
#include <vector>

#include "cranesim/io/results_writer.hpp"
#include "cranesim/model/model.hpp"
#include "cranesim/model/scene.hpp"
#include "cranesim/planning/obstacle.hpp"

namespace cranesim {

/// A part of the crane: capsules of `radius` from each of its joints to the next (a sphere when
/// it has one joint).
struct CranePart {
  std::string name;
  std::vector<int> joints;
  double radius = 0.0;
};

/// The crane's parts: each truss member (lattice section) a capsule from its end sections, its
/// radius that of the circle round its end sections' chords and their tubes; each other member
/// (ropes, strut ties, beams) the chords between its nodes, its radius its round section's (or
/// that of a round section of its area); the load a sphere of `load_radius` about
/// the joint `load_joint`. Reeved ropes and the other rigid bodies are not parts.
std::vector<CranePart> craneParts(const Scene& scene, const Model& model, const std::string& load_joint, double load_radius);

/// Each part's smallest signed distance from each obstacle over a run, when it came, and the
/// smallest of them all.
struct ClearanceRecord {
  std::vector<std::string> parts, obstacles;
  Eigen::MatrixXd minimum, time;  // obstacle × part: m, s
  double margin = 0.0;
  double distance = 0.0, t = 0.0;  // the smallest of `minimum`, and when
  int part = -1, obstacle = -1;    // whose
  std::size_t samples = 0;
  double largest_interval = 0.0;  // between two samples, s
  double compute_s = 0.0;         // wall time of the check
  bool failed() const { return distance < margin; }
};

/// The parts' clearance from the obstacles at every sample the recorder holds.
ClearanceRecord measureClearance(const std::vector<Obstacle>& obstacles, const std::vector<CranePart>& parts,
                                 const ResultsRecorder& recorder, double margin);

}  // namespace cranesim
