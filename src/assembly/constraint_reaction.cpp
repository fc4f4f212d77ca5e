#include "cranesim/assembly/constraint_reaction.hpp"

namespace cranesim {

ConstraintReaction constraintReaction(const Model& model, const Constraint& constraint, const Eigen::SparseMatrix<double>& G,
                                      const double* q, const double* lambda) {
  VecX own = VecX::Zero(model.m);
  own.segment(constraint.row, constraint.rows) = Eigen::Map<const VecX>(lambda + constraint.row, constraint.rows);
  const VecX generalized = -(G.transpose() * own);
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

}  // namespace cranesim
