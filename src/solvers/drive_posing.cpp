#include "cranesim/solvers/drive_posing.hpp"

#include <cmath>
#include <numbers>

#include "cranesim/math/rotation.hpp"
#include "cranesim/model/node_graph.hpp"

namespace cranesim {
namespace {

/// Moves node n rigidly: x ↦ c + R (x − c) + shift.
void moveNode(const Node& n, const Vec3& c, const Mat3& R, const Vec3& shift, VecX& q, VecX* v) {
  if (!n.hasPosition()) return;
  q.segment<3>(n.q) = c + R * (q.segment<3>(n.q) - c) + shift;
  if (n.hasRotation()) q.segment<3>(n.q + 3) = rotationVector(Mat3(R * rotationMatrix<double>(Vec3(q.segment<3>(n.q + 3)))));
  if (n.kind == NodeKind::PointSlope) q.segment<3>(n.q + 3) = R * q.segment<3>(n.q + 3);
  if (!v) return;
  v->segment<3>(n.v) = R * v->segment<3>(n.v);
  if (n.kind == NodeKind::PointSlope) v->segment<3>(n.v + 3) = R * v->segment<3>(n.v + 3);
}

}  // namespace

int poseAtDrives(const Model& model, double t, VecX& q, VecX* v) {
  int posed = 0;
  for (std::size_t ci = 0; ci < model.constraints.size(); ++ci) {
    const Constraint& c = model.constraints[ci];
    if (!c.drive || (c.type != ConstraintType::Revolute && c.type != ConstraintType::Prismatic)) continue;
    NodeGraph graph(model, static_cast<int>(ci));
    const int n1 = model.joints[c.joint1].node, n2 = model.joints[c.joint2].node;
    // The side that moves: the second joint's, or else the first's (turned the other way).
    int moving = -1;
    double sign = 1.0;
    if (n2 >= 0 && !graph.grounded(n2) && (n1 < 0 || !graph.connected(n1, n2))) moving = n2;
    else if (n1 >= 0 && !graph.grounded(n1) && (n2 < 0 || !graph.connected(n1, n2))) moving = n1, sign = -1.0;
    if (moving < 0) continue;
    const Frame j1 = model.jointFrame(q.data(), c.joint1), j2 = model.jointFrame(q.data(), c.joint2);
    double change = (*c.drive)(t) - drivenCoordinate(c.law(), j1, j2);
    if (c.type == ConstraintType::Revolute) change = std::remainder(change, 2.0 * std::numbers::pi);
    if (change == 0.0) continue;
    const Vec3 axis = j1.R.col(c.axis);
    const Mat3 R = c.type == ConstraintType::Revolute ? axisAngle(axis, sign * change) : Mat3::Identity();
    const Vec3 shift = c.type == ConstraintType::Prismatic ? Vec3(sign * change * axis) : Vec3::Zero();
    const Vec3 centre = sign > 0.0 ? j1.r : j2.r;
    const int part = graph.root(moving);
    for (std::size_t n = 0; n < model.nodes.size(); ++n)
      if (graph.root(static_cast<int>(n)) == part) moveNode(model.nodes[n], centre, R, shift, q, v);
    ++posed;
  }
  return posed;
}

}  // namespace cranesim
