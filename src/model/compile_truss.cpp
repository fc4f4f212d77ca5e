// Truss members (`type: truss`, docs/truss.md): one truss description placed in the scene becomes
// the super truss element (3.5), the condensed truss element (the full-member model's stiffness
// condensed onto the end sections, condensed_truss.hpp), the equivalent Timoshenko beam
// (equivalent_beam.hpp) or the full-member model, in which every tube is its own Timoshenko beam
// on shared frame nodes (docs/truss.md).
//
// Full-member model:
// - One frame node per truss node (end-section and internal nodes), shared by every tube that
//   meets there: a rigid connection (assumption 3). Every tube end is turned against its node
//   by a constant rotation (rotated_ends.hpp); all nodes start with the truss frame's axes.
// - Each end section is rigid (assumption 1): a plate, i.e. a frame node at the section origin
//   (on the truss axis) with a rigid body carrying the mass and inertia of that section's
//   cross-section beams, fixed to every node of the section. The cross-section beams are
//   therefore no elements of their own. The plates carry the joints <name>.start / <name>.end.
// - `segments` > 1 splits every tube into that many beams with nodes of its own.

#include "compile_truss.hpp"

#include <fmt/format.h>

#include <array>

#include "cranesim/elements/condensed_truss.hpp"
#include "cranesim/elements/rigid_body.hpp"
#include "cranesim/elements/rotated_ends.hpp"
#include "cranesim/elements/super_truss.hpp"
#include "cranesim/math/rotation.hpp"
#include "cranesim/model/equivalent_beam.hpp"
#include "model_building.hpp"

namespace cranesim {
namespace {

/// Joint names of the truss nodes: <name>.s<section>n<node> for end-section nodes (numbered
/// from 1 as in the scene), <name>.c<chord>k<station> for internal nodes (station k = 1 … order − 1).
std::vector<std::string> nodeNames(const MemberSpec& m, const TrussGeometry& g) {
  std::array<int, 2> in_section{0, 0};
  std::vector<int> on_chord(g.chords.size(), 0);
  std::vector<std::string> names;
  for (const TrussNode& n : g.nodes)
    names.push_back(n.end_section >= 0 ? fmt::format("{}.s{}n{}", m.name, n.end_section + 1, ++in_section[n.end_section])
                                       : fmt::format("{}.c{}k{}", m.name, n.chord + 1, ++on_chord[n.chord]));
  return names;
}

/// Mass, centroid and inertia about the section origin of the cross-section beams of one end
/// section, as thin-walled tubes (centre line and rotary inertia, as the beam elements have).
RigidBodyKernel endPlate(const TrussGeometry& g, int section) {
  const Vec3 origin(section == 0 ? 0.0 : g.length, 0.0, 0.0);
  const double rho = g.material.density;
  RigidBodyKernel plate;
  plate.mass = 0.0;
  Vec3 first_moment = Vec3::Zero();
  Mat3 inertia = Mat3::Zero();
  for (const TrussMember& t : g.members) {
    if (t.role != TrussMemberRole::Cross || g.nodes[t.node1].end_section != section) continue;
    const Vec3 a = g.nodes[t.node1].position - origin, b = g.nodes[t.node2].position - origin;
    const double length = (b - a).norm(), mass = rho * t.section.area * length;
    const Vec3 e = (b - a) / length, c = 0.5 * (a + b);
    const Mat3 axial = e * e.transpose(), transverse = Mat3::Identity() - axial;
    const Mat3 own = mass * length * length / 12.0 * transverse +
                     rho * length * ((t.section.Iy + t.section.Iz) * axial + t.section.Iy * transverse);
    plate.mass += mass;
    first_moment += mass * c;
    inertia += own - mass * skew(c) * skew(c);
  }
  plate.centroid = plate.mass > 0.0 ? Vec3(first_moment / plate.mass) : Vec3::Zero();
  plate.inertia_origin = inertia;
  return plate;
}

/// Of the four section frames of a round tube (x and z each up to sign), the one closest to
/// the placed truss frame R: its relative rotation stays below 120°, away from the π where a
/// rotation vector of the section frame would change branch.
Mat3 closestSectionAxes(const Mat3& R, const Mat3& axes) {
  static const std::array<Vec3, 4> flips = {Vec3(1, 1, 1), Vec3(1, -1, -1), Vec3(-1, -1, 1), Vec3(-1, 1, -1)};
  Mat3 best = axes;
  double best_trace = -4.0;
  for (const Vec3& f : flips) {
    const Mat3 candidate = axes * f.asDiagonal();
    const double trace = (R * candidate).trace();
    if (trace > best_trace) best_trace = trace, best = candidate;
  }
  return best;
}

/// A frame node of member m at `truss_position` in its truss frame (R: truss frame → inertial),
/// with the truss frame's axes, and a joint of the node's name on it.
int addTrussNode(Model& model, const MemberSpec& m, const Mat3& R, const std::string& name, const Vec3& truss_position) {
  const int n = model.addNode(name, NodeKind::Frame, m.name);
  const Node& node = model.nodes[n];
  model.q0.segment<3>(node.q) = m.start + R * truss_position;
  model.q0.segment<3>(node.q + 3) = rotationVector(R);
  model.joints.push_back({name, n, Vec3::Zero(), Mat3::Identity()});
  return n;
}

void compileMembers(Model& model, const MemberSpec& m, const TrussGeometry& g) {
  const Mat3 R = memberFrame(m.start, m.end, m.z_axis);  // truss frame → inertial
  const Vec3 phi = rotationVector(R);

  const std::vector<std::string> names = nodeNames(m, g);
  std::vector<int> node_of(g.nodes.size());
  for (std::size_t n = 0; n < g.nodes.size(); ++n) node_of[n] = addTrussNode(model, m, R, names[n], g.nodes[n].position);
  for (const TrussMember& tube : g.members) model.drawing_lines.push_back({model.findJoint(names[tube.node1]), model.findJoint(names[tube.node2])});

  for (int s = 0; s < 2; ++s) {
    const Vec3 origin(s == 0 ? 0.0 : g.length, 0.0, 0.0);
    const std::string plate_name = fmt::format("{}.section{}", m.name, s + 1);
    const int plate = model.addNode(plate_name, NodeKind::Frame);
    const Node& node = model.nodes[plate];
    model.q0.segment<3>(node.q) = m.start + R * origin;
    model.q0.segment<3>(node.q + 3) = phi;
    const RigidBodyKernel kernel = endPlate(g, s);
    if (kernel.mass > 0.0) addElement(model, kernel, {plate});
    model.joints.push_back({s == 0 ? m.name + ".start" : m.name + ".end", plate, Vec3::Zero(), Mat3::Identity()});
    for (std::size_t n = 0; n < g.nodes.size(); ++n) {
      if (g.nodes[n].end_section != s) continue;
      const std::string& name = model.nodes[node_of[n]].name;
      const int on_plate = static_cast<int>(model.joints.size());
      model.joints.push_back({name + ".plate", plate, g.nodes[n].position - origin, Mat3::Identity()});
      Constraint c;
      c.name = name;
      c.type = ConstraintType::Fixed;
      c.joint1 = on_plate;
      c.joint2 = model.findJoint(name);
      c.where = m.where;
      addConstraint(model, std::move(c));
    }
  }

  for (std::size_t t = 0; t < g.members.size(); ++t) {
    const TrussMember& tube = g.members[t];
    if (tube.role == TrussMemberRole::Cross) continue;  // carried by the end plates
    const Vec3 p1 = g.nodes[tube.node1].position, p2 = g.nodes[tube.node2].position;
    const Mat3 axes = closestSectionAxes(R, memberFrame(p1, p2, tube.z_axis));
    const bool reversed = axes.col(0).dot(p2 - p1) < 0.0;
    const Vec3 from = reversed ? p2 : p1, to = reversed ? p1 : p2;
    std::vector<int> chain = {node_of[reversed ? tube.node2 : tube.node1]};
    for (int j = 1; j < m.segments; ++j)
      chain.push_back(addTrussNode(model, m, R, fmt::format("{}.t{}n{}", m.name, t + 1, j),
                                   from + (static_cast<double>(j) / m.segments) * (to - from)));
    chain.push_back(node_of[reversed ? tube.node1 : tube.node2]);
    TimoshenkoBeamKernel beam;
    beam.length = (to - from).norm() / m.segments;
    beam.section = tube.section;
    beam.material = g.material;
    if (m.quadrature > 0) beam.mass_points = m.quadrature;
    beam.damping = m.damping;
    for (int j = 0; j < m.segments; ++j) addElement(model, RotatedEndsBeamKernel(beam, axes, axes), {chain[j], chain[j + 1]});
  }
}

/// The two end-section frame nodes of a truss member with one element between them (super
/// truss, condensed, equivalent beam): the joints <name>.start / <name>.end, and the end-section
/// nodes as joints on them (the same names as in the full-member model). Returns the two nodes.
std::vector<int> addEndSections(Model& model, const MemberSpec& m, const TrussGeometry& g) {
  const Mat3 R = memberFrame(m.start, m.end, m.z_axis);  // truss frame → inertial
  const std::vector<std::string> names = nodeNames(m, g);
  std::vector<int> section(2);
  for (int s = 0; s < 2; ++s) {
    const Vec3 origin(s == 0 ? 0.0 : g.length, 0.0, 0.0);
    section[s] = model.addNode(fmt::format("{}.section{}", m.name, s + 1), NodeKind::Frame, m.name);
    const Node& node = model.nodes[section[s]];
    model.q0.segment<3>(node.q) = m.start + R * origin;
    model.q0.segment<3>(node.q + 3) = rotationVector(R);
    model.joints.push_back({s == 0 ? m.name + ".start" : m.name + ".end", section[s], Vec3::Zero(), Mat3::Identity()});
    for (std::size_t n = 0; n < g.nodes.size(); ++n)
      if (g.nodes[n].end_section == s) model.joints.push_back({names[n], section[s], g.nodes[n].position - origin, Mat3::Identity()});
  }
  // Drawn: the cross-section beams and the chords as straight lines (the internal nodes are no joints).
  for (const TrussMember& tube : g.members)
    if (g.nodes[tube.node1].end_section >= 0 && g.nodes[tube.node2].end_section >= 0)
      model.drawing_lines.push_back({model.findJoint(names[tube.node1]), model.findJoint(names[tube.node2])});
  for (const auto& chord : g.chords) model.drawing_lines.push_back({model.findJoint(names[chord[0]]), model.findJoint(names[chord[1]])});
  return section;
}

/// The equivalent Timoshenko beam (equivalent_beam.hpp) in `segments` elements between the end
/// sections, with frame nodes <name>.b1 … <name>.b<segments − 1> between them.
void compileEquivalentBeam(Model& model, const MemberSpec& m, const TrussGeometry& g) {
  const std::vector<int> section = addEndSections(model, m, g);
  const EquivalentBeam equivalent = equivalentBeam(g);
  TimoshenkoBeamKernel beam;
  beam.length = g.length / m.segments;
  beam.section = equivalent.section;
  beam.material = equivalent.material;
  if (m.quadrature > 0) beam.mass_points = m.quadrature;
  beam.damping = m.damping;
  const Mat3 R = memberFrame(m.start, m.end, m.z_axis);
  std::vector<int> chain = {section[0]};
  for (int j = 1; j < m.segments; ++j)
    chain.push_back(addTrussNode(model, m, R, fmt::format("{}.b{}", m.name, j), Vec3(j * beam.length, 0.0, 0.0)));
  chain.push_back(section[1]);
  for (int j = 0; j < m.segments; ++j) addElement(model, beam, {chain[j], chain[j + 1]});
}

}  // namespace

void compileTrussMember(Model& model, const MemberSpec& member, const TrussDescription& truss) {
  const TrussGeometry geometry = buildTrussGeometry(truss);
  switch (member.fidelity) {
    case TrussFidelity::Members: compileMembers(model, member, geometry); break;
    case TrussFidelity::SuperTruss:
      addElement(model, SuperTrussKernel(geometry, member.quadrature > 0 ? member.quadrature : 4, member.damping),
                 addEndSections(model, member, geometry));
      break;
    case TrussFidelity::Condensed:
      addElement(model, CondensedTrussKernel(geometry, member.quadrature > 0 ? member.quadrature : 3, member.damping),
                 addEndSections(model, member, geometry));
      break;
    case TrussFidelity::Beam: compileEquivalentBeam(model, member, geometry); break;
  }
}

}  // namespace cranesim
