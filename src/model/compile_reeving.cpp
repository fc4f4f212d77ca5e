#include "compile_reeving.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "cranesim/model/reeved_rope_element.hpp"

namespace cranesim {

void compileReevedRope(Model& model, const MemberSpec& m) {
  const ReevingSpec& reeving = *m.reeving;
  struct Named {
    const std::string& joint;
    const SourceLocation& where;
  };
  std::vector<Named> points = {{reeving.winch, reeving.where_winch}};
  for (const SheaveSpec& s : reeving.sheaves) points.push_back({s.joint, s.where});
  points.push_back({reeving.dead_end, reeving.where_dead_end});

  std::vector<ReevedRopeElement::PathPoint> path;
  std::vector<ReevedRopeElement::Slot> slots;
  std::vector<int> nodes, q, v;
  for (const Named& p : points) {
    const int j = model.findJoint(p.joint);
    if (j < 0) throw SceneError(p.where, fmt::format("unknown joint '{}'", p.joint));
    const Joint& joint = model.joints[j];
    if (joint.node < 0) {
      path.push_back({-1, joint.offset});
      continue;
    }
    auto found = std::find(nodes.begin(), nodes.end(), joint.node);
    if (found == nodes.end()) {
      if (static_cast<int>(nodes.size()) == ReevedRopeElement::kMaxNodes)
        throw SceneError(p.where, fmt::format("rope '{}' runs over more than {} bodies or member nodes", m.name,
                                              ReevedRopeElement::kMaxNodes));
      const Node& node = model.nodes[joint.node];
      slots.push_back({static_cast<int>(q.size()), node.size(), node.hasRotation()});
      for (int k = 0; k < node.size(); ++k) q.push_back(node.q + k), v.push_back(node.v + k);
      nodes.push_back(joint.node);
      found = nodes.end() - 1;
    }
    path.push_back({static_cast<int>(found - nodes.begin()), joint.offset});
  }
  if (nodes.empty()) throw SceneError(m.where, fmt::format("rope '{}' runs over ground joints only: it moves nothing", m.name));

  ReevedRopeKernel k;
  k.total_length = m.length ? *m.length : Profile(ConstantProfile{reeving.drawn_length});
  k.section = m.section;
  k.material = m.material;
  k.damping = m.damping;
  k.speed_band = reeving.speed_band;
  k.points = static_cast<int>(path.size());
  for (std::size_t i = 0; i < reeving.sheaves.size(); ++i) {
    const SheaveSpec& s = reeving.sheaves[i];
    k.friction_exponent[i] = s.friction > 0.0 ? s.friction * s.wrap.value() : -std::log(s.efficiency);
  }
  if (m.length) model.parameter_profiles.push_back(*m.length);
  for (std::size_t p = 0; p + 1 < points.size(); ++p)
    model.drawing_lines.push_back({model.findJoint(points[p].joint), model.findJoint(points[p + 1].joint)});
  model.reeved_ropes.push_back(static_cast<int>(model.elements.size()));
  model.elements.push_back(std::make_unique<ReevedRopeElement>(m.name, std::move(k), std::move(path), std::move(slots),
                                                               std::move(nodes), std::move(q), std::move(v)));
}

}  // namespace cranesim
