// A study's cases: the random draws against the moments of their distributions, their
// independence of the order they are drawn in, the numbering of grid cases, and the bisection of
// a case's load to its capacity.

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <vector>

#include <fmt/format.h>

#include "cranesim/study/capacity_search.hpp"
#include "cranesim/study/case_runner.hpp"
#include "cranesim/study/random_draw.hpp"
#include "cranesim/study/study.hpp"

using namespace cranesim;

namespace {

constexpr int kDraws = 200000;

struct Moments {
  double mean = 0.0, std_dev = 0.0, low = INFINITY, high = -INFINITY;
};

Moments moments(const RandomDistribution& d, std::uint64_t seed, std::uint64_t parameter = 0) {
  Moments m;
  double sum = 0.0, squares = 0.0;
  for (int i = 0; i < kDraws; ++i) {
    const double x = randomDraw(d, seed, static_cast<std::uint64_t>(i), parameter);
    sum += x;
    squares += x * x;
    m.low = std::min(m.low, x);
    m.high = std::max(m.high, x);
  }
  m.mean = sum / kDraws;
  m.std_dev = std::sqrt(squares / kDraws - m.mean * m.mean);
  return m;
}

/// The standard error of a mean of kDraws draws: 5 of them bound a correct generator's error
/// (a chance of 6e-7 to fail).
double tolerance(double std_dev) { return 5.0 * std_dev / std::sqrt(static_cast<double>(kDraws)); }

}  // namespace

TEST_CASE("uniform draws have the uniform's mean and spread and stay inside", "[study]") {
  RandomDistribution d;
  d.kind = RandomDistribution::Kind::Uniform;
  d.low = 2.0, d.high = 5.0;
  const Moments m = moments(d, 7);
  const double std_dev = 3.0 / std::sqrt(12.0);
  CHECK(std::abs(m.mean - 3.5) < tolerance(std_dev));
  CHECK(std::abs(m.std_dev - std_dev) < 0.01 * std_dev);
  CHECK(m.low >= 2.0);
  CHECK(m.high < 5.0);
  CHECK(m.low < 2.001);
  CHECK(m.high > 4.999);
}

TEST_CASE("normal draws have the normal's mean, spread and tails", "[study]") {
  RandomDistribution d;
  d.kind = RandomDistribution::Kind::Normal;
  d.mean = 1000.0, d.std_dev = 50.0;
  const Moments m = moments(d, 11);
  CHECK(std::abs(m.mean - 1000.0) < tolerance(50.0));
  CHECK(std::abs(m.std_dev - 50.0) < 0.01 * 50.0);
  int beyond_two = 0;
  for (int i = 0; i < kDraws; ++i) beyond_two += std::abs(randomDraw(d, 11, i, 0) - 1000.0) > 100.0;
  const double expected = std::erfc(2.0 / std::numbers::sqrt2);  // 4.55 % beyond 2σ
  CHECK(std::abs(beyond_two / double(kDraws) - expected) < 5.0 * std::sqrt(expected / kDraws));
}

TEST_CASE("truncated normal draws stay in their interval with the truncated mean", "[study]") {
  RandomDistribution d;
  d.kind = RandomDistribution::Kind::TruncatedNormal;
  d.mean = 0.0, d.std_dev = 1.0, d.low = 0.0, d.high = 10.0;
  const Moments m = moments(d, 3);
  CHECK(m.low >= 0.0);
  CHECK(m.high <= 10.0);
  // The half-normal: mean √(2/π), standard deviation √(1 − 2/π).
  CHECK(std::abs(m.mean - std::sqrt(2.0 / std::numbers::pi)) < tolerance(0.6028));
  CHECK(normalMassWithin(d) == Approx(0.5).epsilon(1e-12));
}

TEST_CASE("a draw depends on the seed, the case and the parameter, not on the order of drawing", "[study]") {
  RandomDistribution d;
  d.kind = RandomDistribution::Kind::Normal;
  std::vector<double> forward, backward(100);
  for (int i = 0; i < 100; ++i) forward.push_back(randomDraw(d, 42, i, 1));
  for (int i = 99; i >= 0; --i) backward[i] = randomDraw(d, 42, i, 1);
  CHECK(forward == backward);
  CHECK(randomDraw(d, 42, 5, 1) != randomDraw(d, 43, 5, 1));
  CHECK(randomDraw(d, 42, 5, 1) != randomDraw(d, 42, 6, 1));
  CHECK(randomDraw(d, 42, 5, 1) != randomDraw(d, 42, 5, 2));
  // Two parameters of one case are uncorrelated.
  double sxy = 0.0;
  for (int i = 0; i < kDraws; ++i) sxy += randomDraw(d, 42, i, 0) * randomDraw(d, 42, i, 1);
  CHECK(std::abs(sxy / kDraws) < tolerance(1.0));
}

TEST_CASE("grid cases are numbered with the last grid parameter fastest, then the draws", "[study]") {
  Study study;
  study.parameters.resize(3);
  study.parameters[0].values = {1.0, 2.0};
  study.parameters[1].random = RandomDistribution{};
  study.parameters[2].values = {10.0, 20.0, 30.0};
  study.samples = 4;
  study.seed = 9;
  // case = (grid point) × samples + draw, grid point = i0 × 3 + i2
  const std::vector<double> v = study.parameterValues((1 * 3 + 2) * 4 + 3);
  CHECK(v[0] == 2.0);
  CHECK(v[2] == 30.0);
  CHECK(v[1] == randomDraw(*study.parameters[1].random, 9, (1 * 3 + 2) * 4 + 3, 1));
  CHECK(study.parameterValues(0) == std::vector<double>{1.0, randomDraw(RandomDistribution{}, 9, 0, 1), 10.0});
}

TEST_CASE("a parameter that scales with another follows it in proportion in every case", "[study]") {
  // The rope pendulum's 1000 kg ball (inertia 39.14 kg·m² about each axis) at three masses, its
  // inertia following the mass (the same ball, denser) and a random rope modulus beside them.
  const std::string path = std::string(CRANESIM_SOURCE_DIR) + "/configs/study_linked_ball.yaml";
  const Study study = readStudy(path);
  REQUIRE(study.parameters.size() == 3);
  REQUIRE(study.parameters[1].scales_with == std::optional<std::size_t>(0));
  REQUIRE(study.cases == 6);  // the following parameter adds no cases
  for (long i = 0; i < study.cases; ++i) {
    const std::vector<double> values = study.parameterValues(i);
    const Scene scene = caseScene(study, i);
    const RigidBodySpec& ball = scene.bodies[0];
    INFO("case " << i);
    CHECK(ball.mass == values[0]);
    CHECK(values[1] == values[0] / 1000.0);
    for (int axis = 0; axis < 3; ++axis) CHECK(ball.inertia(axis, axis) == Approx(39.14 * values[0] / 1000.0).epsilon(1e-15));
    CHECK(scene.members[0].material.youngs_modulus == values[2]);
  }
}

namespace {

/// A study whose one figure `pull` is bounded by max 1000 (criterion 0) and `other` by max 5,
/// bisecting its load over [from, to] to `tolerance`.
Study capacityStudy(double from, double to, double tolerance) {
  Study study;
  study.figures.resize(2);
  study.figures[0].name = "pull";
  study.figures[1].name = "other";
  study.criteria.resize(2);
  study.criteria[0].figure = 0;
  study.criteria[0].max = 1000.0;
  study.criteria[1].figure = 1;
  study.criteria[1].max = 5.0;
  study.capacity = CapacitySpec{"bodies.load.mass", from, to, tolerance, {}};
  return study;
}

/// A case whose pull is 2 × load, its other figure 1, computed in one Newton step.
CaseRow linearCase(double load) {
  CaseRow row;
  row.status = kCaseComplete;
  row.figures = {2.0 * load, 1.0};
  row.steps = 1.0;
  return row;
}

}  // namespace

TEST_CASE("a case's capacity is bisected to the tolerance from below, with what limits it", "[study][capacity]") {
  // pull = 2 × load reaches its limit 1000 at a load of 500: bisecting [100, 2000] to 1 takes
  // the two ends and ⌈log2(1900)⌉ = 11 halvings.
  const Study study = capacityStudy(100.0, 2000.0, 1.0);
  std::vector<double> loads;
  const CaseRow row = searchCapacity(study, [&](double load) {
    loads.push_back(load);
    return linearCase(load);
  });
  CHECK(row.status == kCaseComplete);
  CHECK(row.capacity <= 500.0);
  CHECK(row.inadmissible_load > 500.0);
  CHECK(row.inadmissible_load - row.capacity <= 1.0);
  CHECK(row.figures[0] == 2.0 * row.capacity);  // the row is the capacity's
  CHECK(row.limited_by == "pull");
  CHECK(loads.size() == 13);
  CHECK(row.steps == 13.0);
  CHECK(loads[0] == 100.0);
  CHECK(loads[1] == 2000.0);
}

TEST_CASE("a capacity outside its bracket, and loads the analysis cannot compute", "[study][capacity]") {
  SECTION("the heaviest load admissible: the capacity is the bracket's end, nothing limits it") {
    const CaseRow row = searchCapacity(capacityStudy(100.0, 400.0, 1.0), linearCase);
    CHECK(row.capacity == 400.0);
    CHECK(std::isnan(row.inadmissible_load));
    CHECK(row.limited_by.empty());
  }
  SECTION("the lightest load inadmissible: no capacity, and what that load violates") {
    const CaseRow row = searchCapacity(capacityStudy(600.0, 900.0, 1.0), [](double load) {
      CaseRow r = linearCase(load);
      r.figures[1] = 6.0;
      return r;
    });
    CHECK(row.status == kCaseComplete);
    CHECK(std::isnan(row.capacity));
    CHECK(row.inadmissible_load == 600.0);
    CHECK(row.limited_by == "pull, other");
  }
  SECTION("a load whose equilibrium fails is inadmissible, and says why") {
    // Above 300 the analysis fails (the crane tips, say): the capacity is 300, not 500.
    const CaseRow row = searchCapacity(capacityStudy(100.0, 2000.0, 1.0), [](double load) {
      if (load <= 300.0) return linearCase(load);
      CaseRow failed;
      failed.status = kCaseFailed;
      failed.message = "no equilibrium";
      return failed;
    });
    CHECK(row.capacity <= 300.0);
    CHECK(row.inadmissible_load - row.capacity <= 1.0);
    CHECK(row.limited_by == "failed: no equilibrium");
  }
  SECTION("the lightest load failing: the case failed, as a case without capacity does") {
    const CaseRow row = searchCapacity(capacityStudy(100.0, 2000.0, 1.0), [](double) {
      CaseRow failed;
      failed.status = kCaseFailed;
      failed.message = "no equilibrium";
      return failed;
    });
    CHECK(row.status == kCaseFailed);
    CHECK(std::isnan(row.capacity));
  }
}

TEST_CASE("a row's capacity travels with it", "[study][capacity]") {
  CaseRow row = linearCase(42.0);
  row.index = 7;
  row.capacity = 41.5;
  row.inadmissible_load = 42.25;
  row.limited_by = "sub_cable, hoist_rope";
  const std::optional<CaseRow> back = decodeRow(encodeRow(row), 2);
  REQUIRE(back);
  CHECK(back->capacity == row.capacity);
  CHECK(back->inadmissible_load == row.inadmissible_load);
  CHECK(back->limited_by == row.limited_by);
  CHECK(back->figures == row.figures);
  const std::optional<CaseRow> plain = decodeRow(encodeRow(linearCase(1.0)), 2);
  REQUIRE(plain);
  CHECK(std::isnan(plain->capacity));
  CHECK(plain->limited_by.empty());
}

TEST_CASE("a study's capacity sets the load and what follows it in each case's scene", "[study][capacity]") {
  // study_linked_ball.yaml's ball (1000 kg, inertia 39.14 kg·m²) with its mass bisected instead of
  // varied: a case's scene at 2500 kg has the inertia 2.5 × 39.14.
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "cranesim_capacity_study";
  std::filesystem::create_directories(dir);
  const std::filesystem::path path = dir / "capacity.yaml";
  std::ofstream(path) << fmt::format(R"(
scene: {}/configs/rope_pendulum.yaml
analysis: static
capacity: {{load: bodies.ball.mass, from: 500, to: 10000, tolerance: 10, scales: [bodies.ball.inertia]}}
figures: [{{name: top, quantity: rope_tension, rope: rope, end: start}}]
criteria: [{{figure: top, max: 2.0e4, source: "a test's limit"}}]
)", CRANESIM_SOURCE_DIR);
  const Study study = readStudy(path.string());
  REQUIRE(study.capacity);
  const Scene scene = caseScene(study, 0, {2500.0});
  CHECK(scene.bodies[0].mass == 2500.0);
  for (int axis = 0; axis < 3; ++axis) CHECK(scene.bodies[0].inertia(axis, axis) == Approx(39.14 * 2.5).epsilon(1e-15));
  // The rope's tension at its top carries the ball and the rope: W = (m + m_rope) g reaches
  // 2e4 N at m = 2e4 / g − m_rope.
  const CaseRow row = runCase(study, 0, {});
  REQUIRE(row.status == kCaseComplete);
  const double hand = 2.0e4 / 9.81 - 7800.0 * std::numbers::pi * 0.01 * 0.01 * 10.0;  // 2014.2 kg
  CHECK(row.figures[0] <= 2.0e4);
  CHECK(row.capacity <= hand * (1.0 + 1e-9));
  CHECK(row.inadmissible_load >= hand * (1.0 - 1e-9));
  CHECK(row.inadmissible_load - row.capacity <= 10.0);
  CHECK(row.limited_by == "top");
  std::filesystem::remove_all(dir);
}
