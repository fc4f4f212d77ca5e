#include "cranesim/io/modes_writer.hpp"

#include <array>

#include "cranesim/version.hpp"
#include "hdf5_file.hpp"

namespace cranesim {
namespace {

/// One label per velocity coordinate, "<node>.<component>": displacements r_x…, body-frame
/// rotations theta_x…, the stretch of spline beam nodes, the slope of spline rope nodes.
std::vector<std::string> velocityLabels(const Model& model) {
  static const std::array<const char*, 3> r{"r_x", "r_y", "r_z"};
  static const std::array<const char*, 3> theta{"theta_x", "theta_y", "theta_z"};
  static const std::array<const char*, 3> slope{"slope_x", "slope_y", "slope_z"};
  std::vector<std::string> labels(model.nv);
  for (const Node& n : model.nodes) {
    if (!n.hasPosition()) {
      labels[n.v] = n.name + ".material";
      continue;
    }
    for (int k = 0; k < 3; ++k) labels[n.v + k] = n.name + "." + r[k];
    if (n.hasRotation())
      for (int k = 0; k < 3; ++k) labels[n.v + 3 + k] = n.name + "." + theta[k];
    if (n.kind == NodeKind::FrameStretch) labels[n.v + 6] = n.name + ".stretch";
    if (n.kind == NodeKind::PointSlope)
      for (int k = 0; k < 3; ++k) labels[n.v + 3 + k] = n.name + "." + slope[k];
  }
  return labels;
}

/// Displacement of a joint origin for the velocity-coordinate perturbation `shape`:
/// δr_J = δr + R (δθ × r_BJ) (R → R(I + δθ̃), 4-5); zero on the ground.
Vec3 jointDisplacement(const Model& model, const VecX& q, int joint, const VecX& shape) {
  const Joint& J = model.joints[joint];
  if (J.node < 0) return Vec3::Zero();
  const Node& n = model.nodes[J.node];
  Vec3 d = shape.segment<3>(n.v);
  if (n.hasRotation()) d += model.nodeFrame(q.data(), J.node).R * Vec3(shape.segment<3>(n.v + 3)).cross(J.offset);
  return d;
}

}  // namespace

void writeModes(const std::string& path, const Model& model, const VecX& q_eq, const ModalResult& modes,
                const ModesMetadata& meta) {
  writeResultsFile(path, [&](Hdf5File& file) {
    file.attribute("/", "engine_version", std::string(kVersion));
    file.attribute("/", "scene_path", meta.scene_path);
    file.attribute("/", "scene_text", meta.scene_text);
    file.attribute("/", "status", std::string("complete"));
    file.attribute("/", "analysis", std::string("modes"));
    file.attribute("/", "t", meta.t);
    file.attribute("/", "free_dofs", static_cast<long>(modes.free_dofs));
    file.attribute("/", "rigid_modes", static_cast<long>(modes.rigid_modes));
    file.attribute("/", "zero_threshold", modes.zero_threshold);
    file.attribute("/", "stiffness_asymmetry", modes.stiffness_asymmetry);
    file.attribute("/", "force_residual", modes.force_residual);

    const auto count = static_cast<hsize_t>(modes.frequencies.size());
    const auto nv = static_cast<hsize_t>(model.nv), nj = static_cast<hsize_t>(model.joints.size());
    file.writeDoubles("/modes/frequency", {count}, modes.frequencies.data());
    file.writeDoubles("/modes/omega_squared", {count}, modes.omega_squared.data());
    if (!meta.labels.empty()) file.writeStrings("/modes/label", {count}, meta.labels);
    // Column k of the nv × count matrix is contiguous: row k of a (count, nv) dataset.
    file.writeDoubles("/modes/shapes", {count, nv}, modes.shapes.data());
    std::vector<double> displacements;
    displacements.reserve(count * nj * 3);
    for (hsize_t k = 0; k < count; ++k)
      for (hsize_t j = 0; j < nj; ++j) {
        const Vec3 d = jointDisplacement(model, q_eq, static_cast<int>(j), modes.shapes.col(k));
        displacements.insert(displacements.end(), d.data(), d.data() + 3);
      }
    file.writeDoubles("/modes/joint_displacements", {count, nj, 3}, displacements.data());

    std::vector<double> positions;
    std::vector<std::string> joints;
    for (std::size_t j = 0; j < model.joints.size(); ++j) {
      const Frame f = model.jointFrame(q_eq.data(), static_cast<int>(j));
      positions.insert(positions.end(), f.r.data(), f.r.data() + 3);
      joints.push_back(model.joints[j].name);
    }
    file.writeDoubles("/equilibrium/q", {static_cast<hsize_t>(model.nq)}, q_eq.data());
    file.writeDoubles("/equilibrium/lambda", {static_cast<hsize_t>(model.m)}, modes.lambda.data());
    file.writeDoubles("/equilibrium/joint_positions", {nj, 3}, positions.data());
    file.writeStrings("/model/joints", {nj}, joints);
    file.writeStrings("/model/velocity_labels", {nv}, velocityLabels(model));
  });
}

}  // namespace cranesim
