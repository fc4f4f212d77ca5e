#pragma once
// The crane's static map (thesis 6.2, 8.4.1): on a grid of boom angles × hoist-rope changes,
// the equilibrium of the crane with its control variables (the unstretched luffing and hoist
// rope lengths) and the load's end point.
//
// The boom angle is prescribed and the luffing rope length is the unknown that holds it: each
// point solves the equilibrium equations bordered by one angle condition,
//   R(x, L) = 0,   θ(q) − θ* = 0,   x = [q, λ], L the luffing rope's unstretched length,
// by a chord (modified Newton) method whose factorised Jacobian is reused from point to point
// and refreshed when the contraction slows. Every point starts from its neighbour's solution:
// first the boom angles at the hoist change nearest the scene's own hoist rope, outwards from
// the scene's equilibrium (a step that fails is halved), then every boom angle's row of hoist
// changes in both directions, the rows in parallel: threads, and MPI ranks under mpirun (each
// row is a task of parallel/task_farm.hpp and starts from its spine point alone, so the map is
// the same, bit for bit, whoever computes its rows).

#include <functional>
#include <string>
#include <vector>

#include "cranesim/model/model.hpp"

namespace cranesim {

/// Which parts of the scene are the crane's controls and its end point.
struct CraneControls {
  std::string luffing_rope;          // rope member whose unstretched length sets the boom angle
  std::string hoist_rope;            // rope member whose unstretched length sets the load height
  std::string boom_foot, boom_head;  // joints: boom angle = elevation of (head − foot) above horizontal
  std::string end_point;             // joint whose position is the planned end point
};

struct StaticMapSpec {
  std::vector<double> boom_angles_deg;  // increasing
  std::vector<double> hoist_changes;    // increasing; m of hoist rope taken in from hoist_length
  double hoist_length = 0.0;            // unstretched hoist rope at hoist change 0 (≤ 0: the scene's)
  double tolerance = 1e-10;             // on the chord step, relative to 1 + max|q| and to L
  int max_iterations = 40;              // per point
  int threads = 0;                      // 0: all cores
};

/// Values per grid point (rows: boom angles, columns: hoist changes); NaN where a point failed.
struct StaticMap {
  std::vector<double> boom_angles_deg, hoist_changes;
  double hoist_length = 0.0;
  Eigen::MatrixXd luffing_length, hoist_rope_length, end_x, end_y, end_z;
  Eigen::MatrixXi iterations;            // chord iterations per point
  std::vector<VecX> equilibria;          // [q, λ] per point, row-major (i · columns + j)
  std::vector<std::string> failures;     // one line per failed point
  int jacobians = 0;                     // Jacobian factorisations over the sweep
  int start_iterations = 0;              // Newton iterations of the scene's own equilibrium
  double start_time_s = 0.0, sweep_time_s = 0.0;
  double time_s = 0.0;                   // all of it: models, start, spine and rows
  int threads = 1;                       // rank 0's threads
  std::string execution;                 // who computed the rows, e.g. "2 threads"

  int rows() const { return static_cast<int>(boom_angles_deg.size()); }
  int columns() const { return static_cast<int>(hoist_changes.size()); }
};

/// The scene with every drive, load scale and rope length frozen at its value at solver.t_start.
Scene freezeScene(const Scene& scene);

/// The frozen scene (freezeScene) with the control ropes' unstretched lengths replaced.
Scene withControls(const Scene& scene, const CraneControls& controls, const Profile& luffing, const Profile& hoist);

/// Checks that the controls name rope members and existing joints; throws SceneError naming
/// `where` (the target file's YAML location of the controls) otherwise.
void checkControls(const Scene& scene, const CraneControls& controls, const SourceLocation& where);

/// The scene as the map solves it: drives frozen at solver.t_start, the hoist rope at
/// `hoist_length`, and the luffing rope's length the time argument (L(t) = t, so that the
/// equilibrium system at time L is the crane with luffing rope L), starting at `luffing_length`.
Model mapModel(const Scene& scene, const CraneControls& controls, double hoist_length, double luffing_length);

class MpiSession;  // parallel/mpi_farm.hpp

/// Sweeps the grid. `log` receives one progress line per finished row (may be empty). With
/// `ranks` (rank 0 of an MPI job), the rows are also farmed out to the other ranks, which call
/// computeStaticMapRowsForRank0 with the same arguments; rank 0 then computes on spec.threads
/// threads, or one when that is 0.
StaticMap computeStaticMap(const Scene& scene, const CraneControls& controls, const StaticMapSpec& spec,
                           const std::function<void(const std::string&)>& log = {}, const MpiSession* ranks = nullptr);

#ifdef CRANESIM_WITH_MPI
/// Ranks 1 … of an MPI job: computes the rows rank 0's computeStaticMap hands out, until the
/// map is done (or rank 0 could not start it).
void computeStaticMapRowsForRank0(const Scene& scene, const CraneControls& controls, const StaticMapSpec& spec,
                                  const MpiSession& ranks);
#endif

}  // namespace cranesim
