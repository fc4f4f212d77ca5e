#include "cranesim/planning/clearance.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

namespace cranesim {
namespace {

/// The radius of the circle about a truss's axis that holds its end sections' chords and their tubes.
double enclosingRadius(const TrussDescription& truss) {
  double radius = 0.0;
  for (const TrussEndSection& section : truss.sections)
    for (const Eigen::Vector2d& node : section.nodes) radius = std::max(radius, node.norm());
  return radius + truss.main_tube.outer_radius;
}

int jointNamed(const Model& model, const std::string& name) {
  const int joint = model.findJoint(name);
  if (joint < 0) throw std::logic_error(fmt::format("the model has no joint '{}'", name));
  return joint;
}

}  // namespace

std::vector<CranePart> craneParts(const Scene& scene, const Model& model, const std::string& load_joint, double load_radius) {
  std::vector<CranePart> parts;
  for (const MemberSpec& m : scene.members) {
    if (m.reeving) continue;
    CranePart part{m.name, {}, 0.0};
    if (m.type == MemberType::Truss) {
      const auto truss = std::find_if(scene.trusses.begin(), scene.trusses.end(),
                                      [&](const TrussDescription& d) { return d.name == m.truss; });
      part.radius = truss == scene.trusses.end() ? 0.0 : enclosingRadius(*truss);
      part.joints = {jointNamed(model, m.name + ".start"), jointNamed(model, m.name + ".end")};
    } else {
      part.radius = m.section.outer_radius > 0.0 ? m.section.outer_radius : std::sqrt(m.section.area / std::numbers::pi);
      for (int i = 0; i <= m.segments; ++i) part.joints.push_back(jointNamed(model, fmt::format("{}.n{}", m.name, i)));
    }
    parts.push_back(std::move(part));
  }
  const std::string load = load_joint.substr(0, load_joint.find('.'));
  parts.push_back({load, {jointNamed(model, load_joint)}, load_radius});
  return parts;
}

ClearanceRecord measureClearance(const std::vector<Obstacle>& obstacles, const std::vector<CranePart>& parts,
                                 const ResultsRecorder& recorder, double margin) {
  const auto started = std::chrono::steady_clock::now();
  ClearanceRecord r;
  for (const CranePart& p : parts) r.parts.push_back(p.name);
  for (const Obstacle& o : obstacles) r.obstacles.push_back(o.name);
  const auto n_obstacles = static_cast<Eigen::Index>(obstacles.size()), n_parts = static_cast<Eigen::Index>(parts.size());
  r.minimum = Eigen::MatrixXd::Constant(n_obstacles, n_parts, std::numeric_limits<double>::infinity());
  r.time = Eigen::MatrixXd::Zero(n_obstacles, n_parts);
  r.margin = margin;
  r.samples = recorder.samples();
  r.distance = std::numeric_limits<double>::infinity();
  const std::vector<double>& times = recorder.time();
  for (std::size_t k = 0; k < r.samples; ++k) {
    if (k > 0) r.largest_interval = std::max(r.largest_interval, times[k] - times[k - 1]);
    for (Eigen::Index j = 0; j < n_parts; ++j) {
      const CranePart& part = parts[j];
      const auto at = [&](int joint) { return Vec3(Eigen::Map<const Vec3>(&recorder.jointPositions(joint)[3 * k])); };
      for (std::size_t s = 0; s + 1 < std::max<std::size_t>(part.joints.size(), 2); ++s) {
        const Capsule capsule{at(part.joints[s]), at(part.joints[std::min(s + 1, part.joints.size() - 1)]), part.radius};
        for (Eigen::Index i = 0; i < n_obstacles; ++i) {
          const double d = signedDistance(obstacles[i].shape, capsule);
          if (d < r.minimum(i, j)) r.minimum(i, j) = d, r.time(i, j) = times[k];
          if (d < r.distance) r.distance = d, r.t = times[k], r.part = static_cast<int>(j), r.obstacle = static_cast<int>(i);
        }
      }
    }
  }
  r.compute_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return r;
}

}  // namespace cranesim
