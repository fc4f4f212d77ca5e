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
constexpr double kShortestHanging = 0.1;                      // m: as the boom's drawing
constexpr int kMaxEquilibria = 20;

/// The equilibrium's figures less the stated ones (0 where none is stated).
struct Miss {
  double figure = 0.0;  // m or deg: the angle's figure
  double height = 0.0;  // m: the hook's height
};

Miss equilibriumMiss(const StatedEquilibrium& stated, const BoomDrawing& drawing) {
  const Scene scene = stated.drawn_at(drawing);
  const Model model = compileModel(scene);
  locateCrane(scene, model);
  const Assembler assembler(model);
  const StaticResult eq = sceneEquilibrium(scene, model, assembler, true);
  const BoomFigures boom = *craneFigures(scene, model, eq.q.data(), eq.t).boom;
  Miss miss;
  if (stated.angle_figure)
    miss.figure = (stated.figure == StatedEquilibrium::Figure::HookRadius ? boom.hook_radius : boom.boom_angle_deg) -
                  stated.angle_figure->value;
  if (stated.hook_height) miss.height = boom.hook_height - stated.hook_height->value;
  return miss;
}

const char* figureName(StatedEquilibrium::Figure figure) {
  return figure == StatedEquilibrium::Figure::HookRadius ? "hook radius" : "boom angle";
}
const char* figureUnit(StatedEquilibrium::Figure figure) {
  return figure == StatedEquilibrium::Figure::HookRadius ? "m" : "°";
}

}  // namespace

StatedEquilibriumSearch searchStatedEquilibrium(const Scene& scene) {
  const StatedEquilibrium& stated = *scene.stated_equilibrium;
  const bool radius = stated.figure == StatedEquilibrium::Figure::HookRadius;
  const double tolerance = radius ? kStatedRadiusTolerance : kStatedBoomAngleTolerance;
  StatedEquilibriumSearch search;
  const auto miss = [&](const BoomDrawing& drawing) {
    ++search.equilibria;
    return equilibriumMiss(stated, drawing);
  };
  // The boom angle's first step: the stretch lowers the boom by about as much at a nearby angle,
  // so a stated angle is met by drawing the boom higher by the miss; a radius too long by a
  // degree's step. Then the secant; an angle already met stays.
  const auto nextAngle = [&](double previous, double previous_miss, double angle, double angle_miss) {
    if (!stated.angle_figure || std::abs(angle_miss) <= tolerance) return angle;
    if (angle == previous || angle_miss == previous_miss)
      return radius ? angle + std::copysign(0.5, angle_miss) : angle - angle_miss;
    return angle - angle_miss * (angle - previous) / (angle_miss - previous_miss);
  };
  BoomDrawing drawing = stated.drawn;
  Miss m = miss(drawing);
  double previous = drawing.angle_deg, previous_miss = m.figure;
  double lowest_figure = m.figure, highest_figure = m.figure;
  while (std::abs(m.figure) > tolerance || std::abs(m.height) > kStatedHookHeightTolerance) {
    BoomDrawing next{nextAngle(previous, previous_miss, drawing.angle_deg, m.figure), drawing.hanging_length + m.height};
    if (stated.angle_figure && (search.equilibria >= kMaxEquilibria || !(next.angle_deg > kLowestAngle && next.angle_deg < kSteepestAngle)))
      throw SceneError(stated.angle_figure->where,
                       fmt::format("no boom angle in ({:g}°, {:g}°) meets the stated {} of {:g} {} in equilibrium: the "
                                   "equilibria tried reach {:.6g} … {:.6g} {}",
                                   kLowestAngle, kSteepestAngle, figureName(stated.figure), stated.angle_figure->value,
                                   figureUnit(stated.figure), stated.angle_figure->value + lowest_figure,
                                   stated.angle_figure->value + highest_figure, figureUnit(stated.figure)));
    if (stated.hook_height && (search.equilibria >= kMaxEquilibria || next.hanging_length < kShortestHanging))
      throw SceneError(stated.hook_height->where,
                       fmt::format("no hoist rope holds the hook at a height of {:g} m in equilibrium: with {:.6g} m of "
                                   "rope it hangs at {:.6g} m, and the rope is at least {:g} m",
                                   stated.hook_height->value, drawing.hanging_length, stated.hook_height->value + m.height,
                                   kShortestHanging));
    previous = drawing.angle_deg, previous_miss = m.figure;
    drawing = next;
    m = miss(drawing);
    lowest_figure = std::min(lowest_figure, m.figure), highest_figure = std::max(highest_figure, m.figure);
  }
  search.drawing = drawing;
  if (stated.angle_figure) search.figure = stated.angle_figure->value + m.figure;
  if (stated.hook_height) search.hook_height = stated.hook_height->value + m.height;
  return search;
}

Scene sceneAtStatedEquilibrium(const Scene& scene, bool quiet) {
  if (!scene.stated_equilibrium) return scene;
  const StatedEquilibrium& stated = *scene.stated_equilibrium;
  const StatedEquilibriumSearch search = searchStatedEquilibrium(scene);
  if (!quiet) {
    std::string drawn, holds, figures;
    if (stated.angle_figure) {
      drawn = fmt::format(" at {:.6f}°", search.drawing.angle_deg);
      holds = stated.figure == StatedEquilibrium::Figure::HookRadius
                  ? fmt::format("holds the hook at a radius of {:.6g} m", search.figure)
                  : fmt::format("stands the boom at {:.6g}°", search.figure);
      figures = fmt::format("{:g}", stated.angle_figure->value);
    }
    if (stated.hook_height) {
      drawn += fmt::format("{} its hoist rope {:.6f} m long", drawn.empty() ? " with" : ",", search.drawing.hanging_length);
      const bool radius = stated.angle_figure && stated.figure == StatedEquilibrium::Figure::HookRadius;
      holds += fmt::format("{} a height of {:.6g} m", holds.empty() ? "holds the hook at" : radius ? " and" : " and holds the hook at",
                           search.hook_height);
      figures += fmt::format("{}{:g}", figures.empty() ? "" : " and ", stated.hook_height->value);
    }
    fmt::print(stderr, "boom '{}' drawn{}: its equilibrium {} (stated {}; {} equilibria)\n", stated.boom, drawn, holds,
               figures, search.equilibria);
  }
  return stated.drawn_at(search.drawing);
}

}  // namespace cranesim
