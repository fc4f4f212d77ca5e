#include "cranesim/model/compile.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "cranesim/elements/cable.hpp"
#include "cranesim/elements/rigid_body.hpp"
#include "cranesim/elements/rotated_ends.hpp"
#include "cranesim/elements/spline_beam.hpp"
#include "cranesim/elements/spline_rope.hpp"
#include "cranesim/elements/strut_tie.hpp"
#include "cranesim/elements/timoshenko_beam.hpp"
#include "cranesim/math/rotation.hpp"
#include "cranesim/model/arc.hpp"
#include "cranesim/model/closest_name.hpp"
#include "cranesim/model/member_force_elements.hpp"
#include "compile_contacts.hpp"
#include "compile_supports.hpp"
#include "compile_reeving.hpp"
#include "compile_truss.hpp"
#include "compile_wind.hpp"
#include "model_building.hpp"

namespace cranesim {
namespace {

NodeKind memberNodeKind(const MemberSpec& m) {
  if (m.type == MemberType::Rope && m.rope_element == RopeElement::Cable) return NodeKind::Point;
  switch (m.type) {
    case MemberType::StrutTie: return NodeKind::Point;
    case MemberType::Timoshenko: return NodeKind::Frame;
    case MemberType::SplineBeam: return NodeKind::FrameStretch;
    case MemberType::Rope: return NodeKind::PointSlope;
    case MemberType::Truss: break;
  }
  return NodeKind::Frame;
}

/// The Timoshenko beam of one element of length `length` of a member.
TimoshenkoBeamKernel timoshenkoBeam(const MemberSpec& m, double length) {
  TimoshenkoBeamKernel k;
  k.length = length;
  k.section = m.section;
  k.material = m.material;
  if (m.quadrature > 0) k.mass_points = m.quadrature;
  k.damping = m.damping;
  return k;
}

/// A rope kernel (spline or cable) with the member's reeled length, section and damping.
template <class Kernel> Kernel ropeKernel(const MemberSpec& m, double chord) {
  Kernel k;
  k.total_length = m.length ? *m.length : Profile(ConstantProfile{chord});
  k.segments = m.segments;
  k.section = m.section;
  k.material = m.material;
  k.damping = m.damping;
  return k;
}

/// A member's nodes and elements: a straight line of elements from start to end, or for a
/// timoshenko member along an arc (model/arc.hpp) nodes on the arc with frames along its tangent
/// and straight elements on the chords, turned against them by constant rotations.
void compileMember(Model& model, const MemberSpec& m) {
  const ArcNodes arc = m.arc ? arcNodes(m.start, m.end, *m.arc, m.segments) : ArcNodes{};
  const Mat3 R = memberFrame(m.start, m.end, m.z_axis);
  const Vec3 axis = m.end - m.start;
  const double chord = axis.norm();
  const double unstretched = m.length ? (*m.length)(model.solver.t_start) : chord;
  if (!(unstretched > 0.0)) throw SceneError(m.where, "the rope's unstretched length must be positive");
  if (m.length) model.parameter_profiles.push_back(*m.length);
  const NodeKind kind = memberNodeKind(m);
  std::vector<int> nodes;
  for (int i = 0; i <= m.segments; ++i) {
    const int n = model.addNode(fmt::format("{}.n{}", m.name, i), kind, m.name);
    const Node& node = model.nodes[n];
    model.q0.segment<3>(node.q) = m.arc ? arc.positions[i] : Vec3(m.start + (static_cast<double>(i) / m.segments) * axis);
    if (node.hasRotation()) model.q0.segment<3>(node.q + 3) = rotationVector(m.arc ? arc.frames[i] : R);
    if (kind == NodeKind::FrameStretch) model.q0(node.q + 6) = 1.0;
    if (kind == NodeKind::PointSlope) model.q0.segment<3>(node.q + 3) = axis / unstretched;  // r' = dr/ds
    model.joints.push_back({node.name, n, Vec3::Zero(), Mat3::Identity()});
    if (i > 0) model.drawing_lines.push_back({static_cast<int>(model.joints.size()) - 2, static_cast<int>(model.joints.size()) - 1});
    nodes.push_back(n);
  }
  model.joints.push_back({m.name + ".start", nodes.front(), Vec3::Zero(), Mat3::Identity()});
  model.joints.push_back({m.name + ".end", nodes.back(), Vec3::Zero(), Mat3::Identity()});
  const double segment = chord / m.segments;
  for (int i = 0; i < m.segments; ++i) {
    const std::vector<int> pair = {nodes[i], nodes[i + 1]};
    switch (m.type) {
      case MemberType::StrutTie: {
        StrutTieKernel k;
        k.length = segment;
        k.section = m.section;
        k.material = m.material;
        k.constant_volume = m.constant_volume;
        k.smoothing = m.smoothing;
        k.damping = m.damping;
        addElement(model, k, pair);
        break;
      }
      case MemberType::Rope: {
        if (m.rope_element == RopeElement::Cable) {
          addElement(model, ropeKernel<CableKernel>(m, chord), pair);
          break;
        }
        SplineRopeKernel k = ropeKernel<SplineRopeKernel>(m, chord);
        k.transverse_damping = m.transverse_damping;
        if (m.quadrature > 0) k.rule = gaussLegendre(m.quadrature);
        addElement(model, k, pair);
        break;
      }
      case MemberType::Timoshenko: {
        if (m.arc) {
          const Vec3 &a = arc.positions[i], &b = arc.positions[i + 1];
          const Mat3 along_chord = memberFrame(a, b, arc.frames[i].col(2));
          addElement(model,
                     RotatedEndsBeamKernel(timoshenkoBeam(m, (b - a).norm()), arc.frames[i].transpose() * along_chord,
                                           arc.frames[i + 1].transpose() * along_chord),
                     pair);
          break;
        }
        addElement(model, timoshenkoBeam(m, segment), pair);
        break;
      }
      case MemberType::SplineBeam: {
        SplineBeamKernel k;
        k.length = segment;
        k.section = m.section;
        k.material = m.material;
        if (m.quadrature > 0) k.rule = gaussLegendre(m.quadrature);
        k.damping = m.damping;
        addElement(model, k, pair);
        break;
      }
      case MemberType::Truss: break;
    }
  }
}

/// `pose: drawn`: the fixed constraint acts on a copy of one of its joints, placed on the same
/// node so that in the drawing (q0) it coincides with the other joint, origin and axes. It
/// then keeps the relative pose the drawing gives the two joints: two members meeting at an
/// angle, without a corner body. The copy goes on a node that turns (a body or a beam node):
/// joint 2's, or joint 1's when joint 2's node cannot carry it.
void keepDrawnPose(Model& model, Constraint& c, const ConstraintSpec& cs) {
  const auto turns = [&](int joint) {
    const int node = model.joints[joint].node;
    return node >= 0 && model.nodes[node].hasRotation();
  };
  int& moved = turns(c.joint2) ? c.joint2 : c.joint1;
  if (!turns(moved))
    throw SceneError(cs.where_pose, "pose: drawn keeps a relative rotation, so one joint must be on a body or a beam "
                                    "node (a frame that turns); neither is");
  const int other = &moved == &c.joint2 ? c.joint1 : c.joint2;
  const Joint& original = model.joints[moved];
  const Frame node = model.nodeFrame(model.q0.data(), original.node);
  const Frame target = model.jointFrame(model.q0.data(), other);
  Joint copy{original.name + "@" + c.name, original.node, node.R.transpose() * (target.r - node.r),
             node.R.transpose() * target.R};
  model.joints.push_back(std::move(copy));
  moved = static_cast<int>(model.joints.size()) - 1;
}

/// Why a joint name is unknown: the closest known name, and the joints the named part has.
std::string unknownJoint(const Model& model, const std::string& name) {
  constexpr std::size_t kListed = 12;
  const std::string part = name.substr(0, name.find('.'));
  std::vector<std::string> names, of_part;
  for (const Joint& joint : model.joints) {
    names.push_back(joint.name);
    if (joint.name.size() > part.size() && joint.name.compare(0, part.size() + 1, part + ".") == 0)
      of_part.push_back(joint.name);
  }
  std::string message = fmt::format("unknown joint '{}'", name);
  if (const std::string closest = closestName(name, names); !closest.empty())
    message += fmt::format("; did you mean '{}'?", closest);
  if (of_part.empty()) {
    message += fmt::format(" (no body, member or ground joint is named '{}.<joint>')", part);
  } else {
    std::string listed;
    for (std::size_t i = 0; i < std::min(of_part.size(), kListed); ++i) listed += (i ? ", " : "") + of_part[i];
    if (of_part.size() > kListed) listed += fmt::format(" and {} more", of_part.size() - kListed);
    message += fmt::format(" ('{}' has {}: {})", part, of_part.size() == 1 ? std::string("one joint")
                                                                          : fmt::format("{} joints", of_part.size()),
                           listed);
  }
  return message;
}

}  // namespace

Model compileModel(const Scene& scene) {
  Model model;
  model.name = scene.name;
  model.gravity = scene.gravity;
  model.solver = scene.solver;
  model.output = scene.output;

  for (const JointSpec& j : scene.ground_joints) model.joints.push_back({"ground." + j.name, -1, j.position, j.rotation});

  for (const RigidBodySpec& b : scene.bodies) {
    const int node = model.addNode(b.name, NodeKind::Frame);
    const Node& n = model.nodes[node];
    model.q0.segment<3>(n.q) = b.position;
    model.q0.segment<3>(n.q + 3) = rotationVector(b.rotation);
    model.v0.segment<3>(n.v) = b.velocity;
    model.v0.segment<3>(n.v + 3) = b.angular_velocity;
    RigidBodyKernel kernel;
    kernel.mass = b.mass;
    kernel.centroid = b.centroid;
    kernel.inertia_origin = RigidBodyKernel::inertiaAboutOrigin(b.mass, b.centroid, b.inertia);
    addElement(model, kernel, {node});
    model.joints.push_back({b.name + ".origin", node, Vec3::Zero(), Mat3::Identity()});
    for (const JointSpec& j : b.joints) {
      if (j.name == "origin") throw SceneError(j.where, "'origin' is reserved: every body has a joint <body>.origin at its origin");
      model.joints.push_back({b.name + "." + j.name, node, j.position, j.rotation});
    }
  }

  std::vector<MemberSpec> reeved;  // after every other member: their paths run over their nodes
  for (const MemberSpec& m : scene.members) {
    if (m.type != MemberType::Truss) {
      MemberSpec member = m;
      if (member.length) member.length = model.attachInput(*m.length, m.name, "rope length", m.where);
      if (member.reeving) reeved.push_back(std::move(member));
      else compileMember(model, member);
      continue;
    }
    const auto type = std::find_if(scene.trusses.begin(), scene.trusses.end(), [&](const TrussDescription& d) { return d.name == m.truss; });
    if (type == scene.trusses.end()) throw SceneError(m.where, fmt::format("unknown truss type '{}'", m.truss));
    compileTrussMember(model, m, *type);
  }

  for (const MemberSpec& m : reeved) compileReevedRope(model, m);

  const auto resolve = [&](const std::string& name, const SourceLocation& where) {
    const int j = model.findJoint(name);
    if (j >= 0) return j;
    throw SceneError(where, unknownJoint(model, name));
  };

  for (const ConstraintSpec& cs : scene.constraints) {
    Constraint c;
    c.name = cs.name;
    c.type = cs.type;
    c.joint1 = resolve(cs.joint1, cs.where_joint1);
    c.joint2 = resolve(cs.joint2, cs.where_joint2);
    const int n1 = model.joints[c.joint1].node, n2 = model.joints[c.joint2].node;
    if (n1 == n2)
      throw SceneError(cs.where, n1 < 0 ? "both joints are on the ground: the constraint constrains nothing"
                                        : fmt::format("both joints are on body '{}': a constraint connects two different bodies",
                                                      model.nodes[n1].name));
    if (cs.keep_drawn_pose) keepDrawnPose(model, c, cs);
    c.axis = cs.axis;
    if (cs.drive) c.drive = model.attachInput(*cs.drive, cs.name, "drive", cs.where);
    c.where = cs.where;
    addConstraint(model, std::move(c));
  }

  for (const LoadSpec& ls : scene.loads) {
    Load l;
    l.name = ls.name;
    l.joint = resolve(ls.joint, ls.where_joint);
    if (model.joints[l.joint].node < 0) throw SceneError(ls.where_joint, "a load on a ground joint acts on nothing");
    l.force = ls.force;
    l.torque = ls.torque;
    l.frame = ls.frame;
    l.scale = model.attachInput(ls.scale, ls.name, "load scale", ls.where);
    model.loads.push_back(std::move(l));
  }

  if (scene.wind) compileWind(model, scene);
  compileContacts(model, scene);
  if (scene.ground_supports) compileSupports(model, scene);

  for (const std::string& member : scene.output.section_forces) {
    const auto spec = std::find_if(scene.members.begin(), scene.members.end(), [&](const MemberSpec& m) { return m.name == member; });
    const bool rope = spec != scene.members.end() && spec->type == MemberType::Rope;
    model.section_force_groups.push_back({member, memberForceElements(model, member, rope), rope});
  }
  return model;
}

}  // namespace cranesim
