#pragma once
// The compiled model: nodes carrying generalized coordinates, elements on nodes, joints
// (frames fixed on nodes, 4-5), constraints between joints, loads on joints. Built once from a
// Scene (model/compile.hpp); constant during a simulation.

#include <memory>
#include <string>
#include <vector>

#include "cranesim/model/constraint_equations.hpp"
#include "cranesim/model/element.hpp"
#include "cranesim/model/scene.hpp"

namespace cranesim {

/// A frame node: q = [r, φ] (6), dq = [ṙ, ω_body] (6), at offsets `q` and `v`.
struct Node {
  std::string name;
  int q = 0;
  int v = 0;
};

/// A frame fixed on a node (4-5): r_J = r + R r_BJ, R_J = R R_BJ. `node` < 0: the ground,
/// where `offset` and `rotation` are the frame itself.
struct Joint {
  std::string name;  // "<body>.<joint>"
  int node = -1;
  Vec3 offset = Vec3::Zero();
  Mat3 rotation = Mat3::Identity();
};

struct Constraint {
  std::string name;
  ConstraintType type = ConstraintType::Fixed;
  int joint1 = -1, joint2 = -1;
  int axis = 2;
  std::optional<Profile> drive;
  int row = 0;   // first row in the constraint vector Φ
  int rows = 0;  // number of equations
  std::vector<std::string> row_labels;
  SourceLocation where;

  ConstraintLaw law() const { return {type, axis, drive ? &*drive : nullptr}; }
};

struct Load {
  std::string name;
  int joint = -1;
  Vec3 force = Vec3::Zero();
  Vec3 torque = Vec3::Zero();
  LoadFrame frame = LoadFrame::Inertial;
  Profile scale;
};

struct Model {
  std::string name;
  std::vector<Node> nodes;
  std::vector<std::unique_ptr<Element>> elements;
  std::vector<Joint> joints;
  std::vector<Constraint> constraints;
  std::vector<Load> loads;
  Vec3 gravity = Vec3::Zero();
  int nq = 0;  // size of q
  int nv = 0;  // size of dq
  int m = 0;   // number of constraint equations
  VecX q0, v0;  // initial state as given by the scene
  SolverSpec solver;
  OutputSpec output;

  /// Frame of a node at coordinates q.
  Frame nodeFrame(const double* q, int node) const;
  /// Frame of a joint at coordinates q.
  Frame jointFrame(const double* q, int joint) const;
  int findJoint(const std::string& name) const;  // −1 if absent
  /// All times where a drive or load profile has a kink or jump in its second derivative.
  std::vector<double> breakpoints() const;
};

}  // namespace cranesim
