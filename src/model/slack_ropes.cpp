#include "cranesim/model/slack_ropes.hpp"

#include <fmt/format.h>

#include "cranesim/model/member_force_elements.hpp"
#include "cranesim/model/reeved_rope.hpp"

namespace cranesim {

std::string slackRopeEnds(const Scene& scene, const Model& model, const VecX& q, double t) {
  const VecX zero = VecX::Zero(model.nv);
  const ElementInput in{q.data(), zero.data(), zero.data(), t, model.gravity};
  std::string slack;
  const auto report = [&](const std::string& rope, double at_start, double at_end) {
    for (const auto& [tension, end] : {std::pair{at_start, "start"}, std::pair{at_end, "end"}})
      if (tension <= 0.0) slack += fmt::format("{}'{}' at its {}", slack.empty() ? "" : ", ", rope, end);
  };
  for (const MemberSpec& m : scene.members) {
    if (m.type != MemberType::Rope) continue;
    if (const int reeved = findReevedRope(model, m.name); reeved >= 0) {
      const ReevedRope& element = reevedRope(model, reeved);
      std::vector<double> parts(static_cast<std::size_t>(element.parts()));
      element.partTensions(in, parts.data());
      report(m.name, parts.front(), parts.back());
      continue;
    }
    const std::vector<int> elements = memberForceElements(model, m.name, true);
    if (elements.empty()) continue;
    double first[kTensionPoints], last[kTensionPoints];
    model.elements[static_cast<std::size_t>(elements.front())]->tensions(in, first);
    model.elements[static_cast<std::size_t>(elements.back())]->tensions(in, last);
    report(m.name, first[0], last[kTensionPoints - 1]);
  }
  return slack;
}

}  // namespace cranesim
