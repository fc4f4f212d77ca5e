// A study's cases: the random draws against the moments of their distributions, their
// independence of the order they are drawn in, and the numbering of grid cases.

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <vector>

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
