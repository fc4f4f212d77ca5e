// A study's figures of a crane's supports (support_pressure, stability_margin, tipping_load,
// tipping_load_fraction) against hand statics: a 20 t carriage on four pads over stiff ground,
// its upper carriage slewed straight ahead and over a corner, a 9 t load hanging 8 m out. The
// hand uses the drawn geometry (the ground settles 1.7e-5 m: the equilibrium's geometry differs
// by about that, 1e-5 of the figures), the bodies' weights, and the rigid plate's pad forces.

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "cranesim/crane/support_statics.hpp"
#include "cranesim/study/case_runner.hpp"
#include "cranesim/study/study.hpp"
#include "carriage_on_pads.hpp"

using namespace cranesim;
using Eigen::Vector2d;

namespace {

constexpr double kGravity = 9.81, kCarriage = 20000, kUpper = 6000, kLoad = 9000;  // kg
constexpr double kPadArea = 0.5, kHalfLength = 2.5, kHalfWidth = 2.0;             // m², m

/// The tests' carriage on pads (carriage_on_pads.hpp) with the masses above, slewed by
/// `slewed_deg`.
std::string carriageOnPads(double slewed_deg) {
  test::CarriageOnPads c;
  c.carriage_mass = kCarriage;
  c.upper_mass = kUpper;
  c.load_mass = kLoad;
  c.pad_area = kPadArea;
  c.gravity = kGravity;
  c.slewed_deg = slewed_deg;
  return test::carriageOnPadsYaml(c);
}

constexpr const char* kStudy = R"(
scene: carriage.yaml
analysis: static
figures:
  - {name: pressure, quantity: support_pressure}
  - {name: margin, quantity: stability_margin}
  - {name: tipping, quantity: tipping_load, body: load}
  - {name: fraction, quantity: tipping_load_fraction, body: load}
)";

/// The four figures of the study above on the carriage slewed by `slewed_deg`.
std::vector<double> supportFigures(double slewed_deg) {
  const auto directory = std::filesystem::temp_directory_path() / fmt::format("cranesim_support_figures_{}", slewed_deg);
  std::filesystem::create_directories(directory);
  std::ofstream(directory / "carriage.yaml") << carriageOnPads(slewed_deg);
  std::ofstream(directory / "study.yaml") << kStudy;
  const CaseRow row = runCase(readStudy((directory / "study.yaml").string()), 0, {});
  std::filesystem::remove_all(directory);
  INFO(row.message);
  REQUIRE(row.status == kCaseComplete);
  return row.figures;
}

/// The signed distance of `point` inside each edge of the pads' rectangle: front (x = 2.5),
/// left (y = 2), rear, right.
std::array<double, 4> insideEdges(const Vector2d& point) {
  return {kHalfLength - point.x(), kHalfWidth - point.y(), kHalfLength + point.x(), kHalfWidth + point.y()};
}

}  // namespace

TEST_CASE("Support figures: the pads' peak pressure, the margin and the tipping load by hand", "[supports][study]") {
  // Straight ahead the front edge faces the load alone; over the 40° corner the left edge
  // (y = 2 m) lies nearest the resultant and is also the one the resultant leaves through first
  // as the load grows, before the front edge (ΔF = 0.251 W against 0.291 W), with a pad lifted.
  for (const double slewed : {0.0, 40.0}) {
    CAPTURE(slewed);
    const Vector2d ahead(std::cos(slewed * std::numbers::pi / 180), std::sin(slewed * std::numbers::pi / 180));
    const Vector2d load = 8.0 * ahead, upper = -1.0 * ahead;
    const double weight = (kCarriage + kUpper + kLoad) * kGravity, load_weight = kLoad * kGravity;
    const Vector2d resultant = (kUpper * upper + kLoad * load) / (kCarriage + kUpper + kLoad);
    const std::vector<PadSpring> pads = {{{2.5, 2}, 1.0}, {{-2.5, 2}, 1.0}, {{-2.5, -2}, 1.0}, {{2.5, -2}, 1.0}};
    const std::vector<double> forces = rigidPlatePadForces(pads, weight, resultant);
    const double pressure = *std::max_element(forces.begin(), forces.end()) / kPadArea;
    const std::array<double, 4> resultant_inside = insideEdges(resultant), load_inside = insideEdges(load);
    const double margin = weight * *std::min_element(resultant_inside.begin(), resultant_inside.end());
    double added = INFINITY;
    for (int e = 0; e < 4; ++e)
      if (load_inside[e] < 0) added = std::min(added, weight * resultant_inside[e] / -load_inside[e]);

    const std::vector<double> figures = supportFigures(slewed);
    CHECK(figures[0] == Approx(pressure).epsilon(1e-4));
    CHECK(figures[1] == Approx(margin).epsilon(1e-4));
    CHECK(figures[2] == Approx(load_weight + added).epsilon(1e-4));
    CHECK(figures[3] == Approx(load_weight / (load_weight + added)).epsilon(1e-4));
    if (slewed == 40.0) CHECK(*std::min_element(forces.begin(), forces.end()) == 0.0);
  }
}
