#pragma once
// The compiled model: nodes carrying generalized coordinates, elements on nodes, joints
// (frames fixed on nodes, 4-5), constraints between joints, loads on joints. Built once from a
// Scene (model/compile.hpp); constant during a simulation.

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "cranesim/model/constraint_equations.hpp"
#include "cranesim/model/element.hpp"
#include "cranesim/model/envelope.hpp"
#include "cranesim/model/scene.hpp"
#include "cranesim/model/wind_field.hpp"

namespace cranesim {

/// What a node's generalized coordinates are. Every kind but Material starts with the position
/// r; the velocity of each coordinate is its time derivative except for the rotation vector φ,
/// whose velocity is the body-frame angular velocity ω = T(φ) φ̇ (2-10).
enum class NodeKind {
  Point,         // [r]: strut tie ends (3-7)
  Frame,         // [r, φ]: rigid bodies (3-1), Timoshenko beam nodes (3-28)
  FrameStretch,  // [r, φ, ‖r'‖]: cubic spline beam nodes (3-54)
  PointSlope,    // [r, r']: cubic spline rope nodes (C-141)
  Material,      // [σ]: how much rope lies beyond a sheave (elements/massive_reeving.hpp), m
};

inline constexpr int kMaxNodeSize = 7;

inline int nodeSize(NodeKind kind) {
  switch (kind) {
    case NodeKind::Point: return 3;
    case NodeKind::Frame: return 6;
    case NodeKind::FrameStretch: return 7;
    case NodeKind::PointSlope: return 6;
    case NodeKind::Material: return 1;
  }
  return 0;
}

/// A node's coordinates sit at q[q … q + size) and its velocities at dq[v … v + size).
struct Node {
  std::string name;
  NodeKind kind = NodeKind::Frame;
  int q = 0;
  int v = 0;
  std::string member;  // the flexible member the node belongs to; empty for a rigid body

  int size() const { return nodeSize(kind); }
  /// Whether coordinates 3…5 are a rotation vector (and velocities 3…5 a body angular velocity).
  bool hasRotation() const { return kind == NodeKind::Frame || kind == NodeKind::FrameStretch; }
  /// Whether coordinates 0…2 are a position (all kinds but Material).
  bool hasPosition() const { return kind != NodeKind::Material; }
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

  ConstraintLaw law(Limit limit = Limit::Left) const { return {type, axis, drive ? &*drive : nullptr, limit}; }
};

struct Load {
  std::string name;
  int joint = -1;
  Vec3 force = Vec3::Zero();
  Vec3 torque = Vec3::Zero();
  LoadFrame frame = LoadFrame::Inertial;
  Profile scale;
};

/// A drive the model's caller commands while it runs (math/input_signal.hpp): a rope's length,
/// a driven constraint, a load's scale. Its signal is the model's mutable part: one run at a time.
struct ModelInput {
  std::string name;  // the rope's, constraint's or load's name
  std::string what;  // "rope length", "drive", "load scale"
  std::shared_ptr<InputSignal> signal;
};

/// A part the wind acts on (a body, a member) and the wind elements (model/wind_elements.hpp)
/// that carry its forces.
struct WindPart {
  std::string name;
  std::vector<int> elements;
};

struct Model {
  std::string name;
  std::vector<Node> nodes;
  std::vector<std::unique_ptr<Element>> elements;
  std::vector<Joint> joints;
  std::vector<Constraint> constraints;
  std::vector<Load> loads;
  /// The wind field, if the scene has one, and the parts exposed to it.
  std::shared_ptr<const WindField> wind;
  std::vector<WindPart> wind_parts;
  /// The reeved ropes' elements (model/reeved_rope_element.hpp), in the scene's order.
  std::vector<int> reeved_ropes;
  /// What a run is checked against (model/envelope.hpp), with the ground's contacts.
  Envelope envelope;
  /// Pairs of joints joined by a straight line when the mechanism is drawn (members' elements,
  /// truss tubes); rigid bodies are drawn from their origin to each of their joints.
  std::vector<std::array<int, 2>> drawing_lines;
  /// The inputs, in the scene's order: ropes, constraints, loads.
  std::vector<ModelInput> inputs;
  /// Time-dependent element parameters (rope lengths): their breakpoints restart the integrator.
  std::vector<Profile> parameter_profiles;
  Vec3 gravity = Vec3::Zero();
  int nq = 0;  // size of q
  int nv = 0;  // size of dq
  int m = 0;   // number of constraint equations
  VecX q0, v0;  // initial state as given by the scene
  SolverSpec solver;
  OutputSpec output;
  /// The beam elements of each member in output.section_forces, in that order, or a rope's
  /// elements (their tensions at kTensionPoints points each).
  struct SectionForceGroup {
    std::string member;
    std::vector<int> elements;
    bool rope = false;
  };
  std::vector<SectionForceGroup> section_force_groups;

  /// Appends a node of the given kind, placing its coordinates after the existing ones.
  int addNode(std::string name, NodeKind kind, std::string member = "");
  /// The absolute tolerance of every coordinate and velocity, [q, dq] (solver.atol by kind).
  VecX absoluteTolerances() const;
  /// Frame of a node at coordinates q (identity rotation for nodes without one).
  Frame nodeFrame(const double* q, int node) const;
  /// Frame of a joint at coordinates q.
  Frame jointFrame(const double* q, int joint) const;
  int findJoint(const std::string& name) const;  // −1 if absent
  int findConstraint(const std::string& name) const;  // −1 if absent
  int findInput(const std::string& name) const;       // −1 if absent
  /// An input profile with its own signal, at rest from solver.t_start and listed in `inputs`
  /// under `name`; any other profile as it is.
  Profile attachInput(const Profile& profile, const std::string& name, const std::string& what,
                      const SourceLocation& where);
  /// All times where a drive, load or element-parameter profile has a kink or jump in its
  /// second derivative.
  std::vector<double> breakpoints() const;
};

}  // namespace cranesim
