#include "compile_contacts.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "cranesim/math/units.hpp"
#include "cranesim/model/closest_name.hpp"
#include "cranesim/model/contact_elements.hpp"
#include "cranesim/model/member_force_elements.hpp"
#include "cranesim/model/reeved_rope.hpp"

namespace cranesim {
namespace {

/// The first `count` coordinate and velocity indices of node n.
void leadingIndices(const Model& model, int n, int count, std::vector<int>& q, std::vector<int>& v) {
  for (int k = 0; k < count; ++k) q.push_back(model.nodes[n].q + k), v.push_back(model.nodes[n].v + k);
}

void compileGroundContacts(Model& model, const Scene& scene, const GroundSurfaceSpec& spec) {
  Envelope& envelope = model.envelope;
  const GroundSurface ground{spec.height, envelope.up, {spec.stiffness, spec.damping, spec.smoothing}, spec.friction, spec.friction_speed};
  for (const GroundContactSpec& c : spec.contacts) {
    GroundContactPart part{c.body.empty() ? c.member : c.body, {}};
    for (std::size_t n = 0; n < model.nodes.size(); ++n) {
      const Node& node = model.nodes[n];
      const bool body = !c.body.empty() && node.member.empty() && node.name == c.body;
      if (!body && (c.member.empty() || node.member != c.member)) continue;
      Vec3 point = Vec3::Zero();
      if (body)
        point = std::find_if(scene.bodies.begin(), scene.bodies.end(), [&](const RigidBodySpec& b) { return b.name == c.body; })->centroid;
      std::vector<int> q, v;
      leadingIndices(model, static_cast<int>(n), body ? 6 : 3, q, v);
      part.elements.push_back(static_cast<int>(model.elements.size()));
      model.elements.push_back(std::make_unique<GroundContactElement>(ground, c.radius, point, body, static_cast<int>(n), std::move(q), std::move(v)));
      envelope.node_in_contact[n] = true;
    }
    envelope.ground_contacts.push_back(std::move(part));
  }
}

/// The joint of the slewing constraint on the turning side: the other one is on the ground or on
/// the carriage that stands on the supports.
int superstructureJoint(const Model& model, const Scene& scene, const CraneSpec& crane) {
  const Constraint& slewing = model.constraints[static_cast<std::size_t>(model.findConstraint(crane.slewing))];
  const auto standing = [&](int joint) {
    const int node = model.joints[joint].node;
    return node < 0 || (scene.ground_supports && model.nodes[node].member.empty() && model.nodes[node].name == scene.ground_supports->body);
  };
  return standing(slewing.joint1) ? slewing.joint2 : slewing.joint1;
}

EnvelopeBoom compileBoom(const Model& model, const Scene& scene, const CraneSpec& crane) {
  EnvelopeBoom boom;
  const Constraint& foot = model.constraints[static_cast<std::size_t>(model.findConstraint(crane.boom_foot))];
  boom.foot_joint = foot.joint1;
  boom.head_joint = model.findJoint(crane.boom_head);
  if (boom.head_joint < 0) throw SceneError(crane.where_boom_head, unknownName("joint", crane.boom_head, namesOf(model.joints)));
  boom.superstructure_joint = superstructureJoint(model, scene, crane);
  boom.limit_deg = crane.boom_angle_limit_deg;
  const Vec3& up = model.envelope.up;
  const Vec3 line = model.jointFrame(model.q0.data(), boom.head_joint).r - model.jointFrame(model.q0.data(), boom.foot_joint).r;
  const Vec3 horizontal = line - up * up.dot(line);
  const Mat3 R = model.jointFrame(model.q0.data(), boom.superstructure_joint).R;
  boom.forward = horizontal.norm() > 1e-9 * line.norm() ? Vec3(R.transpose() * horizontal.normalized()) : Vec3::UnitX();
  return boom;
}

void compileBackstop(Model& model, const CraneSpec& crane, EnvelopeBoom& boom) {
  const BackstopSpec& spec = *crane.backstop;
  const Constraint& foot = model.constraints[static_cast<std::size_t>(model.findConstraint(crane.boom_foot))];
  const int slewing = model.joints[boom.superstructure_joint].node;
  const int foot_joint = model.joints[foot.joint1].node == slewing ? foot.joint1 : foot.joint2;
  if (model.joints[foot_joint].node != slewing)
    throw SceneError(spec.where, fmt::format("the backstop acts between the slewing body '{}' and the boom, but crane.boom_foot '{}' "
                                             "joins neither to it", model.nodes[slewing].name, crane.boom_foot));
  const std::string& point_name = spec.joint.empty() ? crane.boom_head : spec.joint;
  const int point_joint = model.findJoint(point_name);
  if (point_joint < 0) throw SceneError(spec.where_joint, unknownName("joint", point_name, namesOf(model.joints)));
  const int on_boom = model.joints[point_joint].node;
  if (on_boom < 0 || on_boom == slewing || !model.nodes[on_boom].hasRotation() || !model.nodes[slewing].hasRotation())
    throw SceneError(spec.where_joint, fmt::format("the backstop pushes the boom at '{}': a joint on a body or on a beam's or truss "
                                                   "section's frame up the boom, not on the slewing body", point_name));
  const double* q0 = model.q0.data();
  const Vec3& up = model.envelope.up;
  const Frame s = model.nodeFrame(q0, slewing);
  const Vec3 foot_point = model.jointFrame(q0, foot_joint).r, point = model.jointFrame(q0, point_joint).r;
  const Vec3 axis = model.jointFrame(q0, foot_joint).R.col(foot.axis);
  const Vec3 d = point - foot_point, across = d - axis * axis.dot(d);
  // Turning d by a small angle about the axis raises B where axis × d points up.
  const double raise = axis.cross(d).dot(up) / d.norm();
  if (std::abs(raise) < 1e-3 || across.norm() < 1e-3 * d.norm())
    throw SceneError(spec.where, fmt::format("crane.boom_foot '{}' turns about an axis along which '{}' cannot rise: a backstop "
                                             "needs a horizontal hinge across the boom", crane.boom_foot, point_name));
  const Vec3 head = model.jointFrame(q0, boom.head_joint).r;
  const double drawn = boomAngle(foot_point, head, up, s.R * boom.forward);
  if (drawn >= spec.angle_deg)
    throw SceneError(spec.where, fmt::format("the drawing puts the boom at {:.4g}°, at or past its backstop's angle {:g}°",
                                             drawn, spec.angle_deg));
  BackstopElement::Hinge hinge;
  hinge.foot = model.joints[foot_joint].offset;
  hinge.axis = s.R.transpose() * axis;
  hinge.drawn = s.R.transpose() * across.normalized();
  hinge.point = model.joints[point_joint].offset;
  hinge.sense = raise > 0.0 ? 1.0 : -1.0;
  hinge.engaged = (spec.angle_deg - drawn) * kRadiansPerDegree;
  std::vector<int> q, v;
  leadingIndices(model, slewing, 6, q, v);
  leadingIndices(model, on_boom, 6, q, v);
  boom.backstop_element = static_cast<int>(model.elements.size());
  boom.backstop_angle_deg = spec.angle_deg;
  model.elements.push_back(std::make_unique<BackstopElement>(hinge, PenaltyLaw{spec.stiffness, spec.damping, spec.smoothing_deg * kRadiansPerDegree},
                                                             slewing, on_boom, std::move(q), std::move(v)));
}

}  // namespace

void compileContacts(Model& model, const Scene& scene) {
  Envelope& envelope = model.envelope;
  envelope.up = model.gravity.norm() > 0.0 ? Vec3(-model.gravity.normalized()) : Vec3::UnitZ();
  envelope.node_in_contact.assign(model.nodes.size(), false);
  for (const MemberSpec& m : scene.members)
    if (m.breaking_force) {
      EnvelopeRope rope{m.name, *m.breaking_force, memberForceElements(model, m.name, true)};
      for (const int e : model.reeved_ropes)
        if (dynamic_cast<const ReevedRope&>(*model.elements[e]).name() == m.name) rope.elements = {e};
      envelope.ropes.push_back(std::move(rope));
    }
  if (scene.ground_surface) {
    envelope.ground_height = scene.ground_surface->height;
    compileGroundContacts(model, scene, *scene.ground_surface);
  }
  if (scene.crane) {
    envelope.boom = compileBoom(model, scene, *scene.crane);
    if (scene.crane->backstop) compileBackstop(model, *scene.crane, *envelope.boom);
  }
}

}  // namespace cranesim
