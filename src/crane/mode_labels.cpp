#include "cranesim/crane/mode_labels.hpp"

#include <algorithm>

#include "cranesim/assembly/assembler.hpp"

namespace cranesim {
namespace {

enum class Part { Load, Boom, Ropes, Rest };

Part partOf(const Scene& scene, const Node& node) {
  if (node.member.empty()) return node.name == scene.crane->load ? Part::Load : Part::Rest;
  const auto m = std::find_if(scene.members.begin(), scene.members.end(),
                              [&](const MemberSpec& s) { return s.name == node.member; });
  if (m == scene.members.end()) return Part::Rest;
  return m->type == MemberType::Rope || m->type == MemberType::StrutTie ? Part::Ropes : Part::Boom;
}

/// The boom plane's directions: `up`, and its unit normal `across`, horizontal and across the
/// line from the foot to the head.
struct BoomPlane {
  Vec3 up, across;
};

BoomPlane boomPlane(const Scene& scene, const Model& model, const double* q) {
  const Constraint& foot = model.constraints[static_cast<std::size_t>(model.findConstraint(scene.crane->boom_foot))];
  const Vec3 up = model.gravity.norm() > 0.0 ? Vec3(-model.gravity.normalized()) : Vec3::UnitZ();
  const Vec3 reach = model.jointFrame(q, model.findJoint(scene.crane->boom_head)).r - model.jointFrame(q, foot.joint1).r;
  return {up, up.cross(reach).normalized()};
}

std::string labelOf(const ModeShares& s) {
  const double largest = std::max({s.load(), s.boom(), s.ropes, s.rest});
  if (largest == s.load()) {
    const double load = std::max({s.load_sway_in_plane, s.load_sway_out_of_plane, s.load_vertical, s.load_turning});
    return load == s.load_sway_in_plane       ? "in-plane sway"
           : load == s.load_sway_out_of_plane ? "out-of-plane sway"
           : load == s.load_vertical          ? "load bouncing"
                                              : "load turning";
  }
  if (largest == s.boom()) return s.boom_in_plane >= s.boom_out_of_plane ? "boom bending in plane" : "boom bending out of plane";
  return largest == s.ropes ? "rope" : "rest";
}

}  // namespace

std::vector<ModeLabel> labelModes(const Scene& scene, const Model& model, const VecX& q_eq, double t, const ModalResult& modal) {
  const Assembler assembler(model);
  const Eigen::SparseMatrix<double> M = assembler.massMatrix(t, q_eq.data());
  const BoomPlane plane = boomPlane(scene, model, q_eq.data());
  const auto load_body = std::find_if(scene.bodies.begin(), scene.bodies.end(),
                                      [&](const RigidBodySpec& b) { return b.name == scene.crane->load; });
  std::vector<Part> parts;
  for (const Node& node : model.nodes) parts.push_back(partOf(scene, node));  // the reader found the load's body
  std::vector<ModeLabel> labels;
  for (int k = 0; k < modal.shapes.cols(); ++k) {
    const VecX phi = modal.shapes.col(k), momentum = M * phi;
    ModeShares s;
    for (std::size_t i = 0; i < model.nodes.size(); ++i) {
      const Node& node = model.nodes[i];
      const Mat3 R = node.hasRotation() ? model.nodeFrame(q_eq.data(), static_cast<int>(i)).R : Mat3::Identity();
      if (parts[i] == Part::Load) {
        // m v_c² + ωᵀ I_c ω, v_c = v + R (ω × c) with ω in the body's frame.
        const Vec3 omega = phi.segment<3>(node.v + 3);
        const Vec3 v = phi.segment<3>(node.v) + R * omega.cross(load_body->centroid);
        const double across = v.dot(plane.across), vertical = v.dot(plane.up);
        s.load_sway_out_of_plane += load_body->mass * across * across;
        s.load_vertical += load_body->mass * vertical * vertical;
        s.load_sway_in_plane += load_body->mass * (v.squaredNorm() - across * across - vertical * vertical);
        s.load_turning += omega.dot(load_body->inertia * omega);
        continue;
      }
      const double total = phi.segment(node.v, node.size()).dot(momentum.segment(node.v, node.size()));
      if (parts[i] == Part::Ropes) s.ropes += total;
      if (parts[i] == Part::Rest) s.rest += total;
      if (parts[i] != Part::Boom) continue;
      // Translations across the plane leave it; turns about its normal keep the member in it.
      double out = phi.segment<3>(node.v).dot(plane.across) * momentum.segment<3>(node.v).dot(plane.across);
      if (node.hasRotation()) {
        const Vec3 w = R * phi.segment<3>(node.v + 3), h = R * momentum.segment<3>(node.v + 3);
        out += w.dot(h) - w.dot(plane.across) * h.dot(plane.across);
      }
      s.boom_out_of_plane += out;
      s.boom_in_plane += total - out;
    }
    labels.push_back({s, modal.rigid[static_cast<std::size_t>(k)] ? "rigid" : labelOf(s)});
  }
  return labels;
}

}  // namespace cranesim
