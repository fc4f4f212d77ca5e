#include "cranesim/assembly/constraint_reaction.hpp"

namespace cranesim {
namespace {

/// −Gᵀλ of the constraint's rows alone.
VecX generalizedLoad(const Model& model, const Constraint& constraint, const Eigen::SparseMatrix<double>& G, const double* lambda) {
  VecX own = VecX::Zero(model.m);
  own.segment(constraint.row, constraint.rows) = Eigen::Map<const VecX>(lambda + constraint.row, constraint.rows);
  return -(G.transpose() * own);
}

}  // namespace

ConstraintReaction constraintReaction(const Model& model, const Constraint& constraint, const Eigen::SparseMatrix<double>& G,
                                      const double* q, const double* lambda) {
  const VecX generalized = generalizedLoad(model, constraint, G, lambda);
  const bool second = model.joints[constraint.joint2].node >= 0;
  const int node = model.joints[second ? constraint.joint2 : constraint.joint1].node;
  ConstraintReaction out;
  if (node < 0) return out;  // both joints on the ground: nothing moves
  const Frame frame = model.nodeFrame(q, node), axes = model.jointFrame(q, constraint.joint1);
  const Vec3 point = model.jointFrame(q, constraint.joint2).r;
  const int v = model.nodes[node].v;
  const Vec3 force = generalized.segment<3>(v);
  Vec3 moment = (frame.r - point).cross(force);
  if (model.nodes[node].hasRotation()) moment += frame.R * Vec3(generalized.segment<3>(v + 3));
  const double sign = second ? 1.0 : -1.0;
  out.force = sign * (axes.R.transpose() * force);
  out.moment = sign * (axes.R.transpose() * moment);
  return out;
}

double supportMoment(const Model& model, const std::vector<int>& supports, const Vec3& from, const Vec3& to,
                     const Eigen::SparseMatrix<double>& G, const double* q, const double* lambda) {
  const Vec3 axis = (to - from).normalized();
  double moment = 0.0;
  for (const int k : supports) {
    const Constraint& c = model.constraints[k];
    const VecX generalized = generalizedLoad(model, c, G, lambda);
    for (const int joint : {c.joint1, c.joint2}) {
      const int n = model.joints[joint].node;
      if (n < 0) continue;
      const Frame frame = model.nodeFrame(q, n);
      const Vec3 force = generalized.segment<3>(model.nodes[n].v);
      Vec3 torque = (frame.r - from).cross(force);
      if (model.nodes[n].hasRotation()) torque += frame.R * Vec3(generalized.segment<3>(model.nodes[n].v + 3));
      moment += axis.dot(torque);
    }
  }
  return moment;
}

}  // namespace cranesim
