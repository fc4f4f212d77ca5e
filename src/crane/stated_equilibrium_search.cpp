#include "cranesim/crane/stated_equilibrium_search.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "cranesim/crane/crane_figures.hpp"
#include "cranesim/model/compile.hpp"
#include "cranesim/solvers/scene_equilibrium.hpp"

namespace cranesim {
namespace {

constexpr double kLowestAngle = 0.0, kSteepestAngle = 89.5;  // deg: the search's range
constexpr int kMaxEquilibria = 20;

/// The stated figure in the equilibrium of `scene` (drawn at some boom angle).
double equilibriumFigure(const Scene& scene, StatedEquilibrium::Figure figure) {
  const Model model = compileModel(scene);
  locateCrane(scene, model);
  const Assembler assembler(model);
  const StaticResult eq = sceneEquilibrium(scene, model, assembler, true);
  const BoomFigures boom = *craneFigures(scene, model, eq.q.data(), eq.t).boom;
  return figure == StatedEquilibrium::Figure::HookRadius ? boom.hook_radius : boom.boom_angle_deg;
}

}  // namespace

StatedEquilibriumSearch searchStatedEquilibrium(const Scene& scene) {
  const StatedEquilibrium& stated = *scene.stated_equilibrium;
  const bool radius = stated.figure == StatedEquilibrium::Figure::HookRadius;
  const double tolerance = radius ? kStatedRadiusTolerance : kStatedBoomAngleTolerance;
  StatedEquilibriumSearch search;
  const auto miss = [&](double angle) {
    ++search.equilibria;
    return equilibriumFigure(stated.drawn_at(angle), stated.figure) - stated.value;
  };
  // The first step: the stretch lowers the boom by about as much at a nearby angle, so a stated
  // angle is met by drawing the boom higher by the miss; a radius too long by a degree's step.
  double a0 = stated.drawn_angle_deg, e0 = miss(a0);
  double a1 = radius ? a0 + std::copysign(0.5, e0) : a0 - e0, e1 = 0.0;
  double lowest_figure = e0, highest_figure = e0;
  while (std::abs(e0) > tolerance) {
    if (search.equilibria >= kMaxEquilibria || !(a1 > kLowestAngle && a1 < kSteepestAngle))
      throw SceneError(stated.where,
                       fmt::format("no boom angle in ({:g}°, {:g}°) meets the stated {} of {:g} {} in equilibrium: the "
                                   "equilibria tried reach {:.6g} … {:.6g} {}",
                                   kLowestAngle, kSteepestAngle, radius ? "hook radius" : "boom angle", stated.value,
                                   radius ? "m" : "°", stated.value + lowest_figure, stated.value + highest_figure,
                                   radius ? "m" : "°"));
    e1 = miss(a1);
    lowest_figure = std::min(lowest_figure, e1), highest_figure = std::max(highest_figure, e1);
    const double a2 = e1 == e0 ? a1 : a1 - e1 * (a1 - a0) / (e1 - e0);
    a0 = a1, e0 = e1, a1 = a2;
  }
  search.angle_deg = a0;
  search.figure = stated.value + e0;
  return search;
}

Scene sceneAtStatedEquilibrium(const Scene& scene, bool quiet) {
  if (!scene.stated_equilibrium) return scene;
  const StatedEquilibrium& stated = *scene.stated_equilibrium;
  const StatedEquilibriumSearch search = searchStatedEquilibrium(scene);
  if (!quiet)
    fmt::print(stderr, "boom '{}' drawn at {:.6f}°: its equilibrium {} {:.6g} {} (stated {:g}; {} equilibria)\n",
               stated.boom, search.angle_deg,
               stated.figure == StatedEquilibrium::Figure::HookRadius ? "holds the hook at a radius of" : "stands the boom at",
               search.figure, stated.figure == StatedEquilibrium::Figure::HookRadius ? "m" : "°", stated.value,
               search.equilibria);
  return stated.drawn_at(search.angle_deg);
}

}  // namespace cranesim
