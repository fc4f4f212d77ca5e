#include "cranesim/model/model.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "cranesim/math/rotation.hpp"

namespace cranesim {

int Model::addNode(std::string name, NodeKind kind, std::string member) {
  Node n{std::move(name), kind, nq, nv, std::move(member)};
  nq += n.size();
  nv += n.size();
  nodes.push_back(std::move(n));
  q0.conservativeResize(nq);
  v0.conservativeResize(nv);
  q0.tail(nodes.back().size()).setZero();
  v0.tail(nodes.back().size()).setZero();
  return static_cast<int>(nodes.size()) - 1;
}

VecX Model::absoluteTolerances() const {
  const AbsoluteTolerance& atol = solver.atol;
  VecX out(nq + nv);
  for (const Node& node : nodes) {
    // Every kind starts with r (or is the length σ); the rest (φ, ‖r'‖, r') is dimensionless.
    const int lengths = node.hasPosition() ? 3 : 1;
    out.segment(node.q, node.size()).setConstant(atol.rotation);
    out.segment(node.q, lengths).setConstant(atol.position);
    out.segment(nq + node.v, node.size()).setConstant(atol.angular_velocity);
    out.segment(nq + node.v, lengths).setConstant(atol.velocity);
  }
  return out;
}

Frame Model::nodeFrame(const double* q, int node) const {
  const Node& n = nodes[node];
  return {Vec3(q + n.q), n.hasRotation() ? rotationMatrix<double>(Vec3(q + n.q + 3)) : Mat3::Identity()};
}

Frame Model::jointFrame(const double* q, int joint) const {
  const Joint& j = joints[joint];
  if (j.node < 0) return {j.offset, j.rotation};
  const Frame n = nodeFrame(q, j.node);
  return {n.r + n.R * j.offset, n.R * j.rotation};
}

int Model::findJoint(const std::string& name) const {
  for (std::size_t k = 0; k < joints.size(); ++k)
    if (joints[k].name == name) return static_cast<int>(k);
  return -1;
}

int Model::findConstraint(const std::string& name) const {
  for (std::size_t k = 0; k < constraints.size(); ++k)
    if (constraints[k].name == name) return static_cast<int>(k);
  return -1;
}

int Model::findInput(const std::string& name) const {
  for (std::size_t k = 0; k < inputs.size(); ++k)
    if (inputs[k].name == name) return static_cast<int>(k);
  return -1;
}

Profile Model::attachInput(const Profile& profile, const std::string& name, const std::string& what,
                           const SourceLocation& where) {
  if (!profile.input()) return profile;
  if (const int k = findInput(name); k >= 0)
    throw SceneError(where, fmt::format("a {} and a {} are both inputs named '{}': an input's name must be unique",
                                        inputs[k].what, what, name));
  Profile attached = profile;
  InputProfile& input = *attached.input();
  input.signal = std::make_shared<InputSignal>(input.spec, solver.t_start);
  inputs.push_back({name, what, input.signal});
  return attached;
}

std::vector<double> Model::breakpoints() const {
  std::vector<double> out;
  const auto add = [&](const Profile& p) {
    for (double t : p.breakpoints())
      if (t > solver.t_start && t < solver.t_end) out.push_back(t);
  };
  for (const Constraint& c : constraints)
    if (c.drive) add(*c.drive);
  for (const Load& l : loads) add(l.scale);
  for (const Profile& p : parameter_profiles) add(p);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace cranesim
