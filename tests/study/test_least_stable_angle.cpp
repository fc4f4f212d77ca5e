// A study's least stable angle (study/least_stable_angle.hpp): the golden-section search between
// the worst grid angle's neighbours on figures of known extreme, at the ends of the grid and with
// angles the analysis cannot compute; and on a carriage whose pads stand on a trapezoid, whose
// least stable direction lies between grid angles and is known by hand.
//
// The hand: a rigid carriage, its weight W_c on the slewing axis, an upper carriage W_u with its
// centroid e behind the axis, a point load at radius R. About a tipping edge at distance h from
// the axis with outward normal n, a load slewed to the direction u tips the carriage when
//   P (R n·u − h) = W_c h + W_u (h + e n·u),
// so P(n·u) = (W_c h + W_u (h + e n·u)) / (R n·u − h), whose derivative in n·u is
// −(R (W_c + W_u) h + W_u e h) / (R n·u − h)² < 0: over each edge the load tips the carriage
// most easily straight across it, u = n, and the least stable direction over a polygon of pads
// is the normal of the edge with the smallest P(1) — never a corner's diagonal, which lies
// farther from both its edges than their normals' feet do. Pads on a trapezoid whose front edge
// 4x + y = 2√17 m lies h = 2 m from the axis, its other edges 3 m, put the least stable
// direction at atan(1/4) = 14.036°, between the grid's 0° and 22.5°.

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "carriage_on_pads.hpp"
#include "cranesim/study/case_runner.hpp"
#include "cranesim/study/least_stable_angle.hpp"
#include "cranesim/study/study.hpp"

using namespace cranesim;

namespace {

/// A study of one figure searched over `grid` for its worst (worst: max or min) to `tolerance`.
Study searchStudy(std::vector<double> grid, bool worst_is_max, double tolerance) {
  Study study;
  study.figures.resize(1);
  study.figures[0].name = "figure";
  study.least_stable = LeastStableAngleSpec{"constraints.slewing.drive.value", std::move(grid), 0, worst_is_max, tolerance};
  return study;
}

/// A case whose figure is `f(angle)`, computed in one step; `evaluated` counts the calls.
AngledCase caseOf(const std::function<double(double)>& f, int& evaluated) {
  return [&f, &evaluated](double angle) {
    ++evaluated;
    CaseRow row;
    row.status = kCaseComplete;
    row.figures = {f(angle)};
    row.steps = 1.0;
    return row;
  };
}

}  // namespace

TEST_CASE("the least stable angle between grid angles, by golden-section search", "[study][least_stable]") {
  SECTION("an inner extreme: the worst grid angle's neighbours bracket it") {
    // Largest at 31.7°; on the grid 22.5° is the worst (9.2° off against 45°'s 13.3°).
    const std::function<double(double)> f = [](double a) { return std::cos((a - 31.7) * std::numbers::pi / 180.0); };
    int evaluated = 0;
    const CaseRow row = searchLeastStableAngle(searchStudy({0, 22.5, 45, 67.5, 90}, true, 0.01), caseOf(f, evaluated));
    CHECK(row.status == kCaseComplete);
    CHECK(row.worst_grid_angle == 22.5);
    CHECK(std::abs(row.least_stable_angle - 31.7) <= 0.01);
    CHECK(row.least_stable_value == f(row.least_stable_angle));
    CHECK(row.figures[0] == row.least_stable_value);
    // The grid's 5, then one a step as the bracket of 45° shrinks by about 1/φ to 0.01°: 18.
    CHECK(evaluated >= 5 + 15);
    CHECK(evaluated <= 5 + 21);
    CHECK(row.steps == evaluated);
  }
  SECTION("worst: min, the extreme at the grid's end: the end itself") {
    const std::function<double(double)> f = [](double a) { return 1.0 + a * a; };
    int evaluated = 0;
    const CaseRow row = searchLeastStableAngle(searchStudy({0, 22.5, 45}, false, 0.1), caseOf(f, evaluated));
    CHECK(row.worst_grid_angle == 0.0);
    CHECK(row.least_stable_angle == 0.0);
    CHECK(row.least_stable_value == 1.0);
  }
  SECTION("worst: min inside the last grid step") {
    const std::function<double(double)> f = [](double a) { return (a - 80.0) * (a - 80.0); };
    int evaluated = 0;
    const CaseRow row = searchLeastStableAngle(searchStudy({0, 45, 90}, false, 1e-3), caseOf(f, evaluated));
    CHECK(row.worst_grid_angle == 90.0);
    CHECK(std::abs(row.least_stable_angle - 80.0) <= 1e-3);
  }
  SECTION("a grid angle whose analysis fails is the worst: the carriage tips there") {
    const std::function<double(double)> f = [](double a) { return a; };
    int evaluated = 0;
    const AngledCase tips = [&](double angle) {
      CaseRow row = caseOf(f, evaluated)(angle);
      if (angle == 45.0) row.status = kCaseFailed, row.message = "the carriage 'carriage' has tipped", row.figures = {NAN};
      return row;
    };
    const CaseRow row = searchLeastStableAngle(searchStudy({0, 22.5, 45, 67.5, 90}, true, 0.1), tips);
    CHECK(row.status == kCaseFailed);
    CHECK(row.least_stable_angle == 45.0);
    CHECK(row.worst_grid_angle == 45.0);
    CHECK(evaluated == 5);
  }
  SECTION("a signal stops the search: the interrupted row") {
    int evaluated = 0;
    const AngledCase stopped = [&](double angle) {
      ++evaluated;
      CaseRow row;
      row.status = angle > 30.0 ? kCaseInterrupted : kCaseComplete;
      row.figures = {angle};
      return row;
    };
    CHECK(searchLeastStableAngle(searchStudy({0, 22.5, 45, 67.5}, true, 0.1), stopped).status == kCaseInterrupted);
    CHECK(evaluated == 3);
  }
}

namespace {

constexpr double kGravity = 9.81, kCarriage = 20000, kUpper = 6000, kBehind = 1.0, kRadius = 8.0;  // kg, m
constexpr double kFrontEdge = 2.0, kOtherEdges = 3.0;                                               // m from the axis

/// The tests' carriage on pads (carriage_on_pads.hpp) on a trapezoid: its front edge
/// 4x + y = 2√17 m (normal at atan(1/4), 2 m from the axis), the others 3 m from it.
std::string carriageOnTrapezoid(double load_mass) {
  const double front = kFrontEdge * std::sqrt(17.0);  // 4x + y on the front edge
  return test::carriageOnPadsYaml({.carriage_mass = kCarriage,
                                   .upper_mass = kUpper,
                                   .load_mass = load_mass,
                                   .gravity = kGravity,
                                   .pads = {{{(front - kOtherEdges) / 4.0, kOtherEdges},
                                             {-kOtherEdges, kOtherEdges},
                                             {-kOtherEdges, -kOtherEdges},
                                             {(front + kOtherEdges) / 4.0, -kOtherEdges}}}});
}

/// Case 0 of `study_text` on the carriage above with a 5 t load.
CaseRow trapezoidCase(const std::string& study_text, const std::string& name) {
  const auto directory = std::filesystem::temp_directory_path() / ("cranesim_least_stable_" + name);
  std::filesystem::create_directories(directory);
  std::ofstream(directory / "carriage.yaml") << carriageOnTrapezoid(5000.0);
  std::ofstream(directory / "study.yaml") << study_text;
  const CaseRow row = runCase(readStudy((directory / "study.yaml").string()), 0, {});
  std::filesystem::remove_all(directory);
  return row;
}

}  // namespace

TEST_CASE("the least stable angle of a carriage on a trapezoid of pads, and its capacity there, by hand",
          "[study][least_stable][supports]") {
  const double worst_deg = std::atan2(1.0, 4.0) * 180.0 / std::numbers::pi;  // 14.036°
  const double tipping = kGravity * (kCarriage * kFrontEdge + kUpper * (kFrontEdge + kBehind)) / (kRadius - kFrontEdge);  // 9.667 t
  constexpr const char* kFigures = R"(
scene: carriage.yaml
analysis: static
figures:
  - {name: tipping, quantity: tipping_load, body: load}
  - {name: fraction, quantity: tipping_load_fraction, body: load}
)";
  SECTION("over the front edge's normal, the tipping load at its least") {
    const CaseRow row = trapezoidCase(std::string(kFigures) + R"(
least_stable_angle: {angle: constraints.slewing.drive.value, range: {from: 0, to: 337.5, count: 16}, figure: tipping,
                     worst: min, tolerance: 0.02}
)", "search");
    INFO(row.message);
    REQUIRE(row.status == kCaseComplete);
    CHECK(row.worst_grid_angle == 22.5);  // 9.80 t there, 10.04 t at 0°
    CHECK(std::abs(row.least_stable_angle - worst_deg) <= 0.02);
    // The ground settles 1.7e-5 m under the pads: the hand's rigid geometry holds to ~1e-5.
    CHECK(row.least_stable_value == Approx(tipping).epsilon(5e-5));
    CHECK(row.figures[0] == row.least_stable_value);
    CHECK(row.figures[1] == Approx(5000.0 * kGravity / tipping).epsilon(5e-5));
  }
  SECTION("with a capacity: the load that reaches 85 % of the tipping load there") {
    const CaseRow row = trapezoidCase(std::string(kFigures) + R"(
criteria:
  - {figure: fraction, max: 0.85, source: "a test's limit"}
capacity: {load: bodies.load.mass, from: 1000, to: 20000, tolerance: 5}
least_stable_angle: {angle: constraints.slewing.drive.value, values: [0, 22.5, 45, 67.5, 90], figure: fraction,
                     worst: max, tolerance: 0.02}
)", "capacity");
    INFO(row.message);
    REQUIRE(row.status == kCaseComplete);
    CHECK(std::abs(row.least_stable_angle - worst_deg) <= 0.02);
    // The search ran at the bracket's light end, 1 t.
    CHECK(row.least_stable_value == Approx(1000.0 * kGravity / tipping).epsilon(5e-5));
    const double capacity = 0.85 * tipping / kGravity;  // 8216.7 kg
    CHECK(row.capacity <= capacity * (1.0 + 5e-5));
    CHECK(row.inadmissible_load >= capacity * (1.0 - 5e-5));
    CHECK(row.inadmissible_load - row.capacity <= 5.0);
    CHECK(row.limited_by == "fraction");
  }
}
