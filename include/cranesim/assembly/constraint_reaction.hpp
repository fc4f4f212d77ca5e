#pragma once
// The load a constraint transmits, from its multipliers: the generalized force −Gᵀλ of its rows
// on the node of its second joint (a force on the node's origin, inertial axes, and a torque in
// the node's axes: virtual power ṙᵀf + ωᵀτ), reduced to the second joint's origin and expressed
// in the first joint's axes. For a slewing ring [ground.ring, pedestal.origin] with axis z this
// is what the ring carries: the axial force F_z, the radial force (F_x, F_y), the tilting moment
// (M_x, M_y) and the slewing drive's torque M_z. When the second joint is on the ground, the same
// load follows from the first joint's node by Newton's third law.

#include <Eigen/Sparse>

#include "cranesim/model/model.hpp"

namespace cranesim {

struct ConstraintReaction {
  Vec3 force = Vec3::Zero();   // N
  Vec3 moment = Vec3::Zero();  // N·m, about the second joint's origin
};

/// `G`: the constraint Jacobian (m × nv) at q; `lambda`: all m multipliers.
ConstraintReaction constraintReaction(const Model& model, const Constraint& constraint, const Eigen::SparseMatrix<double>& G,
                                      const double* q, const double* lambda);

/// The moment about the directed line `from` → `to` (right hand) of the loads the constraints
/// `supports` carry to the nodes they hold (−Gᵀλ of their rows: a force on each node's origin,
/// a torque in its axes). For supports that join the structure to the ground this is the
/// ground's moment on the structure about a tipping edge: minus the moment of gravity, loads and
/// inertia about it, positive while the structure stands on its footprint.
double supportMoment(const Model& model, const std::vector<int>& supports, const Vec3& from, const Vec3& to,
                     const Eigen::SparseMatrix<double>& G, const double* q, const double* lambda);

}  // namespace cranesim
