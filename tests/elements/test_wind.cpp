// Wind: the drag on a load and its height profile by hand, the static offset of a hanging load,
// the turbulence series' variance and spectrum, aerodynamic damping of a swing in still air,
// and the wind elements' Jacobians against finite differences.

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <fstream>
#include <random>
#include <sstream>

#include "cranesim/math/turbulence.hpp"
#include "cranesim/model/truss_geometry.hpp"
#include "cranesim/model/wind_elements.hpp"
#include "element_differences.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

/// A 10 t load hung from a hinge about y, its centroid (the body origin) `length` below the pivot
/// at height `height`; WIND is replaced by the scene's wind block.
std::string hangingLoad(const std::string& wind, double length = 10.0, double height = 30.0) {
  std::string yaml = fmt::format(R"(
name: hanging load
gravity: [0, 0, -9.81]
ground:
  joints: [{{name: pivot, position: [0, 0, {}]}}]
bodies:
  - name: load
    mass: 10000
    inertia: [100, 100, 100]
    position: [0, 0, {}]
    joints: [{{name: top, position: [0, 0, {}]}}]
constraints:
  - {{name: hinge, type: revolute, joints: [ground.pivot, load.top], axis: y}}
solver: {{t_end: 1, rtol: 1.0e-8, atol: 1.0e-10}}
output: {{interval: 0.01}}
)",
                                 height, height - length, length);
  return yaml + wind;
}

/// The generalized wind force on element `e` of `model` at q0 and at rest, at time t.
VecX windForceAtRest(const Model& model, int e, double t = 0.0) {
  const VecX v = VecX::Zero(model.nv);
  const ElementInput in{model.q0.data(), v.data(), v.data(), t, model.gravity};
  VecX r(model.elements[e]->size());
  model.elements[e]->residual(in, r.data());
  return -r;
}

}  // namespace

TEST_CASE("The drag on a load at rest is q c A by hand", "[wind]") {
  // 12 m/s at 10 m, power law α = 0.14, the load's centroid at 25 m; area 1.2 m²/t · 10 t.
  const Model model = test::loadYaml(hangingLoad(R"(
wind:
  speed: 12
  azimuth: 30
  profile: {law: power, exponent: 0.14}
  bodies: [{body: load}]
)", 5.0));
  REQUIRE(model.wind_parts.size() == 1);
  const VecX Q = windForceAtRest(model, model.wind_parts[0].elements[0]);
  const double v = 12.0 * std::pow(25.0 / 10.0, 0.14), q = 0.5 * 1.25 * v * v, cA = 1.2 * 12.0;
  const Vec3 expected = q * cA * Vec3(std::cos(std::numbers::pi / 6), std::sin(std::numbers::pi / 6), 0.0);
  CHECK((Q.head<3>() - expected).norm() <= 1e-9 * expected.norm());
  CHECK(Q.tail<3>().norm() <= 1e-9 * expected.norm());  // at the centroid: no moment
}

TEST_CASE("The wind at a joint off the centroid turns the load", "[wind]") {
  const Model model = test::loadYaml(hangingLoad(R"(
wind:
  speed: 10
  direction: [0, 2, 0]
  bodies: [{body: load, area: 4, drag_coefficient: 1.5, joint: load.top}]
)", 5.0));
  const VecX Q = windForceAtRest(model, model.wind_parts[0].elements[0]);
  const double F = 0.5 * 1.25 * 100.0 * 1.5 * 4.0;
  CHECK((Q.head<3>() - Vec3(0, F, 0)).norm() <= 1e-12 * F);
  // At p = (0, 0, 5) in body axes (identity rotation): moment p × F = (−5 F, 0, 0).
  CHECK((Q.tail<3>() - Vec3(-5.0 * F, 0, 0)).norm() <= 1e-12 * F);
}

TEST_CASE("The height profiles follow their laws at three heights", "[wind]") {
  WindFieldSpec spec;
  spec.speed = 20.0;
  spec.reference_height = 10.0;
  spec.ground_height = 2.0;
  SECTION("power law") {
    spec.profile.law = WindProfileLaw::Power;
    spec.profile.exponent = 0.14;
    const WindField wind(spec, Vec3(0, 0, -9.81));
    for (const double z : {3.0, 27.0, 80.0}) {
      const double v = wind.velocity<double>(Vec3(1.0, -4.0, z + 2.0), 0.0).x();
      CHECK(std::abs(v - 20.0 * std::pow(z / 10.0, 0.14)) <= 1e-12 * v);
    }
    CHECK(wind.velocity<double>(Vec3(0, 0, 2.5), 0.0).x() == Approx(20.0 * std::pow(0.1, 0.14)).epsilon(1e-12));  // below z_min = 1 m
  }
  SECTION("logarithmic law, EN 1991-1-4 terrain category III") {
    spec.profile.law = WindProfileLaw::Logarithmic;
    spec.profile.roughness_length = 0.3;
    spec.profile.minimum_height = 5.0;
    const WindField wind(spec, Vec3(0, 0, -9.81));
    for (const double z : {7.0, 27.0, 80.0}) {
      const double v = wind.velocity<double>(Vec3(0, 0, z + 2.0), 0.0).x();
      CHECK(std::abs(v - 20.0 * std::log(z / 0.3) / std::log(10.0 / 0.3)) <= 1e-12 * v);
    }
    CHECK(wind.velocity<double>(Vec3(0, 0, 4.0), 0.0).x() == Approx(20.0 * std::log(5.0 / 0.3) / std::log(10.0 / 0.3)).epsilon(1e-12));
  }
}

TEST_CASE("A gust rises and falls smoothly to its factor", "[wind]") {
  WindFieldSpec spec;
  spec.speed = 10.0;
  spec.gust = GustSpec{2.0, 1.0, 5.0, 1.5};
  const WindField wind(spec, Vec3(0, 0, -9.81));
  CHECK(wind.gustFactor(1.9) == 1.0);
  CHECK(wind.gustFactor(2.5) == Approx(1.25).epsilon(1e-14));
  CHECK(wind.gustFactor(4.0) == 1.5);
  CHECK(wind.gustFactor(6.5) == Approx(1.25).epsilon(1e-14));
  CHECK(wind.gustFactor(7.1) == 1.0);
  // Continuous first derivative at the rise's end and the fall's start.
  const double h = 1e-6;
  for (const double t : {2.0, 3.0, 6.0, 7.0})
    CHECK(std::abs((wind.gustFactor(t + h) - wind.gustFactor(t)) - (wind.gustFactor(t) - wind.gustFactor(t - h))) <= 1e-10);
}

TEST_CASE("A hanging load's offset in steady wind is F L / W", "[wind]") {
  // Uniform wind, so the force does not change as the load moves: tan θ = F/W exactly.
  const std::string yaml = hangingLoad(R"(
wind:
  speed: 10
  direction: [1, 0, 0]
  bodies: [{body: load}]
)");
  const Vec3 at = test::equilibriumJointPosition(yaml, "load.origin");
  const double F = 0.5 * 1.25 * 100.0 * 1.2 * 12.0, W = 10000.0 * 9.81, L = 10.0;
  const double offset = at.x();
  CHECK(std::abs(offset - F * L / W) <= 1e-3 * F * L / W);
  CHECK(std::abs(offset - L * std::sin(std::atan(F / W))) <= 1e-8 * offset);
}

TEST_CASE("Turbulence reproduces its standard deviation and the spectrum's -5/3 slope", "[wind]") {
  const double sigma = 3.0, L = 340.2, V = 20.0, T = 600.0;
  const TurbulenceSeries u(sigma, L, V, T, 2.0, 42);
  const double dt = 0.05;
  const int n = static_cast<int>(std::round(T / dt));
  std::vector<double> samples(n);
  double mean = 0.0;
  for (int j = 0; j < n; ++j) mean += (samples[j] = u(j * dt)) / n;
  double variance = 0.0;
  for (const double s : samples) variance += (s - mean) * (s - mean) / n;
  CHECK(std::abs(std::sqrt(variance) - sigma) <= 0.05 * sigma);
  CHECK(std::abs(std::sqrt(variance) - sigma) <= 2e-3 * sigma);  // exact over a whole period, up to interpolation

  // Periodogram at the harmonics 0.2 … 1 Hz (the Kaimal spectrum's inertial range for L/V = 17 s),
  // and the least-squares slope of log S against log f: the target's own slope there is
  // −5/3 · x/(1 + x), x = 6 f L/V, −1.62 on average; −5/3 only as f → ∞.
  const auto slope = [](const std::vector<double>& f, const std::vector<double>& s) {
    double mx = 0, my = 0;
    for (std::size_t k = 0; k < f.size(); ++k) mx += std::log(f[k]) / f.size(), my += std::log(s[k]) / f.size();
    double sxy = 0, sxx = 0;
    for (std::size_t k = 0; k < f.size(); ++k)
      sxy += (std::log(f[k]) - mx) * (std::log(s[k]) - my), sxx += (std::log(f[k]) - mx) * (std::log(f[k]) - mx);
    return sxy / sxx;
  };
  std::vector<double> f, measured, target;
  for (int k = static_cast<int>(0.2 * T); k <= static_cast<int>(1.0 * T); ++k) {
    std::complex<double> X = 0.0;
    const std::complex<double> turn = std::polar(1.0, -2.0 * std::numbers::pi * k / n);
    std::complex<double> z = 1.0;
    for (int j = 0; j < n; ++j, z *= turn) X += samples[j] * z;
    f.push_back(k / T);
    measured.push_back(2.0 * std::norm(X) / n / n * T);  // one-sided: a_k²/2 = S Δf
    target.push_back(kaimalSpectrum(k / T, sigma, L, V));
  }
  const double measured_slope = slope(f, measured), target_slope = slope(f, target);
  CAPTURE(measured_slope, target_slope);
  CHECK(std::abs(measured_slope - target_slope) <= 0.01);
  CHECK(std::abs(measured_slope + 5.0 / 3.0) <= 0.1);

  // Seeded: the same seed gives the same series, another seed another one.
  const TurbulenceSeries same(sigma, L, V, T, 2.0, 42), other(sigma, L, V, T, 2.0, 43);
  CHECK(same(123.4) == u(123.4));
  CHECK(other(123.4) != u(123.4));
}

TEST_CASE("A swing in still air decays as quadratic drag predicts", "[wind]") {
  // A 1 t point-like load on a 10 m hinge, area 20 m², c = 1.2, released at θ₀ = 0.1 rad in still
  // air. Quadratic drag k|v|v (k = ½ρcA) takes per half swing ∫ k|v|³ dt = (4/3) k L³ θ₀³ ω², from
  // E = ½ J ω² θ₀² (J = m L² + I): Δθ₀ = −(4/3) k L³ θ₀² / J per half swing, so 1/θ₀ grows
  // linearly by (4/3) k L³ / J per half swing.
  const double m = 1000.0, L = 10.0, I = 1.0, k = 0.5 * 1.25 * 1.2 * 20.0, theta0 = 0.1;
  Scene scene = parseScene(fmt::format(R"(
name: swing in still air
gravity: [0, 0, -9.81]
ground:
  joints: [{{name: pivot, position: [0, 0, 0]}}]
bodies:
  - name: load
    mass: {}
    inertia: [{}, {}, {}]
    position: [{}, 0, {}]
    rotation: {{axis: [0, 1, 0], angle: {}}}
    joints: [{{name: top, position: [0, 0, {}]}}]
constraints:
  - {{name: hinge, type: revolute, joints: [ground.pivot, load.top], axis: y}}
wind:
  speed: 0
  direction: [1, 0, 0]
  bodies: [{{body: load, area: 20}}]
solver: {{t_end: 40, rtol: 1.0e-9, atol: 1.0e-11}}
output: {{interval: 0.001}}
)",
                                       m, I, I, I, -L * std::sin(theta0), -L * std::cos(theta0), theta0, L),
                           "<test>");
  const test::SimulationRun run(scene);
  REQUIRE(run.outcome.complete);
  const std::vector<double>& t = run.recorder.time();
  const std::vector<double>& x = run.jointPositions("load.origin");
  // The extremes of x between sign changes: one per half swing.
  std::vector<double> inverse_amplitude;
  double extreme = 0.0;
  for (std::size_t s = 1; s < t.size(); ++s) {
    const double xs = x[3 * s];
    if (std::abs(xs) > std::abs(extreme)) extreme = xs;
    if (xs * x[3 * (s - 1)] < 0.0) {
      inverse_amplitude.push_back(1.0 / std::asin(std::abs(extreme) / L));
      extreme = 0.0;
    }
  }
  REQUIRE(inverse_amplitude.size() >= 10);
  const double per_half_swing = (inverse_amplitude.back() - inverse_amplitude.front()) / (inverse_amplitude.size() - 1.0);
  const double predicted = 4.0 / 3.0 * k * L * L * L / (m * L * L + I);
  CAPTURE(per_half_swing, predicted, inverse_amplitude.size());
  CHECK(std::abs(per_half_swing - predicted) <= 5e-3 * predicted);
  // The wind's work is in the energy books: the balance holds.
  CHECK(run.recorder.relativeBalanceDrift() <= 1e-5);
}

TEST_CASE("The wind elements' Jacobians match finite differences", "[wind]") {
  WindFieldSpec spec;
  spec.speed = 15.0;
  spec.direction = Vec3(0.6, 0.8, 0.0);
  spec.profile.law = WindProfileLaw::Power;
  spec.profile.exponent = 0.2;
  spec.turbulence = TurbulenceSpec{0.15, 340.2, 600.0, 2.0, 7};
  const auto wind = std::make_shared<const WindField>(spec, Vec3(0, 0, -9.81));
  std::mt19937 random(5);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const auto check = [&](const Element& e, const VecX& q, const VecX& v) {
    const VecX a = VecX::Zero(e.size());
    ElementInput in{q.data(), v.data(), a.data(), 3.7, Vec3(0, 0, -9.81)};
    in.load_factor = 0.8;
    test::checkMasslessJacobian(e, in, 1e-6);
  };
  SECTION("a load at a point off its origin") {
    const BodyWindElement e(wind, 14.4, Vec3(0.3, -0.2, 1.5), 0, {0, 1, 2, 3, 4, 5}, {0, 1, 2, 3, 4, 5});
    VecX q(6), v(6);
    q << 2.0, -1.0, 25.0, 0.3 * uniform(random), 0.3 * uniform(random), 0.3 * uniform(random);
    for (int k = 0; k < 6; ++k) v(k) = 3.0 * uniform(random);
    check(e, q, v);
  }
  SECTION("a lattice section through its two end-section frames") {
    std::vector<int> indices(12);
    for (int k = 0; k < 12; ++k) indices[k] = k;
    const std::vector<Vec3> points = {Vec3(0, 1.5, 1.4), Vec3(15, 1.5, 1.4), Vec3(2.5, -1.5, 1.4), Vec3(5, 1.5, -1.4),
                                      Vec3(15, -1.5, -1.4)};
    const std::vector<WindTube> tubes = {{0, 1, 0.24}, {2, 3, 0.12}, {1, 4, 0.24}};
    const LatticeWindElement e(wind, points, tubes, 15.0, 3, 0, 1, indices, indices);
    VecX q(12), v(12);
    q << 0.0, 0.0, 20.0, 0.2, -0.3, 0.1, 14.8, 0.5, 22.0, 0.25, -0.35, 0.05;
    for (int k = 0; k < 12; ++k) v(k) = 2.0 * uniform(random);
    check(e, q, v);
  }
  SECTION("a rope element between two spline rope nodes") {
    std::vector<int> indices(12);
    for (int k = 0; k < 12; ++k) indices[k] = k;
    const LineWindElement e(wind, 1.2 * 0.04, 3, 0, 1, 6, indices, indices);
    VecX q(12), v(12);
    q << 0.0, 0.0, 40.0, 0.1, 0.0, -1.0, 1.5, 0.5, 28.0, 0.1, 0.0, -1.0;
    for (int k = 0; k < 12; ++k) v(k) = 4.0 * uniform(random);
    check(e, q, v);
  }
}

TEST_CASE("Every lattice fidelity sees the same wind, the tubes' cross-flow drag", "[wind]") {
  // The 15 m type 2 section along x in 20 m/s towards (0.6, 0.8, 0), c = 1.2, shielding 0.6:
  // each tube counts ½ ρ c d (1 + η)/2 ℓ |w⊥| w⊥ in the uniform wind (the Gauss points integrate
  // it exactly).
  std::ifstream file(test::configPath("truss_type2_cantilever.yaml"));
  std::stringstream text;
  text << file.rdbuf();
  const std::string wind = R"(
wind:
  speed: 20
  direction: [0.6, 0.8, 0]
  members: [{member: boom, shielding: 0.6}]
)";
  const Scene scene = parseScene(text.str() + wind, "<test>");
  const TrussGeometry g = buildTrussGeometry(scene.trusses[0]);
  const Vec3 w(12.0, 16.0, 0.0);
  Vec3 expected = Vec3::Zero();
  for (const TrussMember& tube : g.members) {
    const Vec3 chord = g.nodes[tube.node2].position - g.nodes[tube.node1].position, e = chord.normalized();
    const Vec3 across = w - e * e.dot(w);
    expected += 0.5 * 1.25 * 1.2 * 2.0 * tube.section.outer_radius * 0.8 * chord.norm() * across.norm() * across;
  }
  for (const char* fidelity : {"members", "super_truss", "condensed", "beam"}) {
    std::string yaml = text.str() + wind;
    yaml.replace(yaml.find("fidelity: members"), 17, std::string("fidelity: ") + fidelity);
    const Model model = test::loadYaml(yaml);
    REQUIRE(model.wind_parts.size() == 1);
    const VecX v = VecX::Zero(model.nv);
    const ElementInput in{model.q0.data(), v.data(), v.data(), 0.0, model.gravity};
    const Vec3 F = dynamic_cast<const WindElement&>(*model.elements[model.wind_parts[0].elements[0]]).resultantForce(in);
    CAPTURE(fidelity, F.transpose(), expected.transpose());
    CHECK((F - expected).norm() <= 1e-12 * expected.norm());
  }
}

TEST_CASE("A lattice cantilever bends alike in the wind as full-member model and condensed section", "[wind]") {
  // Without gravity, 30 m/s across the 15 m section clamped at its start: half the tubes' wind
  // reaches the free end section at either fidelity, whose stiffness the condensed element
  // condenses from the full-member model.
  std::ifstream file(test::configPath("truss_type2_cantilever.yaml"));
  std::stringstream text;
  text << file.rdbuf();
  std::string yaml = text.str() + R"(
wind:
  speed: 30
  direction: [0, 1, 0]
  members: [{member: boom}]
)";
  yaml.replace(yaml.find("gravity: [0, 0, -9.81]"), 22, "gravity: [0, 0, 0]");
  const double members = test::equilibriumJointPosition(yaml, "boom.end").y();
  yaml.replace(yaml.find("fidelity: members"), 17, "fidelity: condensed");
  const double condensed = test::equilibriumJointPosition(yaml, "boom.end").y();
  CAPTURE(members, condensed);
  CHECK(members > 0.0);
  CHECK(std::abs(condensed - members) <= 1e-5 * members);
}
