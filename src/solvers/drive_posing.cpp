#include "cranesim/solvers/drive_posing.hpp"

#include <cmath>
#include <numbers>
#include <numeric>

#include "cranesim/math/rotation.hpp"

namespace cranesim {
namespace {

/// Nodes joined by elements and by constraints other than `cut`; the ground is node −1 and is
/// joined to nothing (it does not move).
class NodeGraph {
 public:
  NodeGraph(const Model& model, int cut) : parent_(model.nodes.size()) {
    std::iota(parent_.begin(), parent_.end(), 0);
    for (const auto& e : model.elements)
      for (int n : e->nodes()) join(e->nodes().front(), n);
    for (std::size_t c = 0; c < model.constraints.size(); ++c) {
      if (static_cast<int>(c) == cut) continue;
      const int a = model.joints[model.constraints[c].joint1].node, b = model.joints[model.constraints[c].joint2].node;
      if (a < 0 || b < 0) grounded_.push_back(a < 0 ? b : a);
      else join(a, b);
    }
  }
  int root(int n) {
    while (parent_[n] != n) n = parent_[n] = parent_[parent_[n]];
    return n;
  }
  /// Whether node n's part touches the ground through a constraint other than the cut one.
  bool grounded(int n) {
    for (int g : grounded_)
      if (g >= 0 && root(g) == root(n)) return true;
    return false;
  }

 private:
  void join(int a, int b) { parent_[root(a)] = root(b); }
  std::vector<int> parent_;
  std::vector<int> grounded_;
};

/// Moves node n rigidly: x ↦ c + R (x − c) + shift.
void moveNode(const Node& n, const Vec3& c, const Mat3& R, const Vec3& shift, VecX& q, VecX* v) {
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
    if (n2 >= 0 && !graph.grounded(n2) && (n1 < 0 || graph.root(n1) != graph.root(n2))) moving = n2;
    else if (n1 >= 0 && !graph.grounded(n1) && (n2 < 0 || graph.root(n1) != graph.root(n2))) moving = n1, sign = -1.0;
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
