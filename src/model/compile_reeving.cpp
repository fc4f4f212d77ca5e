#include "compile_reeving.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "cranesim/model/massive_reeved_rope_element.hpp"
#include "cranesim/model/reeved_rope_element.hpp"

namespace cranesim {
namespace {

/// The path of the rope `m` over the joints it names: its points on the nodes of their bodies
/// and members, those nodes (into `nodes`, their coordinates into `q` and `v`), and the joints.
struct PlacedPath {
  RopePath path;
  std::vector<int> joints;
};

PlacedPath placePath(const Model& model, const MemberSpec& m, std::vector<int>& nodes, std::vector<int>& q, std::vector<int>& v) {
  const ReevingSpec& reeving = *m.reeving;
  struct Named {
    const std::string& joint;
    const SourceLocation& where;
  };
  std::vector<Named> points = {{reeving.winch, reeving.where_winch}};
  for (const SheaveSpec& s : reeving.sheaves) points.push_back({s.joint, s.where});
  points.push_back({reeving.dead_end, reeving.where_dead_end});

  PlacedPath out;
  for (const Named& p : points) {
    const int j = model.findJoint(p.joint);
    if (j < 0) throw SceneError(p.where, fmt::format("unknown joint '{}'", p.joint));
    out.joints.push_back(j);
    const Joint& joint = model.joints[j];
    if (joint.node < 0) {
      out.path.points.push_back({-1, joint.offset});
      continue;
    }
    auto found = std::find(nodes.begin(), nodes.end(), joint.node);
    if (found == nodes.end()) {
      if (static_cast<int>(nodes.size()) == RopePath::kMaxNodes)
        throw SceneError(p.where, fmt::format("rope '{}' runs over more than {} bodies or member nodes", m.name,
                                              RopePath::kMaxNodes));
      const Node& node = model.nodes[joint.node];
      out.path.slots.push_back({static_cast<int>(q.size()), node.size(), node.hasRotation()});
      for (int k = 0; k < node.size(); ++k) q.push_back(node.q + k), v.push_back(node.v + k);
      nodes.push_back(joint.node);
      found = nodes.end() - 1;
    }
    out.path.points.push_back({static_cast<int>(found - nodes.begin()), joint.offset});
  }
  if (nodes.empty()) throw SceneError(m.where, fmt::format("rope '{}' runs over ground joints only: it moves nothing", m.name));
  return out;
}

/// λ_i of each sheave: μ θ of a capstan, −ln η of a turning sheave.
template <class Kernel> void setFriction(Kernel& k, const ReevingSpec& reeving) {
  for (std::size_t i = 0; i < reeving.sheaves.size(); ++i) {
    const SheaveSpec& s = reeving.sheaves[i];
    k.friction_exponent[i] = s.friction > 0.0 ? s.friction * s.wrap.value() : -std::log(s.efficiency);
  }
}

void addMassless(Model& model, const MemberSpec& m) {
  std::vector<int> nodes, q, v;
  PlacedPath placed = placePath(model, m, nodes, q, v);
  ReevedRopeKernel k;
  k.total_length = m.length ? *m.length : Profile(ConstantProfile{m.reeving->drawn_length});
  k.section = m.section;
  k.material = m.material;
  k.damping = m.damping;
  k.points = static_cast<int>(placed.joints.size());
  k.pre_sliding = m.reeving->pre_sliding;
  setFriction(k, *m.reeving);
  model.reeved_ropes.push_back(static_cast<int>(model.elements.size()));
  model.elements.push_back(std::make_unique<ReevedRopeElement>(m.name, std::move(k), std::move(placed.path), std::move(nodes),
                                                               std::move(q), std::move(v)));
}

/// The massive form: the parts' inner nodes placed evenly on the drawn chords, the sheaves'
/// material coordinates where the rope's length at the start shares out over the chords.
void addMassive(Model& model, const MemberSpec& m) {
  const ReevingSpec& reeving = *m.reeving;
  std::vector<int> nodes, q, v;
  PlacedPath placed = placePath(model, m, nodes, q, v);
  MassiveReevingKernel k;
  k.total_length = m.length ? *m.length : Profile(ConstantProfile{reeving.drawn_length});
  k.section = m.section;
  k.material = m.material;
  k.damping = m.damping;
  k.speed_band = reeving.speed_band;
  k.points = static_cast<int>(placed.joints.size());
  k.elements_per_part = reeving.elements_per_part;
  setFriction(k, reeving);
  for (std::size_t i = 0; i < reeving.sheaves.size(); ++i)
    k.sheave_mass[i] = k.sheaveMass(reeving.sheaves[i].radius, reeving.sheaves[i].inertia);

  std::vector<Vec3> at;
  for (const int j : placed.joints) at.push_back(model.jointFrame(model.q0.data(), j).r);
  std::vector<double> beyond(at.size(), 0.0);  // Σ of the chords from each point to the dead end
  for (std::size_t p = at.size() - 1; p-- > 0;) beyond[p] = beyond[p + 1] + (at[p + 1] - at[p]).norm();
  const double scale = k.total_length(model.solver.t_start) / beyond[0];
  const int n = k.elements_per_part;
  for (int part = 0; part + 1 < k.points; ++part)
    for (int e = 1; e < n; ++e) {
      const int node = model.addNode(fmt::format("{}.part{}.n{}", m.name, part, e), NodeKind::Point, m.name);
      model.q0.segment<3>(model.nodes[node].q) = at[part] + (static_cast<double>(e) / n) * (at[part + 1] - at[part]);
      nodes.push_back(node);
      for (int c = 0; c < 3; ++c) q.push_back(model.nodes[node].q + c), v.push_back(model.nodes[node].v + c);
    }
  for (int i = 1; i + 1 < k.points; ++i) {
    const int node = model.addNode(fmt::format("{}.sheave{}", m.name, i), NodeKind::Material, m.name);
    model.q0(model.nodes[node].q) = scale * beyond[i];
    nodes.push_back(node);
    q.push_back(model.nodes[node].q), v.push_back(model.nodes[node].v);
  }
  model.reeved_ropes.push_back(static_cast<int>(model.elements.size()));
  model.elements.push_back(std::make_unique<MassiveReevedRopeElement>(m.name, std::move(k), std::move(placed.path),
                                                                      std::move(nodes), std::move(q), std::move(v)));
}

}  // namespace

void compileReevedRope(Model& model, const MemberSpec& m) {
  if (m.reeving->elements_per_part > 0) addMassive(model, m);
  else addMassless(model, m);
  if (m.length) model.parameter_profiles.push_back(*m.length);
  const std::vector<std::string> joints = [&] {
    std::vector<std::string> out = {m.reeving->winch};
    for (const SheaveSpec& s : m.reeving->sheaves) out.push_back(s.joint);
    out.push_back(m.reeving->dead_end);
    return out;
  }();
  for (std::size_t p = 0; p + 1 < joints.size(); ++p)
    model.drawing_lines.push_back({model.findJoint(joints[p]), model.findJoint(joints[p + 1])});
}

}  // namespace cranesim
