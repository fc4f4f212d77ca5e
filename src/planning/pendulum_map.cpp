#include "cranesim/planning/pendulum_map.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <exception>
#include <mutex>
#include <numbers>
#include <stdexcept>

#include "cranesim/parallel/task_farm.hpp"
#include "cranesim/solvers/modes.hpp"

namespace cranesim {
namespace {

/// `count` indices spread evenly over 0 … size − 1, both ends included.
std::vector<int> spreadIndices(int size, int count) {
  std::vector<int> indices;
  for (int k = 0; k < count; ++k)
    indices.push_back(static_cast<int>(std::lround(static_cast<double>(k) * (size - 1) / (count - 1))));
  return indices;
}

}  // namespace

SwayPeriods swayPeriods(const Model& model, const VecX& q, double t, const CraneControls& controls, bool across) {
  const ModalResult modes = computeModes(model, q, t, 0);
  const Node& node = model.nodes[model.joints[model.findJoint(controls.end_point)].node];
  SwayPeriods periods;
  for (Eigen::Index k = 0; k < modes.frequencies.size(); ++k) {
    if (modes.rigid[k] || modes.omega_squared(k) <= 0.0) continue;
    const Eigen::Vector3d v = modes.shapes.col(k).segment<3>(node.v).cwiseAbs();
    if (v.x() > v.y() && v.x() > v.z() && periods.along == 0.0) periods.along = 1.0 / modes.frequencies(k);
    if (v.y() > v.x() && v.y() > v.z() && periods.across == 0.0) periods.across = 1.0 / modes.frequencies(k);
  }
  if (periods.along == 0.0)
    throw std::runtime_error(fmt::format("no mode of the crane sways '{}' in its plane", controls.end_point));
  if (across && periods.across == 0.0)
    throw std::runtime_error(fmt::format("no mode of the crane sways '{}' across its plane", controls.end_point));
  return periods;
}

double pendulumLength(double period, double gravity) { return gravity * std::pow(period / (2.0 * std::numbers::pi), 2); }

PendulumMap measurePendulumMap(const Scene& scene, const CraneControls& controls, const StaticMap& map, bool across,
                               double gravity, const PendulumGridSpec& spec, int threads) {
  const auto started = std::chrono::steady_clock::now();
  const std::vector<int> rows = spreadIndices(map.rows(), std::min(spec.boom_angles, map.rows()));
  const std::vector<int> columns = spreadIndices(map.columns(), std::min(spec.hoist_changes, map.columns()));
  PendulumMap pendulum;
  for (GridData* d : {&pendulum.along, &pendulum.across}) {
    for (int i : rows) d->u.push_back(map.boom_angles_deg[i]);
    for (int j : columns) d->v.push_back(map.hoist_changes[j]);
    d->values.resize(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(columns.size()));
  }

  // One task per sub-grid point: the map's model at its hoist rope (the luffing rope is the
  // model's time, as the map solved it) about the map's equilibrium.
  const long points = static_cast<long>(rows.size() * columns.size());
  std::vector<long> tasks(points);
  for (long k = 0; k < points; ++k) tasks[k] = k;
  TaskQueue queue(tasks);
  std::mutex lock;
  std::exception_ptr error;
  LocalWorkers workers(queue, std::max(1, threads), [&](long task, const std::string&) {
    const int a = static_cast<int>(task / static_cast<long>(columns.size())), b = static_cast<int>(task % static_cast<long>(columns.size()));
    const int i = rows[a], j = columns[b];
    try {
      const double luffing = map.luffing_length(i, j);
      const VecX& equilibrium = map.equilibria[static_cast<std::size_t>(i) * map.columns() + j];
      if (!std::isfinite(luffing) || equilibrium.size() == 0)
        throw std::runtime_error("the static map has no equilibrium there");
      const Model model = mapModel(scene, controls, map.hoist_length - map.hoist_changes[j], luffing);
      const SwayPeriods periods = swayPeriods(model, equilibrium.head(model.nq), luffing, controls, across);
      pendulum.along.values(a, b) = pendulumLength(periods.along, gravity);
      pendulum.across.values(a, b) = pendulumLength(across ? periods.across : periods.along, gravity);
    } catch (const std::exception& e) {
      std::lock_guard guard(lock);
      if (!error)
        error = std::make_exception_ptr(std::runtime_error(fmt::format(
            "the load's pendulum at boom angle {:.4g}°, hoist change {:.4g} m: {}", map.boom_angles_deg[i], map.hoist_changes[j], e.what())));
      queue.abandon();
    }
  });
  workers.join();
  if (error) std::rethrow_exception(error);

  const SurfaceSpec fit{SurfaceKind::Polynomial, std::min(spec.order_u, static_cast<int>(rows.size()) - 1),
                        std::min(spec.order_v, static_cast<int>(columns.size()) - 1)};
  pendulum.along_fit = FittedSurface::fit(pendulum.along, fit);
  pendulum.across_fit = FittedSurface::fit(pendulum.across, fit);
  pendulum.modal_analyses = static_cast<int>(points);
  pendulum.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return pendulum;
}

}  // namespace cranesim
