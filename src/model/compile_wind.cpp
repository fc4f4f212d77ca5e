#include "compile_wind.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <unordered_map>

#include "cranesim/model/wind_elements.hpp"

namespace cranesim {
namespace {

/// The coordinate and velocity indices of `nodes`, in order.
void nodeIndices(const Model& model, const std::vector<int>& nodes, std::vector<int>& q, std::vector<int>& v) {
  for (int n : nodes)
    for (int k = 0; k < model.nodes[n].size(); ++k) q.push_back(model.nodes[n].q + k), v.push_back(model.nodes[n].v + k);
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
