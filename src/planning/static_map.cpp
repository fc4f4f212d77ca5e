#include "cranesim/planning/static_map.hpp"

#include <fmt/format.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/info.h>

#include <Eigen/SparseLU>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <numbers>
#include <optional>

#include "cranesim/model/compile.hpp"
#include "cranesim/solvers/equilibrium_path.hpp"
#include "cranesim/solvers/equilibrium_system.hpp"
#include "cranesim/solvers/statics.hpp"

namespace cranesim {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

template <class SceneT> auto& member(SceneT& scene, const std::string& name) {
  for (auto& m : scene.members)
    if (m.name == name) return m;
  throw std::logic_error("no member " + name);  // checkControls rules this out
}

/// A control rope's unstretched length at solver.t_start (the chord when the scene gives none).
double ropeLengthAtStart(const Scene& scene, const std::string& rope) {
  const MemberSpec& m = member(scene, rope);
  return m.length ? (*m.length)(scene.solver.t_start) : (m.end - m.start).norm();
}

/// Boom angle and end point of a state, with the angle's gradient over the coordinates.
class CraneGeometry {
 public:
  CraneGeometry(const Model& model, const CraneControls& controls)
      : model_(model),
        foot_(model.findJoint(controls.boom_foot)),
        head_(model.findJoint(controls.boom_head)),
        end_(model.findJoint(controls.end_point)) {
    for (int joint : {foot_, head_}) {
      const int node = model.joints[joint].node;
      if (node < 0) continue;
      for (int k = 0; k < model.nodes[node].size(); ++k) angle_coordinates_.push_back(model.nodes[node].q + k);
    }
  }

  double boomAngle(const VecX& x) const {
    const Vec3 d = model_.jointFrame(x.data(), head_).r - model_.jointFrame(x.data(), foot_).r;
    return std::atan2(d.z(), std::hypot(d.x(), d.y()));
  }
  Vec3 endPoint(const VecX& x) const { return model_.jointFrame(x.data(), end_).r; }

  /// ∂θ/∂q by central differences over the coordinates of the two boom joints' nodes.
  std::vector<std::pair<int, double>> angleGradient(VecX x) const {
    std::vector<std::pair<int, double>> gradient;
    for (int k : angle_coordinates_) {
      const double x0 = x(k), h = 1e-6 * (1.0 + std::abs(x0));
      x(k) = x0 + h;
      const double up = boomAngle(x);
      x(k) = x0 - h;
      const double down = boomAngle(x);
      x(k) = x0;
      gradient.emplace_back(k, (up - down) / (2.0 * h));
    }
    return gradient;
  }

 private:
  const Model& model_;
  int foot_, head_, end_;
  std::vector<int> angle_coordinates_;
};

/// A factorised equilibrium Jacobian and ∂R/∂L, carried from point to point.
struct ChordJacobian {
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  VecX residual_by_length;
  bool valid = false;
  int factorisations = 0;
};

struct PointState {
  VecX x;
  double luffing_length = 0.0;
};

struct PointOutcome {
  bool converged = false;
  int iterations = 0;
  std::string why;
};

/// J and ∂R/∂L at the state s, factorised.
bool refreshJacobian(EquilibriumSystem& system, const PointState& s, ChordJacobian& jacobian) {
  system.setTime(s.luffing_length);
  const VecX r = system.residual(s.x);
  if (!factoriseShifted(system.jacobian(s.x), system.model().nv, jacobian.lu)) return false;
  const double h = 1e-7 * s.luffing_length;
  system.setTime(s.luffing_length + h);
  jacobian.residual_by_length = (system.residual(s.x) - r) / h;
  system.setTime(s.luffing_length);
  jacobian.valid = true;
  ++jacobian.factorisations;
  return true;
}

/// Chord iterations on the bordered system. In the map's models the luffing rope's length is
/// the time argument (length profile L(t) = t), so R(x, L) is the system at time L.
PointOutcome solvePoint(EquilibriumSystem& system, const CraneGeometry& geometry, PointState& s, double angle,
                        ChordJacobian& jacobian, const StaticMapSpec& spec) {
  const Model& model = system.model();
  double previous_step = std::numeric_limits<double>::infinity();
  bool fresh = false;
  for (int it = 1; it <= spec.max_iterations; ++it) {
    system.setTime(s.luffing_length);
    const VecX r = system.residual(s.x);
    if (!r.allFinite()) return {false, it, "the residual is not finite"};
    if (!jacobian.valid) {
      if (!refreshJacobian(system, s, jacobian)) return {false, it, "singular equilibrium Jacobian"};
      fresh = true;
    }
    // Bordered solve: dx = −a − b dL with J a = R, J b = ∂R/∂L, and θ(q + dq) = θ* to first order.
    const VecX a = jacobian.lu.solve(r), b = jacobian.lu.solve(jacobian.residual_by_length);
    double ga = 0.0, gb = 0.0;
    for (const auto& [k, g] : geometry.angleGradient(s.x)) {
      ga += g * a(k);
      gb += g * b(k);
    }
    if (std::abs(gb) < 1e-300) return {false, it, "the luffing rope does not move the boom (slack?)"};
    const double dL = (geometry.boomAngle(s.x) - angle - ga) / gb;
    const VecX dx = -a - b * dL;
    const double step = std::max(dx.head(model.nq).cwiseAbs().maxCoeff() / (1.0 + s.x.head(model.nq).cwiseAbs().maxCoeff()),
                                 std::abs(dL) / s.luffing_length);
    if (!fresh && step > 0.5 * previous_step) {  // slow contraction: refresh the Jacobian here
      jacobian.valid = false;
      continue;
    }
    s.x += dx;
    s.luffing_length += dL;
    reparameteriseRotations(model, s.x);
    fresh = false;
    previous_step = step;
    if (!(s.luffing_length > 0.0)) return {false, it, "the luffing rope length became negative"};
    if (step < spec.tolerance) return {true, it, ""};
  }
  return {false, spec.max_iterations, fmt::format("no convergence in {} chord iterations", spec.max_iterations)};
}

/// The point at `angle` from a solved one at `from_angle` (same hoist change): a step that does not
/// converge is halved, down to 1/16 of it. A stiff rope stretches to second order when the boom
/// turns, so a long step leaves the chord iteration far outside its region of convergence.
PointOutcome solveAngleStep(EquilibriumSystem& system, const CraneGeometry& geometry, PointState& s, double from_angle,
                            double angle, ChordJacobian& jacobian, const StaticMapSpec& spec, int halvings = 4) {
  const PointState from = s;
  PointOutcome outcome = solvePoint(system, geometry, s, angle, jacobian, spec);
  if (outcome.converged || halvings == 0) return outcome;
  s = from;
  jacobian.valid = false;
  const double middle = 0.5 * (from_angle + angle);
  const PointOutcome first = solveAngleStep(system, geometry, s, from_angle, middle, jacobian, spec, halvings - 1);
  if (!first.converged) return first;
  outcome = solveAngleStep(system, geometry, s, middle, angle, jacobian, spec, halvings - 1);
  outcome.iterations += first.iterations;
  return outcome;
}

/// Linear extrapolation from two neighbours along a grid line.
PointState predict(const PointState& older, const PointState& newer, double s_older, double s_newer, double s) {
  const double w = (s - s_newer) / (s_newer - s_older);
  return {newer.x + w * (newer.x - older.x), newer.luffing_length + w * (newer.luffing_length - older.luffing_length)};
}

}  // namespace

Scene freezeScene(const Scene& scene) {
  Scene frozen = scene;
  const double t = scene.solver.t_start;
  const auto freeze = [t](const Profile& p) { return Profile(ConstantProfile{p(t)}); };
  for (MemberSpec& m : frozen.members)
    if (m.length) m.length = freeze(*m.length);
  for (ConstraintSpec& c : frozen.constraints)
    if (c.drive) c.drive = freeze(*c.drive);
  for (LoadSpec& l : frozen.loads) l.scale = freeze(l.scale);
  return frozen;
}

void checkControls(const Scene& scene, const CraneControls& controls, const SourceLocation& where) {
  for (const std::string& rope : {controls.luffing_rope, controls.hoist_rope}) {
    bool found = false;
    for (const MemberSpec& m : scene.members)
      if (m.name == rope) {
        if (m.type != MemberType::Rope)
          throw SceneError(where, fmt::format("member '{}' is not a rope: only a rope's length is a control", rope));
        found = true;
      }
    if (!found) throw SceneError(where, fmt::format("the scene has no member '{}'", rope));
  }
  if (controls.luffing_rope == controls.hoist_rope)
    throw SceneError(where, "the luffing and hoist ropes must be different members");
  const Model model = compileModel(scene);
  for (const std::string& joint : {controls.boom_foot, controls.boom_head, controls.end_point})
    if (model.findJoint(joint) < 0) throw SceneError(where, fmt::format("the scene has no joint '{}'", joint));
}

Scene withControls(const Scene& scene, const CraneControls& controls, const Profile& luffing, const Profile& hoist) {
  Scene driven = freezeScene(scene);
  member(driven, controls.luffing_rope).length = luffing;
  member(driven, controls.hoist_rope).length = hoist;
  return driven;
}

Model mapModel(const Scene& scene, const CraneControls& controls, double hoist_length, double luffing_length) {
  Scene driven = withControls(scene, controls, Profile(RampProfile{0.0, 1.0, 0.0}), Profile(ConstantProfile{hoist_length}));
  driven.solver.t_start = luffing_length;
  return compileModel(driven);
}

StaticMap computeStaticMap(const Scene& scene, const CraneControls& controls, const StaticMapSpec& spec,
                           const std::function<void(const std::string&)>& log) {
  using Clock = std::chrono::steady_clock;
  const int threads = spec.threads > 0 ? spec.threads : tbb::info::default_concurrency();
  tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, threads);
  const auto say = [&](const std::string& line) {
    if (log) log(line);
  };

  StaticMap map;
  map.boom_angles_deg = spec.boom_angles_deg;
  map.hoist_changes = spec.hoist_changes;
  map.threads = threads;
  const int rows = map.rows(), columns = map.columns();
  for (Eigen::MatrixXd* m : {&map.luffing_length, &map.hoist_rope_length, &map.end_x, &map.end_y, &map.end_z})
    m->setConstant(rows, columns, std::numeric_limits<double>::quiet_NaN());
  map.iterations.setZero(rows, columns);
  map.equilibria.resize(static_cast<std::size_t>(rows) * columns);

  // The spine column: the hoist change closest to the scene's own hoist rope.
  const auto t0 = Clock::now();
  const double start_luffing = ropeLengthAtStart(scene, controls.luffing_rope);
  const double scene_hoist = ropeLengthAtStart(scene, controls.hoist_rope);
  map.hoist_length = spec.hoist_length > 0.0 ? spec.hoist_length : scene_hoist;
  int spine_column = 0;
  for (int j = 1; j < columns; ++j)
    if (std::abs(map.hoist_length - map.hoist_changes[j] - scene_hoist) <
        std::abs(map.hoist_length - map.hoist_changes[spine_column] - scene_hoist))
      spine_column = j;

  // Where the continuation starts: the scene's equilibrium with its hoist rope at the spine
  // column's length (a hoist rope paid out from a solved state would start slack).
  const Scene start_scene = withControls(scene, controls, Profile(ConstantProfile{start_luffing}),
                                         Profile(ConstantProfile{map.hoist_length - map.hoist_changes[spine_column]}));
  const Model start_model = compileModel(start_scene);
  const StaticResult start = solveEquilibrium(start_scene, start_model, start_scene.solver.t_start);
  map.start_iterations = start.iterations;
  map.start_time_s = std::chrono::duration<double>(Clock::now() - t0).count();
  if (!start.converged) throw std::runtime_error("the scene's equilibrium, where the map starts: " + start.message);
  say(fmt::format("scene equilibrium: {} Newton iterations, {:.1f} s", start.iterations, map.start_time_s));

  std::vector<Model> models;
  for (double change : spec.hoist_changes) {
    if (!(map.hoist_length - change > 0.0))
      throw std::invalid_argument(fmt::format("hoist change {} m exceeds the hoist rope's length {} m", change, map.hoist_length));
    models.push_back(mapModel(scene, controls, map.hoist_length - change, start_luffing));
  }
  const CraneGeometry geometry(models[0], controls);  // joints sit alike in every map model

  const auto t1 = Clock::now();
  std::mutex record_mutex;
  std::atomic<int> factorisations{0};
  const auto record = [&](int i, int j, const PointState& s, const PointOutcome& outcome) {
    std::lock_guard lock(record_mutex);
    map.iterations(i, j) = outcome.iterations;
    if (!outcome.converged) {
      map.failures.push_back(fmt::format("boom angle {:g}°, hoist change {:g} m: {}", map.boom_angles_deg[i],
                                         map.hoist_changes[j], outcome.why));
      return;
    }
    const Vec3 end = geometry.endPoint(s.x);
    map.luffing_length(i, j) = s.luffing_length;
    map.hoist_rope_length(i, j) = map.hoist_length - map.hoist_changes[j];
    map.end_x(i, j) = end.x();
    map.end_y(i, j) = end.y();
    map.end_z(i, j) = end.z();
    map.equilibria[static_cast<std::size_t>(i) * columns + j] = s.x;
  };

  // The spine: boom angles outwards from the scene's equilibrium, in the spine column.
  std::vector<PointState> spine(rows);
  std::vector<bool> spine_ok(rows, false);
  {
    EquilibriumSystem system(models[spine_column], start_luffing);
    PointState origin;
    origin.x.resize(system.size());
    origin.x << start.q, start.lambda;
    origin.luffing_length = start_luffing;
    const double start_angle = geometry.boomAngle(origin.x);
    int nearest = 0;
    for (int i = 1; i < rows; ++i)
      if (std::abs(map.boom_angles_deg[i] * kDegree - start_angle) < std::abs(map.boom_angles_deg[nearest] * kDegree - start_angle))
        nearest = i;
    ChordJacobian jacobian;
    for (int direction : {-1, +1}) {
      jacobian.valid = false;
      for (int i = direction < 0 ? nearest : nearest + 1; i >= 0 && i < rows; i += direction) {
        const int back1 = i - direction, back2 = i - 2 * direction;
        const auto solved = [&](int k) { return k >= 0 && k < rows && spine_ok[k]; };
        const double angle = map.boom_angles_deg[i] * kDegree;
        PointState s;
        PointOutcome outcome;
        if (solved(back1) && solved(back2)) {
          s = predict(spine[back2], spine[back1], map.boom_angles_deg[back2], map.boom_angles_deg[back1],
                      map.boom_angles_deg[i]);
          outcome = solvePoint(system, geometry, s, angle, jacobian, spec);
        }
        if (!outcome.converged) {  // no extrapolation, or it failed: from the neighbour, in halved steps if need be
          const int spent = outcome.iterations;
          s = solved(back1) ? spine[back1] : origin;
          if (spent > 0) jacobian.valid = false;
          outcome = solveAngleStep(system, geometry, s, solved(back1) ? map.boom_angles_deg[back1] * kDegree : start_angle,
                                   angle, jacobian, spec);
          outcome.iterations += spent;
        }
        record(i, spine_column, s, outcome);
        if (!outcome.converged) break;  // the angles beyond would start from a failed point
        spine[i] = s;
        spine_ok[i] = true;
      }
    }
    factorisations += jacobian.factorisations;
  }
  say(fmt::format("hoist change {:g} m: {} boom angles, {:.1f} s", map.hoist_changes[spine_column],
                  std::count(spine_ok.begin(), spine_ok.end(), true),
                  std::chrono::duration<double>(Clock::now() - t1).count()));

  // The rows: hoist changes at each boom angle, one task per row.
  tbb::enumerable_thread_specific<std::vector<std::unique_ptr<EquilibriumSystem>>> systems;
  std::atomic<int> rows_done{0};
  tbb::parallel_for(0, rows, [&](int i) {
    if (!spine_ok[i]) return;
    auto& mine = systems.local();
    if (mine.empty()) mine.resize(columns);
    ChordJacobian jacobian;
    std::vector<std::optional<PointState>> row(columns);
    row[spine_column] = spine[i];
    for (int direction : {+1, -1}) {  // from the spine column towards both ends of the row
      jacobian.valid = false;
      for (int j = spine_column + direction; j >= 0 && j < columns; j += direction) {
        if (!mine[j]) mine[j] = std::make_unique<EquilibriumSystem>(models[j], start_luffing);
        // Extrapolated from the two previous points of the row; on the way back from the spine
        // column those are the spine and its neighbour on the other side. (A copy of the
        // neighbour would leave a paid-out hoist rope slack, without stiffness: Newton fails.)
        const int back1 = j - direction, back2 = j - 2 * direction;
        PointState s = back2 >= 0 && back2 < columns && row[back2]
                           ? predict(*row[back2], *row[back1], map.hoist_changes[back2], map.hoist_changes[back1],
                                     map.hoist_changes[j])
                           : *row[back1];
        const PointOutcome outcome = solvePoint(*mine[j], geometry, s, map.boom_angles_deg[i] * kDegree, jacobian, spec);
        record(i, j, s, outcome);
        if (!outcome.converged) break;
        row[j] = s;
      }
    }
    factorisations += jacobian.factorisations;
    say(fmt::format("boom angle {:g}°: row done ({}/{})", map.boom_angles_deg[i], ++rows_done, rows));
  });
  map.jacobians = factorisations;
  map.sweep_time_s = std::chrono::duration<double>(Clock::now() - t1).count();
  return map;
}

}  // namespace cranesim
