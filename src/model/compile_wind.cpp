#include "compile_wind.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <unordered_map>

#include "cranesim/model/massive_reeved_rope_element.hpp"
#include "cranesim/model/truss_geometry.hpp"
#include "cranesim/model/wind_elements.hpp"

namespace cranesim {
namespace {

/// The coordinate and velocity indices of `nodes`, in order.
void nodeIndices(const Model& model, const std::vector<int>& nodes, std::vector<int>& q, std::vector<int>& v) {
  for (int n : nodes)
    for (int k = 0; k < model.nodes[n].size(); ++k) q.push_back(model.nodes[n].q + k), v.push_back(model.nodes[n].v + k);
}

/// The wind on every tube of a truss member, through its end sections <name>.section1 and
/// <name>.section2 (every fidelity has them). Each tube counts (1 + η)/2 times: across a doubly
/// symmetric section, half of its tube area lies in the lee of the other half.
std::unique_ptr<Element> latticeWind(const Model& model, const Scene& scene, const MemberSpec& member, const WindMemberSpec& m,
                                     int points_per_tube, const std::unordered_map<std::string, int>& node_of) {
  const TrussDescription& truss = *std::find_if(scene.trusses.begin(), scene.trusses.end(), [&](const TrussDescription& d) { return d.name == member.truss; });
  const TrussGeometry g = buildTrussGeometry(truss);
  std::vector<Vec3> points;
  for (const TrussNode& node : g.nodes) points.push_back(node.position);
  std::vector<WindTube> tubes;
  for (const TrussMember& tube : g.members)
    tubes.push_back({tube.node1, tube.node2, m.drag_coefficient * 2.0 * tube.section.outer_radius * 0.5 * (1.0 + m.shielding)});
  const int a = node_of.at(member.name + ".section1"), b = node_of.at(member.name + ".section2");
  std::vector<int> q, v;
  nodeIndices(model, {a, b}, q, v);
  return std::make_unique<LatticeWindElement>(model.wind, std::move(points), std::move(tubes), g.length, points_per_tube, a, b,
                                              std::move(q), std::move(v));
}

/// The wind on the cable from chain node c to c + 1 of a massive reeved rope, through the points
/// where those nodes sit.
std::unique_ptr<Element> chainWind(const Model& model, const MassiveReevedRopeElement& rope, int c, double drag_diameter,
                                   int points) {
  RopePath ends;
  std::vector<int> nodes, q, v;
  for (const MassiveReevedRopeElement::ChainPoint& p : {rope.chainPoint(c), rope.chainPoint(c + 1)}) {
    if (p.node < 0) {
      ends.points.push_back({-1, p.offset});
      continue;
    }
    auto found = std::find(nodes.begin(), nodes.end(), p.node);
    if (found == nodes.end()) {
      const Node& node = model.nodes[p.node];
      ends.slots.push_back({static_cast<int>(q.size()), node.size(), node.hasRotation()});
      nodeIndices(model, {p.node}, q, v);
      nodes.push_back(p.node);
      found = nodes.end() - 1;
    }
    ends.points.push_back({static_cast<int>(found - nodes.begin()), p.offset});
  }
  return std::make_unique<PathLineWindElement>(model.wind, drag_diameter, points, std::move(ends), std::move(nodes), std::move(q),
                                               std::move(v));
}

}  // namespace

void compileWind(Model& model, const Scene& scene) {
  const WindSpec& spec = *scene.wind;
  model.wind = std::make_shared<const WindField>(spec.field, scene.gravity);
  std::unordered_map<std::string, int> node_of;
  for (std::size_t n = 0; n < model.nodes.size(); ++n) node_of.emplace(model.nodes[n].name, static_cast<int>(n));

  for (const WindBodySpec& b : spec.bodies) {
    const RigidBodySpec& body = *std::find_if(scene.bodies.begin(), scene.bodies.end(), [&](const RigidBodySpec& s) { return s.name == b.body; });
    const int node = node_of.at(b.body);
    Vec3 point = body.centroid;
    if (!b.joint.empty()) point = model.joints[model.findJoint(b.joint)].offset;
    std::vector<int> q, v;
    nodeIndices(model, {node}, q, v);
    model.wind_parts.push_back({b.body, {static_cast<int>(model.elements.size())}});
    model.elements.push_back(std::make_unique<BodyWindElement>(model.wind, b.drag_coefficient * b.area, point, node, std::move(q), std::move(v)));
  }

  for (const WindMemberSpec& m : spec.members) {
    const MemberSpec& member = *std::find_if(scene.members.begin(), scene.members.end(), [&](const MemberSpec& s) { return s.name == m.member; });
    WindPart part{m.member, {}};
    if (member.type == MemberType::Truss) {
      part.elements.push_back(static_cast<int>(model.elements.size()));
      model.elements.push_back(latticeWind(model, scene, member, m, spec.quadrature, node_of));
      model.wind_parts.push_back(std::move(part));
      continue;
    }
    if (member.reeving) {  // massive (the reader refuses the wind on massless parts)
      const auto& rope = dynamic_cast<const MassiveReevedRopeElement&>(reevedRope(model, findReevedRope(model, m.member)));
      for (int c = 0; c + 1 < rope.kernel().chainNodes(); ++c) {
        part.elements.push_back(static_cast<int>(model.elements.size()));
        model.elements.push_back(chainWind(model, rope, c, m.drag_coefficient * m.diameter, spec.quadrature));
      }
      model.wind_parts.push_back(std::move(part));
      continue;
    }
    for (int i = 0; i < member.segments; ++i) {
      const int a = node_of.at(fmt::format("{}.n{}", m.member, i)), b = node_of.at(fmt::format("{}.n{}", m.member, i + 1));
      std::vector<int> q, v;
      nodeIndices(model, {a, b}, q, v);
      part.elements.push_back(static_cast<int>(model.elements.size()));
      model.elements.push_back(std::make_unique<LineWindElement>(model.wind, m.drag_coefficient * m.diameter, spec.quadrature, a, b,
                                                                 model.nodes[a].size(), std::move(q), std::move(v)));
    }
    model.wind_parts.push_back(std::move(part));
  }
}

}  // namespace cranesim
