#include "cranesim/model/member_force_elements.hpp"

#include <algorithm>

namespace cranesim {

std::vector<int> memberForceElements(const Model& model, const std::string& member, bool rope) {
  const VecX zero_v = VecX::Zero(model.nv);
  const ElementInput drawn{model.q0.data(), zero_v.data(), zero_v.data(), model.solver.t_start, model.gravity};
  std::vector<int> elements;
  for (std::size_t e = 0; e < model.elements.size(); ++e) {
    const auto& nodes = model.elements[e]->nodes();
    if (!std::all_of(nodes.begin(), nodes.end(), [&](int n) { return model.nodes[n].member == member; })) continue;
    double forces[std::max(12, kTensionPoints)];
    if (rope ? model.elements[e]->tensions(drawn, forces) : model.elements[e]->sectionForces(drawn, forces))
      elements.push_back(static_cast<int>(e));
  }
  return elements;
}

}  // namespace cranesim
