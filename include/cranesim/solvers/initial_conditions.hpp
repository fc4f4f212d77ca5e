#pragma once
// Consistent initial conditions (docs/architecture.md#consistent-initial-state): positions on
// Φ = 0, velocities on Φ̇ = 0, and accelerations and multipliers from the saddle-point system (4-3)
//   [M  Gᵀ] [d(dq)/dt]   [−F + Q]
//   [G  0 ] [   λ    ] = [  −Γ  ].

#include <vector>

#include "cranesim/assembly/assembler.hpp"
#include "cranesim/math/sparse_lu.hpp"

namespace cranesim {

struct DynamicState {
  double t = 0.0;
  VecX q, v, a, lambda, qdot;
};

/// Checks the constraint Jacobian for redundant equations; throws SceneError naming them.
void requireIndependentConstraints(const Assembler& assembler, const VecX& q, double t);

/// How far assembly moved the drawing: the largest displacement of a joint (m) and the largest
/// turn of a joint frame (rad), each with the joint's name, and the scene's size (the diagonal
/// of the drawn joints' bounding box) the displacement is measured against.
struct AssemblyMove {
  double displacement = 0.0, rotation = 0.0, scene_size = 0.0;
  std::string displaced_joint, rotated_joint;
  /// "0.87 mm at joint 'jib.tip'; 1.2e-05 rad at 'jib.tip'", for the tools' reports.
  std::string describe() const;
  /// Whether the drawing moved by more than rounding (1e-9 of its size, or 1e-9 rad).
  bool visible() const { return displacement > 1e-9 * scene_size || rotation > 1e-9; }
};

/// Assembles (q, v): positions closed onto Φ = 0 by the least change of the coordinates
/// (Gauss–Newton, minimum-norm steps), velocities projected onto Φ̇ = 0, then a and λ solved.
/// Throws SceneError naming the most violated constraint when the drawing cannot be closed or
/// closing it moves a joint by more than `tolerance` × the scene's size or turns one by more
/// than `tolerance` rad (solver.assembly_tolerance). `move`, if given, receives the move.
DynamicState consistentInitialState(const Assembler& assembler, double t, VecX q, VecX v, double tolerance,
                                    AssemblyMove* move = nullptr);

/// The scene's drawn state (q, v) at time t: posed at its drives' values (solvers/drive_posing.hpp),
/// then assembled as by consistentInitialState.
DynamicState assembledInitialState(const Assembler& assembler, double t, VecX q, VecX v, double tolerance,
                                   AssemblyMove* move = nullptr);

/// Solves the saddle-point system (4-3) for a and λ, or for a drive's velocity jump, by KLU. While
/// M's and G's patterns stay the same, as they do from one output sample to the next, keeps the
/// matrix's pattern (the values scattered into it), the ordering and symbolic analysis, and
/// refactors with the previous pivot sequence while that stays well conditioned.
class AccelerationSolver {
 public:
  void solve(const Assembler& assembler, DynamicState& state, const ConstraintState& constraints, Limit limit);
  /// The same with the mass matrix M(state.q) at hand.
  void solve(const Assembler& assembler, DynamicState& state, const ConstraintState& constraints,
             const Eigen::SparseMatrix<double>& mass, Limit limit);
  /// jumpVelocities (below) with this solver's factorisation.
  double jump(const Assembler& assembler, DynamicState& state, const ConstraintState& constraints);

 private:
  /// Factorises [M Gᵀ; G 0]; `where` completes the message when it is singular.
  void factorise(const Eigen::SparseMatrix<double>& mass, const Eigen::SparseMatrix<double>& G, double t,
                 const char* where);
  /// Whether M and G have the patterns the saddle-point matrix was built for.
  bool samePattern(const Eigen::SparseMatrix<double>& mass, const Eigen::SparseMatrix<double>& G) const;
  /// Builds the saddle-point matrix's pattern and where each entry of M and G goes in it.
  void buildPattern(const Eigen::SparseMatrix<double>& mass, const Eigen::SparseMatrix<double>& G);

  Eigen::SparseMatrix<double> matrix_;
  std::vector<int> mass_slots_, constraint_slots_, transposed_slots_;  // value positions of M's, G's and Gᵀ's entries
  std::vector<int> mass_outer_, mass_inner_, constraint_outer_, constraint_inner_;  // the patterns built for
  SparseLU lu_;
};

/// The velocities just after a drive's velocity jumps (a breakpoint where a ramp starts, a
/// linear table's knot): the response of the masses to the impulse through the constraints,
/// [M Gᵀ; G 0] [Δv; p] = [0; −(G v + Φ_t)] at (state.t, state.q), C evaluated on the coming
/// side. A least-norm change of v would move directions no impulse reaches (a pendulum's bob when
/// its cart jumps). Returns the kinetic energy the jump adds: the drives' impulsive work.
double jumpVelocities(const Assembler& assembler, DynamicState& state, const ConstraintState& constraints);

/// Recomputes a, λ and q̇ for a state whose q and v are already consistent. `limit`: Right
/// when restarting from a breakpoint, so the accelerations are those of the coming segment.
void solveAccelerations(const Assembler& assembler, DynamicState& state, Limit limit = Limit::Left);
/// The same with the constraint quantities at (state.t, state.q, state.v) already evaluated.
void solveAccelerations(const Assembler& assembler, DynamicState& state, const ConstraintState& constraints,
                        Limit limit = Limit::Left);

}  // namespace cranesim
