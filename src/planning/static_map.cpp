#include "cranesim/planning/static_map.hpp"

#include <fmt/format.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
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

#include "cranesim/io/command_line.hpp"
#include "cranesim/model/compile.hpp"
#include "cranesim/parallel/byte_stream.hpp"
#include "cranesim/parallel/task_farm.hpp"
#ifdef CRANESIM_WITH_MPI
#include "cranesim/parallel/mpi_farm.hpp"
#endif
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
  if (m.length) return (*m.length)(scene.solver.t_start);
  return m.reeving ? m.reeving->drawn_length : (m.end - m.start).norm();
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

namespace {

/// One sweep of the grid: the models (one per hoist change), the spine column (boom angles
/// outwards from the scene's equilibrium) and the rows of hoist changes at each boom angle, each
/// row a task of the farm (parallel/task_farm.hpp) that starts from its spine point alone, so a
/// row is the same whichever thread or rank computes it.
class StaticMapSweep {
 public:
  StaticMapSweep(const Scene& scene, const CraneControls& controls, const StaticMapSpec& spec)
      : scene_(scene), controls_(controls), spec_(spec) {
    map_.boom_angles_deg = spec.boom_angles_deg;
    map_.hoist_changes = spec.hoist_changes;
    for (Eigen::MatrixXd* m : {&map_.luffing_length, &map_.hoist_rope_length, &map_.end_x, &map_.end_y, &map_.end_z})
      m->setConstant(rows(), columns(), std::numeric_limits<double>::quiet_NaN());
    map_.iterations.setZero(rows(), columns());
    map_.equilibria.resize(static_cast<std::size_t>(rows()) * columns());
    failures_.resize(static_cast<std::size_t>(rows()) * columns());

    start_luffing_ = ropeLengthAtStart(scene, controls.luffing_rope);
    const double scene_hoist = ropeLengthAtStart(scene, controls.hoist_rope);
    map_.hoist_length = spec.hoist_length > 0.0 ? spec.hoist_length : scene_hoist;
    for (int j = 1; j < columns(); ++j)  // the hoist change closest to the scene's own hoist rope
      if (std::abs(map_.hoist_length - map_.hoist_changes[j] - scene_hoist) <
          std::abs(map_.hoist_length - map_.hoist_changes[spine_column_] - scene_hoist))
        spine_column_ = j;
    for (double change : spec.hoist_changes) {
      if (!(map_.hoist_length - change > 0.0))
        throw std::invalid_argument(fmt::format("hoist change {} m exceeds the hoist rope's length {} m", change, map_.hoist_length));
      models_.push_back(mapModel(scene, controls, map_.hoist_length - change, start_luffing_));
    }
    geometry_.emplace(models_[0], controls);  // joints sit alike in every map model
    spine_.resize(rows());
  }

  int rows() const { return static_cast<int>(map_.boom_angles_deg.size()); }
  int columns() const { return static_cast<int>(map_.hoist_changes.size()); }
  StaticMap& map() { return map_; }

  /// The scene's equilibrium with its hoist rope at the spine column's length (a hoist rope paid
  /// out from a solved state would start slack), then the boom angles outwards from it.
  void solveSpine(const std::function<void(const std::string&)>& say) {
    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    const Scene start_scene =
        withControls(scene_, controls_, Profile(ConstantProfile{start_luffing_}),
                     Profile(ConstantProfile{map_.hoist_length - map_.hoist_changes[spine_column_]}));
    const Model start_model = compileModel(start_scene);
    const StaticResult start = solveEquilibrium(start_scene, start_model, start_scene.solver.t_start);
    map_.start_iterations = start.iterations;
    map_.start_time_s = std::chrono::duration<double>(Clock::now() - t0).count();
    if (!start.converged) throw std::runtime_error("the scene's equilibrium, where the map starts: " + start.message);
    say(fmt::format("scene equilibrium: {} Newton iterations, {:.1f} s", start.iterations, map_.start_time_s));

    const auto t1 = Clock::now();
    EquilibriumSystem system(models_[spine_column_], start_luffing_);
    PointState origin;
    origin.x.resize(system.size());
    origin.x << start.q, start.lambda;
    origin.luffing_length = start_luffing_;
    const double start_angle = geometry_->boomAngle(origin.x);
    int nearest = 0;
    for (int i = 1; i < rows(); ++i)
      if (std::abs(angle(i) - start_angle) < std::abs(angle(nearest) - start_angle)) nearest = i;
    ChordJacobian jacobian;
    for (int direction : {-1, +1}) {
      jacobian.valid = false;
      for (int i = direction < 0 ? nearest : nearest + 1; i >= 0 && i < rows(); i += direction) {
        const int back1 = i - direction, back2 = i - 2 * direction;
        const auto solved = [&](int k) { return k >= 0 && k < rows() && spine_[k]; };
        PointState s;
        PointOutcome outcome;
        if (solved(back1) && solved(back2)) {
          s = predict(*spine_[back2], *spine_[back1], map_.boom_angles_deg[back2], map_.boom_angles_deg[back1],
                      map_.boom_angles_deg[i]);
          outcome = solvePoint(system, *geometry_, s, angle(i), jacobian, spec_);
        }
        if (!outcome.converged) {  // no extrapolation, or it failed: from the neighbour, in halved steps if need be
          const int spent = outcome.iterations;
          s = solved(back1) ? *spine_[back1] : origin;
          if (spent > 0) jacobian.valid = false;
          outcome = solveAngleStep(system, *geometry_, s, solved(back1) ? angle(back1) : start_angle, angle(i),
                                   jacobian, spec_);
          outcome.iterations += spent;
        }
        record(i, spine_column_, s, outcome);
        if (!outcome.converged) break;  // the angles beyond would start from a failed point
        spine_[i] = s;
      }
    }
    map_.jacobians += jacobian.factorisations;
    say(fmt::format("hoist change {:g} m: {} boom angles, {:.1f} s", map_.hoist_changes[spine_column_],
                    std::count_if(spine_.begin(), spine_.end(), [](const auto& p) { return p.has_value(); }),
                    std::chrono::duration<double>(Clock::now() - t1).count()));
  }

  /// The spine's points, for the other ranks.
  std::string encodeSpine() const {
    ByteWriter out;
    encodePoints(out, spine_);
    return out.take();
  }
  void decodeSpine(const std::string& bytes) {
    ByteReader in(bytes);
    decodePoints(in, spine_);
  }

  /// The rows whose spine point was found: the farm's tasks.
  std::vector<long> rowTasks() const {
    std::vector<long> tasks;
    for (int i = 0; i < rows(); ++i)
      if (spine_[i]) tasks.push_back(i);
    return tasks;
  }

  /// Row i: hoist changes from the spine column towards both ends of the row, as bytes
  /// (recordRow reads them). `systems` holds the calling worker's equilibrium system per column.
  std::string computeRow(int i, std::vector<std::unique_ptr<EquilibriumSystem>>& systems) const {
    if (systems.empty()) systems.resize(columns());
    ChordJacobian jacobian;
    std::vector<std::optional<PointState>> row(columns());
    std::vector<PointOutcome> outcomes(columns());
    row[spine_column_] = *spine_[i];
    for (int direction : {+1, -1}) {
      jacobian.valid = false;
      for (int j = spine_column_ + direction; j >= 0 && j < columns(); j += direction) {
        if (!systems[j]) systems[j] = std::make_unique<EquilibriumSystem>(models_[j], start_luffing_);
        // Extrapolated from the two previous points of the row; on the way back from the spine
        // column those are the spine and its neighbour on the other side. (A copy of the
        // neighbour would leave a paid-out hoist rope slack, without stiffness: Newton fails.)
        const int back1 = j - direction, back2 = j - 2 * direction;
        PointState s = back2 >= 0 && back2 < columns() && row[back2]
                           ? predict(*row[back2], *row[back1], map_.hoist_changes[back2], map_.hoist_changes[back1],
                                     map_.hoist_changes[j])
                           : *row[back1];
        outcomes[j] = solvePoint(*systems[j], *geometry_, s, angle(i), jacobian, spec_);
        if (!outcomes[j].converged) break;
        row[j] = s;
      }
    }
    row[spine_column_].reset();  // the spine's point is recorded already
    ByteWriter out;
    out.put(i);
    out.put(jacobian.factorisations);
    for (const PointOutcome& outcome : outcomes) {
      out.put(outcome.iterations);
      out.put(outcome.why);
    }
    encodePoints(out, row);
    return out.take();
  }

  /// Records a row computeRow wrote; returns its boom angle's index.
  int recordRow(const std::string& bytes) {
    ByteReader in(bytes);
    const int i = in.get<int>();
    if (i < 0 || i >= rows()) throw std::runtime_error("corrupt static map row");
    map_.jacobians += in.get<int>();
    std::vector<PointOutcome> outcomes(columns());
    for (PointOutcome& outcome : outcomes) {
      outcome.iterations = in.get<int>();
      outcome.why = in.getString();
    }
    std::vector<std::optional<PointState>> row(columns());
    decodePoints(in, row);
    for (int j = 0; j < columns(); ++j) {
      if (j == spine_column_ || (outcomes[j].iterations == 0 && !row[j])) continue;  // the spine's, or not tried
      outcomes[j].converged = row[j].has_value();
      record(i, j, row[j] ? *row[j] : PointState{}, outcomes[j]);
    }
    return i;
  }

  /// The failed points' lines, in the grid's order.
  void collectFailures() {
    for (std::string& failure : failures_)
      if (!failure.empty()) map_.failures.push_back(std::move(failure));
  }

 private:
  double angle(int i) const { return map_.boom_angles_deg[i] * kDegree; }

  void record(int i, int j, const PointState& s, const PointOutcome& outcome) {
    const std::size_t k = static_cast<std::size_t>(i) * columns() + j;
    map_.iterations(i, j) = outcome.iterations;
    if (!outcome.converged) {
      failures_[k] = fmt::format("boom angle {:g}°, hoist change {:g} m: {}", map_.boom_angles_deg[i],
                                 map_.hoist_changes[j], outcome.why);
      return;
    }
    const Vec3 end = geometry_->endPoint(s.x);
    map_.luffing_length(i, j) = s.luffing_length;
    map_.hoist_rope_length(i, j) = map_.hoist_length - map_.hoist_changes[j];
    map_.end_x(i, j) = end.x();
    map_.end_y(i, j) = end.y();
    map_.end_z(i, j) = end.z();
    map_.equilibria[k] = s.x;
  }

  static void encodePoints(ByteWriter& out, const std::vector<std::optional<PointState>>& points) {
    for (const std::optional<PointState>& p : points) {
      out.put(p.has_value());
      if (!p) continue;
      out.put(p->luffing_length);
      out.putArray(p->x.data(), p->x.size());
    }
  }
  static void decodePoints(ByteReader& in, std::vector<std::optional<PointState>>& points) {
    for (std::optional<PointState>& p : points) {
      p.reset();
      if (!in.get<bool>()) continue;
      p.emplace();
      p->luffing_length = in.get<double>();
      p->x.resize(in.getLength());
      in.getArrayValues(p->x.data(), p->x.size());
    }
  }

  const Scene& scene_;
  const CraneControls& controls_;
  const StaticMapSpec& spec_;
  StaticMap map_;
  std::vector<std::string> failures_;  // per point, row-major; empty where none
  double start_luffing_ = 0.0;
  int spine_column_ = 0;
  std::vector<Model> models_;
  std::optional<CraneGeometry> geometry_;
  std::vector<std::optional<PointState>> spine_;
};

}  // namespace

StaticMap computeStaticMap(const Scene& scene, const CraneControls& controls, const StaticMapSpec& spec,
                           const std::function<void(const std::string&)>& log, const MpiSession* ranks) {
  using Clock = std::chrono::steady_clock;
  const auto say = [&](const std::string& line) {
    if (log) log(line);
  };
  // Under MPI every rank is a core's worth of work: rank 0 computes on one thread unless told more.
  const int threads = spec.threads > 0 ? spec.threads : ranks ? 1 : tbb::info::default_concurrency();
  const tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, threads);

  const auto t0 = Clock::now();
  StaticMapSweep sweep(scene, controls, spec);
  std::string spine;
  try {
    sweep.solveSpine(say);
    spine = sweep.encodeSpine();
  } catch (...) {
#ifdef CRANESIM_WITH_MPI
    if (ranks) ranks->broadcast(spine);  // empty: the other ranks stop
#endif
    throw;
  }
#ifdef CRANESIM_WITH_MPI
  if (ranks) ranks->broadcast(spine);
#endif

  const auto t1 = Clock::now();
  StaticMap& map = sweep.map();
  map.threads = threads;
  map.execution = fmt::format("{} thread{}", threads, threads == 1 ? "" : "s");
  const std::vector<long> tasks = sweep.rowTasks();
  std::mutex record_mutex;
  int rows_done = 0;
  const auto record = [&](const std::string& bytes, const std::string& worker) {
    std::lock_guard lock(record_mutex);
    const int i = sweep.recordRow(bytes);
    say(fmt::format("boom angle {:g}°: row done ({}/{}, {})", map.boom_angles_deg[i], ++rows_done, tasks.size(), worker));
  };
  {
    // One row per core: the rows are the parallelism, each row's element loops run serially.
    const tbb::global_control one_thread_per_row(tbb::global_control::max_allowed_parallelism, 1);
    tbb::enumerable_thread_specific<std::vector<std::unique_ptr<EquilibriumSystem>>> systems;
    TaskQueue queue(tasks);
    std::exception_ptr error;  // the first exception of a worker thread, rethrown here
    LocalWorkers local(queue, threads, [&](long i, const std::string& worker) {
      try {
        record(sweep.computeRow(static_cast<int>(i), systems.local()), worker);
      } catch (...) {
        std::lock_guard lock(record_mutex);
        if (!error) error = std::current_exception();
        queue.abandon();
      }
    }, ranks ? "rank 0 " : "");
#ifdef CRANESIM_WITH_MPI
    if (ranks) {
      map.execution = fmt::format("{} MPI ranks ({} on rank 0, one on each other rank)", ranks->size(), map.execution);
      serveTasksToRanks(*ranks, queue, [&](std::string bytes, int rank) { record(bytes, fmt::format("rank {}", rank)); });
    }
#endif
    local.join();
    if (error) std::rethrow_exception(error);
  }
  sweep.collectFailures();
  map.sweep_time_s = std::chrono::duration<double>(Clock::now() - t1).count();
  map.time_s = std::chrono::duration<double>(Clock::now() - t0).count();
  return std::move(map);
}

#ifdef CRANESIM_WITH_MPI
void computeStaticMapRowsForRank0(const Scene& scene, const CraneControls& controls, const StaticMapSpec& spec,
                                  const MpiSession& ranks) {
  const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  StaticMapSweep sweep(scene, controls, spec);
  std::string spine;
  ranks.broadcast(spine);
  if (spine.empty()) return;  // rank 0 could not start the map
  sweep.decodeSpine(spine);
  std::vector<std::unique_ptr<EquilibriumSystem>> systems;
  computeTasksForRank0(ranks, [&](long i, const std::string& worker) {
    try {
      return sweep.computeRow(static_cast<int>(i), systems);
    } catch (const std::exception& e) {  // rank 0 would wait for this row forever: end the job
      fmt::print(stderr, "error: static map, {}, boom angle {:g}°: {}\n", worker, spec.boom_angles_deg[i], e.what());
      ranks.abort(kExitSolverFailure);
    }
  });
}
#endif

}  // namespace cranesim
