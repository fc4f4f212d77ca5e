// Load charts by radius over three boom lengths (configs/study_load_chart_by_radius.yaml): each
// chart point's scene, drawn at the boom angle the tool finds, holds the hook at its radius; and
// at one radius per boom length the capacity — the load at which the limiting criterion, the sub
// cable's F_min / Z_p, is reached — agrees with a hand estimate by moments about the boom foot,
// and the study that bisects each case's load to its capacity (study_capacity_by_radius.yaml)
// finds it too.

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <set>
#include <string>

#include <fmt/format.h>

#include "cranesim/crane/crane_figures.hpp"
#include "cranesim/crane/stated_equilibrium_search.hpp"
#include "cranesim/solvers/scene_equilibrium.hpp"
#include "cranesim/study/capacity_search.hpp"
#include "cranesim/study/case_runner.hpp"
#include "cranesim/study/study.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

constexpr double kRopeLimit = 2.907e6;         // N: each rope's F_min / Z_p (study_load_chart.yaml)
constexpr double kRingLimit = 9.15e7;          // N·m: the slewing ring's rated moment
constexpr double kRopeMassPerMetre = 7800.0 * std::numbers::pi * 0.05 * 0.05;  // kg/m: ropes and ties alike
constexpr double kSceneGravity = 9.8;               // the scenes' gravity

/// A configured crane with its load of `mass` and its hook stated `radius` m from the slewing
/// axis, drawn at the boom angle the tool finds, in equilibrium.
struct LoadedCrane {
  LoadedCrane(const std::string& file, double radius, double mass)
      : scene(sceneAtStatedEquilibrium(parseScene(fmt::format(R"(
base: {}
modify:
  booms.boom.angle_deg: from_equilibrium
  booms.boom.equilibrium: {{hook_radius: {:.17g}}}
  bodies.load.mass: {:.17g}
)", file, radius, mass), test::configPath("capacity.yaml")), true)),
        model(compileModel(scene)),
        eq(solveEquilibrium(scene, model, 0.0)) {
    REQUIRE(eq.converged);
  }
  Vec3 joint(const std::string& name) const { return model.jointFrame(eq.q.data(), model.findJoint(name)).r; }
  ConstraintLoad load(const char* constraint) const {
    return constraintLoad(model.constraints[static_cast<std::size_t>(model.findConstraint(constraint))], eq.lambda.data());
  }
  /// Σ uᵀ M u over the elements on the member's own nodes, u a unit translation along z: its mass.
  double memberMass(const std::string& member) const {
    VecX u = VecX::Zero(model.nv);
    for (const Node& n : model.nodes)
      if (n.member == member) u(n.v + 2) = 1.0;
    const VecX zero = VecX::Zero(model.nv);
    const ElementInput in{eq.q.data(), zero.data(), zero.data(), 0.0, model.gravity};
    double mass = 0.0;
    for (const auto& e : model.elements) {
      const int size = e->size();
      VecX local(size);
      for (int k = 0; k < size; ++k) local(k) = u(e->velocityIndices()[k]);
      if (local.isZero()) continue;
      MatX M(size, size);
      e->mass(in, M.data());
      mass += local.dot(M * local);
    }
    return mass;
  }
  Scene scene;
  Model model;
  StaticResult eq;
};

/// The y component of the moment about the foot pin O of a force `force` at `at` (x–z plane).
double moment(const Vec3& at, const Vec3& O, const Vec3& force) { return (at - O).cross(force).y(); }

/// The load at which a straight increasing `f` of the load crosses `level`, by the secant.
template <class F> double crossing(const F& f, double level, double m0, double m1, double tolerance) {
  double f0 = f(m0) - level, f1 = f(m1) - level;
  for (int k = 0; k < 20 && std::abs(m1 - m0) > tolerance; ++k) {
    const double m2 = m1 - f1 * (m1 - m0) / (f1 - f0);
    m0 = m1, f0 = f1, m1 = m2, f1 = f(m1) - level;
  }
  return m1;
}

}  // namespace

TEST_CASE("Capacity at a stated radius per boom length against moments about the boom foot", "[crane][load_chart]") {
  struct Configuration {
    const char* scene;
    int ties;
    double hanging_length;  // m: the hoist rope's unstretched length
  };
  const auto [file, ties, hanging_length] = GENERATE(Configuration{"crane_configured_short.yaml", 1, 39.8342},
                                                     Configuration{"crane_configured.yaml", 2, 54.8342},
                                                     Configuration{"crane_configured_long.yaml", 2, 69.8342});
  const double radius = 25.0;
  const std::string scene = file;  // lambdas capture copies, not structured bindings
  const int tie_count = ties;
  const double hanging = hanging_length;
  INFO(scene << " at " << radius << " m");

  // The capacity: the load at which the sub cable's tension at its anchor reaches its limit, to
  // 1 kg (a secant on the load, each step the boom angle found for the radius and its equilibrium).
  const auto sub_cable = [&](double mass) { return LoadedCrane(scene, radius, mass).load("sub_cable_anchor").force; };
  const double capacity = crossing(sub_cable, kRopeLimit, 50000.0, 100000.0, 1.0);
  const LoadedCrane at(scene, radius, capacity);
  CHECK(at.load("sub_cable_anchor").force == Approx(kRopeLimit).epsilon(1e-5));
  // … and the sub cable is what limits it: the other criteria hold there.
  CHECK(at.load("hoist_rope_start").force < kRopeLimit);
  CHECK(at.load("luffing_rope_start").force < kRopeLimit);
  CHECK(at.load("slewing").other < kRingLimit);

  // By hand, in the equilibrium's geometry (x–z plane), moments about the foot pin O that both
  // booms turn about. The main boom: the load and the hanging hoist rope at the sheave, each
  // section's weight at its midpoint, and the luffing line at the head's tie joint H — its
  // tension along H→D plus the share of the line's weight (ties and rope, each at its midpoint)
  // that H carries, as a beam from H to the derrick's top D would. The derrick: that line's pull
  // at D, its sections' weights and the sub cable, straight from D to its anchor A, half its
  // weight at each end. The sections' masses are their mass matrices' (uᵀ M u); the rest by hand.
  const Vec3 O = at.joint("pedestal.boom_foot"), H = at.joint("head.tie"), D = at.joint("derrick3.end");
  const Vec3 A = at.joint("pedestal.sub_cable_anchor"), sheave = at.joint("head.sheave");
  const Vec3 down = -Vec3::UnitZ();
  const auto weightMoment = [&](const std::string& boom) {  // its truss sections' weights about O
    double sum = 0.0;
    for (const MemberSpec& m : at.scene.members)
      if (m.type == MemberType::Truss && m.name.rfind(boom, 0) == 0)
        sum += moment(0.5 * (at.joint(m.name + ".start") + at.joint(m.name + ".end")), O, at.memberMass(m.name) * kSceneGravity * down);
    return sum;
  };
  const double boom_weight = weightMoment("boom"), derrick_weight = weightMoment("derrick");
  double line_weight = 0.0, weight_at_H = 0.0;  // N
  std::vector<std::string> line;
  for (int k = 1; k <= tie_count; ++k) line.push_back(fmt::format("tie{}", k));
  line.push_back("luffing_rope");
  for (const std::string& part : line) {
    const Vec3 a = at.joint(part + ".start"), b = at.joint(part + ".end");
    const double w = kRopeMassPerMetre * (b - a).norm() * kSceneGravity;
    line_weight += w;
    weight_at_H += w * (0.5 * (a + b) - D).x() / (H - D).x();
  }
  const Vec3 along_line = (D - H).normalized(), towards_anchor = (A - D).normalized();
  const double sub_cable_weight = kRopeMassPerMetre * (A - D).norm() * kSceneGravity;
  const double hoist_rope_mass = kRopeMassPerMetre * hanging;
  const auto hand_sub_cable = [&](double mass) {
    const double loads = moment(sheave, O, (mass + hoist_rope_mass) * kSceneGravity * down) + boom_weight +
                         moment(H, O, weight_at_H * down);
    const double line_tension = -loads / moment(H, O, along_line);
    const Vec3 pull_at_D = -line_tension * along_line + (line_weight - weight_at_H) * down;
    const double sub_tension = -(moment(D, O, pull_at_D) + derrick_weight + moment(D, O, 0.5 * sub_cable_weight * down)) /
                               moment(D, O, towards_anchor);
    return (-sub_tension * towards_anchor + 0.5 * sub_cable_weight * down).norm();  // at the anchor
  };
  const double hand_capacity = crossing(hand_sub_cable, kRopeLimit, 50000.0, 100000.0, 1e-3);
  UNSCOPED_INFO(file << ": capacity at " << radius << " m " << capacity << " kg, by hand " << hand_capacity << " kg");
  CHECK(capacity == Approx(hand_capacity).epsilon(0.005));  // the issue asks 2 %

  // The study's bisection (configs/study_capacity_by_radius.yaml) brackets the same capacity to
  // its 0.1 t from below and names the sub cable; the boom angle it reports there holds the hook
  // at the radius again. The load chart's grid (study_load_chart_by_radius.yaml) agrees: its
  // heaviest grid load below the capacity is admissible, the next one is not.
  const auto caseAt = [&](const Study& study, double mass) {
    for (long i = 0; i < study.cases; ++i) {
      const std::vector<double> values = study.parameterValues(i);
      if (std::filesystem::path(study.scene_paths[static_cast<std::size_t>(values[0])]).filename() == scene &&
          values[1] == radius && (values.size() < 3 || values[2] == mass))
        return i;
    }
    FAIL("no case at " << radius << " m, " << mass << " kg");
    return 0L;
  };
  const Study bisected = readStudy(std::string(CRANESIM_SOURCE_DIR) + "/configs/study_capacity_by_radius.yaml");
  const CaseRow row = runCase(bisected, caseAt(bisected, 0.0), {});
  REQUIRE(row.status == kCaseComplete);
  UNSCOPED_INFO(file << ": bisected " << row.capacity << " … " << row.inadmissible_load << " kg in " << row.wall_time_s << " s");
  CHECK(row.capacity <= capacity + 1.0);  // the secant's 1 kg
  CHECK(row.inadmissible_load >= capacity - 1.0);
  CHECK(row.inadmissible_load - row.capacity <= bisected.capacity->tolerance);
  CHECK(row.limited_by == "sub_cable");
  const auto figure = [&](const Study& study, const char* name) {
    const auto f = std::find_if(study.figures.begin(), study.figures.end(), [&](const FigureSpec& s) { return s.name == name; });
    REQUIRE(f != study.figures.end());
    return static_cast<std::size_t>(f - study.figures.begin());
  };
  CHECK(row.figures[figure(bisected, "radius")] == Approx(radius).margin(kStatedRadiusTolerance));
  CHECK(row.figures[figure(bisected, "sub_cable")] <= kRopeLimit);
  const Scene by_angle = sceneAtStatedEquilibrium(parseScene(fmt::format(R"(
base: {}
modify:
  booms.boom.angle_deg: from_equilibrium
  booms.boom.equilibrium: {{boom_angle_deg: {:.17g}}}
  bodies.load.mass: {:.17g}
)", scene, row.figures[figure(bisected, "boom_angle")], row.capacity), test::configPath("by_angle.yaml")), true);
  const Model by_angle_model = compileModel(by_angle);
  const StaticResult by_angle_eq = solveEquilibrium(by_angle, by_angle_model, 0.0);
  REQUIRE(by_angle_eq.converged);
  CHECK(craneFigures(by_angle, by_angle_model, by_angle_eq.q.data(), by_angle_eq.t).boom->hook_radius ==
        Approx(radius).margin(0.01));

  const Study grid = readStudy(std::string(CRANESIM_SOURCE_DIR) + "/configs/study_load_chart_by_radius.yaml");
  const std::vector<double>& loads = grid.parameters.back().scales_with ? grid.parameters[grid.parameters.size() - 2].values
                                                                        : grid.parameters.back().values;
  const auto above = std::upper_bound(loads.begin(), loads.end(), row.capacity);
  REQUIRE(above != loads.begin());
  REQUIRE(above != loads.end());
  CHECK(admissible(grid, runCase(grid, caseAt(grid, *(above - 1)), {})));
  CHECK_FALSE(admissible(grid, runCase(grid, caseAt(grid, *above), {})));
}

TEST_CASE("Each chart point of the shipped study: its radius, and reproduced from its boom angle", "[crane][load_chart][study]") {
  // configs/study_load_chart_by_radius.yaml: its three scenes × six radii at 100 t, computed as
  // the study computes them, hold the hook at the stated radius to 1 cm; the boom angle the case
  // reports (its control: what the angle indicator reads), stated as the equilibrium's boom angle
  // of the same crane, holds it there again.
  const Study study = readStudy(std::string(CRANESIM_SOURCE_DIR) + "/configs/study_load_chart_by_radius.yaml");
  REQUIRE(study.parameters.front().path == kSceneParameter);
  REQUIRE(study.scene_paths.size() == 3);
  const auto figure = [&](const char* name) {
    const auto f = std::find_if(study.figures.begin(), study.figures.end(), [&](const FigureSpec& s) { return s.name == name; });
    REQUIRE(f != study.figures.end());
    return static_cast<std::size_t>(f - study.figures.begin());
  };
  const std::size_t radius_figure = figure("radius"), angle_figure = figure("boom_angle");
  std::set<std::pair<double, double>> checked;  // (scene, radius)
  for (long i = 0; i < study.cases; ++i) {
    const std::vector<double> values = study.parameterValues(i);
    const double scene = values[0], radius = values[1], mass = values[2];
    if (mass != 100000.0) continue;
    const std::string& path = study.scene_paths[static_cast<std::size_t>(scene)];
    INFO("case " << i << ": " << path << ", " << radius << " m, " << mass << " kg");
    const CaseRow row = runCase(study, i, {});
    REQUIRE(row.status == kCaseComplete);
    CHECK(row.figures[radius_figure] == Approx(radius).margin(0.01));
    const Scene by_angle = sceneAtStatedEquilibrium(parseScene(fmt::format(R"(
base: {}
modify:
  booms.boom.angle_deg: from_equilibrium
  booms.boom.equilibrium: {{boom_angle_deg: {:.17g}}}
  bodies.load.mass: {:.17g}
)", path, row.figures[angle_figure], mass), test::configPath("by_angle.yaml")), true);
    const Model model = compileModel(by_angle);
    const StaticResult eq = solveEquilibrium(by_angle, model, 0.0);
    REQUIRE(eq.converged);
    CHECK(craneFigures(by_angle, model, eq.q.data(), eq.t).boom->hook_radius == Approx(radius).margin(0.01));
    checked.insert({scene, radius});
  }
  CHECK(checked.size() == 3 * 6);
}
