#include "cranesim/crane/crane_figures.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "cranesim/model/closest_name.hpp"
#include "cranesim/model/member_force_elements.hpp"
#include "cranesim/model/reeved_rope.hpp"

namespace cranesim {
namespace {

int jointIndex(const Model& model, const std::string& name, const SourceLocation& where) {
  const int j = model.findJoint(name);
  if (j < 0) throw SceneError(where, unknownName("joint", name, namesOf(model.joints)));
  return j;
}

/// The distance of `p` from the line through `a` along the unit vector `n`.
double radius(const Vec3& p, const Vec3& a, const Vec3& n) {
  const Vec3 v = p - a;
  return (v - v.dot(n) * n).norm();
}

RopeTension ropeTension(const Model& model, const std::string& rope, const double* q, double t) {
  const VecX zero = VecX::Zero(model.nv);
  const ElementInput in{q, zero.data(), zero.data(), t, model.gravity};
  if (const int reeved = findReevedRope(model, rope); reeved >= 0) {  // its winch's part and its dead end's
    const ReevedRope& element = reevedRope(model, reeved);
    std::vector<double> parts(static_cast<std::size_t>(element.parts()));
    element.partTensions(in, parts.data());
    return {rope, parts.front(), parts.back()};
  }
  const std::vector<int> elements = memberForceElements(model, rope, true);
  double first[kTensionPoints], last[kTensionPoints];
  model.elements[static_cast<std::size_t>(elements.front())]->tensions(in, first);
  model.elements[static_cast<std::size_t>(elements.back())]->tensions(in, last);
  return {rope, first[0], last[kTensionPoints - 1]};
}

BoomFigures boomFigures(const Scene& scene, const Model& model, const double* q) {
  const CraneSpec& spec = *scene.crane;
  const Constraint& slewing = model.constraints[static_cast<std::size_t>(model.findConstraint(spec.slewing))];
  const Constraint& foot = model.constraints[static_cast<std::size_t>(model.findConstraint(spec.boom_foot))];
  const Frame axis_frame = model.jointFrame(q, slewing.joint1);
  const Vec3 axis_point = axis_frame.r, axis = axis_frame.R.col(slewing.axis);
  const Vec3 up = model.gravity.norm() > 0.0 ? Vec3(-model.gravity.normalized()) : axis;
  const Vec3 foot_point = model.jointFrame(q, foot.joint1).r;
  const Vec3 head = model.jointFrame(q, model.findJoint(spec.boom_head)).r;
  const Vec3 hook = model.jointFrame(q, model.findJoint(spec.hook)).r;
  BoomFigures f;
  const EnvelopeBoom& envelope = *model.envelope.boom;
  f.boom_angle_deg = boomAngle(foot_point, head, up, model.jointFrame(q, envelope.superstructure_joint).R * envelope.forward);
  f.head_height = head.dot(up);
  f.hook_radius = radius(hook, axis_point, axis);
  f.hook_height = hook.dot(up);
  if (!spec.load.empty()) {
    const auto body = std::find_if(scene.bodies.begin(), scene.bodies.end(), [&](const RigidBodySpec& b) { return b.name == spec.load; });
    for (std::size_t n = 0; n < model.nodes.size(); ++n)
      if (model.nodes[n].member.empty() && model.nodes[n].name == spec.load) {
        const Frame frame = model.nodeFrame(q, static_cast<int>(n));
        const Vec3 centre = frame.r + frame.R * body->centroid;
        f.load_radius = radius(centre, axis_point, axis);
        f.load_height = centre.dot(up);
      }
  }
  return f;
}

}  // namespace

void locateCrane(const Scene& scene, const Model& model) {
  if (!scene.crane) return;
  jointIndex(model, scene.crane->boom_head, scene.crane->where_boom_head);
  jointIndex(model, scene.crane->hook, scene.crane->where_hook);
}

CraneFigures craneFigures(const Scene& scene, const Model& model, const double* q, double t) {
  CraneFigures figures;
  if (scene.crane) figures.boom = boomFigures(scene, model, q);
  std::vector<std::string> ropes = scene.crane ? scene.crane->ropes : std::vector<std::string>{};
  if (ropes.empty())
    for (const MemberSpec& m : scene.members)
      if (m.type == MemberType::Rope) ropes.push_back(m.name);
  for (const std::string& rope : ropes) figures.ropes.push_back(ropeTension(model, rope, q, t));
  return figures;
}

std::string describeCraneFigures(const CraneFigures& figures) {
  std::string text;
  if (const auto& b = figures.boom) {
    text += "crane\n";
    text += fmt::format("{:<24} {:>12.4f}   foot hinge to head, above the horizontal\n", "  boom angle [deg]", b->boom_angle_deg);
    text += fmt::format("{:<24} {:>12.4f}   above the ground origin\n", "  head height [m]", b->head_height);
    text += fmt::format("{:<24} {:>12.4f}   from the slewing axis\n", "  hook radius [m]", b->hook_radius);
    text += fmt::format("{:<24} {:>12.4f}\n", "  hook height [m]", b->hook_height);
    if (b->load_radius) text += fmt::format("{:<24} {:>12.4f}   its centre of mass\n", "  load radius [m]", *b->load_radius);
    if (b->load_height) text += fmt::format("{:<24} {:>12.4f}\n", "  load height [m]", *b->load_height);
  }
  if (!figures.ropes.empty()) text += fmt::format("{:<24} {:>12} {:>12}\n", "rope tension", "start [N]", "end [N]");
  for (const RopeTension& r : figures.ropes) text += fmt::format("  {:<22} {:>12.6g} {:>12.6g}\n", r.rope, r.at_start, r.at_end);
  return text;
}

}  // namespace cranesim
