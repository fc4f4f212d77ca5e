// Modal analysis (solvers/modes.hpp) of assembled models: the natural frequencies of the
// thesis' cantilever (8.1.2) built from either beam element against Euler–Bernoulli, Rayleigh
// and Timoshenko beam theory, with their convergence in the number of segments; torsion and
// axial quarter-wave frequencies; rigid-body modes of a free beam; pendulums, whose whole
// stiffness is the geometric stiffness of the constraint force.

#include <catch2/catch.hpp>

#include <cstdio>
#include <numbers>

#include "cantilever_theory.hpp"
#include "cranesim/elements/section.hpp"
#include "cranesim/solvers/modes.hpp"
#include "cranesim/solvers/statics.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDensity = 7800.0, kYoungsModulus = 2.06e11, kPoisson = 0.25;
constexpr double kShearModulus = kYoungsModulus / (2.0 * (1.0 + kPoisson));

/// A straight steel beam of solid round section along x, clamped at x = 0 or free, no gravity.
std::string beamYaml(const std::string& type, double length, double radius, int segments, bool clamped) {
  std::string yaml = "name: modal beam\ngravity: [0, 0, 0]\nground:\n  joints: [{name: wall, position: [0, 0, 0]}]\n";
  yaml += "members:\n  - name: beam\n    type: " + type + "\n    start: [0, 0, 0]\n    end: [" + std::to_string(length) +
          ", 0, 0]\n    z_axis: [0, 0, 1]\n    segments: " + std::to_string(segments) +
          "\n    section: {radius: " + std::to_string(radius) +
          "}\n    material: {density: 7800, youngs_modulus: 2.06e11, poisson_ratio: 0.25}\n";
  if (clamped) yaml += "constraints:\n  - {name: clamp, type: fixed, joints: [ground.wall, beam.start]}\n";
  return yaml + "solver: {t_end: 1}\n";
}

struct BeamProperties {
  double L, r;
  Section s = Section::circular(r, 0.0, kPoisson);
  double EI() const { return kYoungsModulus * s.Iz; }
  double kGA() const { return s.shear_factor * kShearModulus * s.area; }
  double rhoA() const { return kDensity * s.area; }
  double rhoI() const { return kDensity * s.Iz; }
  double eulerBernoulli(int n) const { return test::eulerBernoulliCantileverFrequency(n, L, EI(), rhoA()); }
  std::vector<double> timoshenko() const { return test::timoshenkoCantileverFrequencies(L, EI(), kGA(), rhoA(), rhoI(), 3); }
  /// Rotary inertia without shear deformation: the continuum limit of the spline beam.
  std::vector<double> rayleigh() const { return test::timoshenkoCantileverFrequencies(L, EI(), 1e6 * kGA(), rhoA(), rhoI(), 3); }
  /// Quarter-wave frequencies of a clamped–free bar (1/4L)√(GJ/ρJ_p), (1/4L)√(E/ρ) (round: J = J_p).
  double torsion() const { return std::sqrt(kShearModulus * s.J / (kDensity * (s.Iy + s.Iz))) / (4.0 * L); }
  double axial() const { return std::sqrt(kYoungsModulus / kDensity) / (4.0 * L); }
};

/// The non-rigid modes of a beam along x sorted by what moves: a straight beam's modes are
/// pure, so the largest of the three shares names them. Bending modes come in (y, z) pairs.
struct BeamModes {
  ModalResult modal;
  std::vector<double> bending, torsion, axial;
  double bendingPairSpread = 0.0;  // max relative difference within the (y, z) pairs
  double bendingFrequency(int n) const { return bending.at(2 * n); }
};

BeamModes beamModes(const std::string& type, const BeamProperties& beam, int segments, bool clamped = true) {
  const Model model = test::loadYaml(beamYaml(type, beam.L, beam.r, segments, clamped));
  BeamModes out{computeModes(model, model.q0, 0.0, 0), {}, {}, {}};  // unloaded: q0 is the equilibrium
  const double gyration2 = (beam.s.Iy + beam.s.Iz) / beam.s.area;
  for (int k = 0; k < out.modal.frequencies.size(); ++k) {
    if (out.modal.rigid[k]) continue;
    double axial = 0.0, bending = 0.0, torsion = 0.0;
    for (const Node& n : model.nodes) {
      const auto u = out.modal.shapes.col(k).segment(n.v, 4);
      axial += u(0) * u(0);
      bending += u(1) * u(1) + u(2) * u(2);
      torsion += gyration2 * u(3) * u(3);
    }
    const double f = out.modal.frequencies(k);
    if (bending >= axial && bending >= torsion) out.bending.push_back(f);
    else if (torsion >= axial) out.torsion.push_back(f);
    else out.axial.push_back(f);
  }
  for (std::size_t k = 0; k + 1 < out.bending.size(); k += 2)
    out.bendingPairSpread = std::max(out.bendingPairSpread, std::abs(out.bending[k + 1] / out.bending[k] - 1.0));
  return out;
}

double relativeError(double value, double reference) { return value / reference - 1.0; }

}  // namespace

TEST_CASE("modes: slender cantilever bending frequencies converge for both beam elements", "[modes][timoshenko][spline_beam]") {
  const BeamProperties beam{15.0, 0.15};
  const std::vector<double> timoshenko = beam.timoshenko(), rayleigh = beam.rayleigh();
  for (const std::string type : {"timoshenko", "spline_beam"}) {
    // The element's own continuum limit: Timoshenko's beam, or Rayleigh's (EB kinematics with
    // rotary inertia) for the spline beam.
    const std::vector<double>& limit = type == "timoshenko" ? timoshenko : rayleigh;
    std::vector<double> previous(3, 1.0);
    for (int segments : {3, 5, 10}) {
      const BeamModes modes = beamModes(type, beam, segments);
      REQUIRE(modes.bending.size() >= 6);
      CHECK(modes.modal.rigid_modes == 0);
      CHECK(modes.bendingPairSpread < 1e-9);
      CHECK(modes.modal.stiffness_asymmetry < 1e-12);
      for (int n = 0; n < 3; ++n) {
        const double f = modes.bendingFrequency(n);
        const double e_eb = relativeError(f, beam.eulerBernoulli(n)), e_limit = relativeError(f, limit[n]);
        std::printf("[modes] cantilever L=15 r=0.15 %-11s %2d segments mode %d: %.6f Hz, vs EB %+.4f %%, vs %s %+.4f %%\n",
                    type.c_str(), segments, n + 1, f, 100 * e_eb, type == "timoshenko" ? "Timoshenko" : "Rayleigh",
                    100 * e_limit);
        CHECK(std::abs(e_limit) < std::abs(previous[n]));
        previous[n] = e_limit;
        if (segments == 10) {
          CHECK(std::abs(e_limit) < 5e-4);  // measured ≤ 3.9e-4 (mode 3)
          CHECK(std::abs(e_eb) < 4e-3);     // shear and rotary inertia: −0.33 % on mode 3 (Timoshenko)
        }
      }
    }
  }
}

TEST_CASE("modes: cantilever torsion and axial quarter-wave frequencies", "[modes][timoshenko][spline_beam]") {
  const BeamProperties beam{15.0, 0.15};
  for (const std::string type : {"timoshenko", "spline_beam"}) {
    const BeamModes modes = beamModes(type, beam, 10);
    REQUIRE(!modes.torsion.empty());
    REQUIRE(!modes.axial.empty());
    const double e_torsion = relativeError(modes.torsion.front(), beam.torsion());
    const double e_axial = relativeError(modes.axial.front(), beam.axial());
    std::printf("[modes] cantilever %-11s 10 segments: torsion %.5f Hz (%+.4f %%), axial %.5f Hz (%+.4f %%)\n",
                type.c_str(), modes.torsion.front(), 100 * e_torsion, modes.axial.front(), 100 * e_axial);
    CHECK(std::abs(e_torsion) < 2e-3);  // linear twist interpolation: +0.10 %
    CHECK(std::abs(e_axial) < 1e-3);
  }
}

TEST_CASE("modes: thick cantilever, Timoshenko beam against the Timoshenko frequency equation", "[modes][timoshenko][spline_beam]") {
  const BeamProperties beam{2.0, 0.3};
  const std::vector<double> timoshenko = beam.timoshenko(), rayleigh = beam.rayleigh();
  for (const std::string type : {"timoshenko", "spline_beam"}) {
    const BeamModes modes = beamModes(type, beam, 10);
    REQUIRE(modes.bending.size() >= 6);
    for (int n = 0; n < 3; ++n) {
      const double f = modes.bendingFrequency(n);
      std::printf("[modes] thick cantilever L=2 r=0.3 %-11s mode %d: %.3f Hz, vs Timoshenko %+.3f %%, vs Rayleigh "
                  "%+.3f %%, vs EB %+.3f %%\n", type.c_str(), n + 1, f, 100 * relativeError(f, timoshenko[n]),
                  100 * relativeError(f, rayleigh[n]), 100 * relativeError(f, beam.eulerBernoulli(n)));
      if (type == "timoshenko") {
        // The Hermite centre line of the mass (slopes = section axes) converges slower than the
        // exact Timoshenko stiffness where shear is large: +0.01, +0.19, +0.82 % at 10 segments.
        CHECK(std::abs(relativeError(f, timoshenko[n])) < 1e-2);
      } else {
        // Euler–Bernoulli kinematics: the spline beam is Rayleigh's beam and misses the shear
        // deformation, 3.5 to 33 % too stiff against Timoshenko's for this section.
        CHECK(std::abs(relativeError(f, rayleigh[n])) < 5e-4);
        CHECK(relativeError(f, timoshenko[n]) > 0.03);
      }
    }
  }
}

TEST_CASE("modes: a free beam has six rigid-body modes and the free–free bending frequency", "[modes][timoshenko][spline_beam]") {
  const BeamProperties beam{15.0, 0.15};
  const double free_free = 4.730040745 * 4.730040745 / (2 * kPi * beam.L * beam.L) * std::sqrt(beam.EI() / beam.rhoA());
  for (const std::string type : {"timoshenko", "spline_beam"}) {
    const BeamModes modes = beamModes(type, beam, 10, false);
    CHECK(modes.modal.rigid_modes == 6);
    for (int k = 0; k < 6; ++k) {
      CHECK(modes.modal.rigid[k]);
      CHECK(modes.modal.frequencies(k) == 0.0);
    }
    CHECK(!modes.modal.rigid[6]);
    const double f = modes.bendingFrequency(0);
    std::printf("[modes] free–free %-11s 10 segments: largest rigid |ω²| %.3g (threshold %.3g), first bending %.6f Hz "
                "(EB %+.4f %%)\n", type.c_str(), modes.modal.omega_squared.head(6).cwiseAbs().maxCoeff(),
                modes.modal.zero_threshold, f, 100 * relativeError(f, free_free));
    CHECK(std::abs(relativeError(f, free_free)) < 2e-3);  // shear and rotary inertia: −0.10 %
  }
}

TEST_CASE("modes: pendulum frequencies come from the geometric stiffness of the hinge force", "[modes][pendulum]") {
  // Both start hanging: solveStatics from a tilted start reaches the upright equilibrium from
  // some angles (5°, 10°, 60° for configs/pendulum.yaml), which would test statics, not modes.
  SECTION("point-like mass hanging from a hinge") {
    const double m = 2.0, l = 1.5, g = 9.81, I = 1e-6;
    const std::string yaml = R"(
name: point-mass pendulum
gravity: [0, 0, -9.81]
ground:
  joints: [{name: pivot, position: [0, 0, 0]}]
bodies:
  - name: bob
    mass: 2.0
    inertia: [1.0e-6, 1.0e-6, 1.0e-6]
    position: [0, 0, -1.5]
    joints: [{name: top, position: [0, 0, 1.5]}]
constraints:
  - {name: hinge, type: revolute, joints: [ground.pivot, bob.top], axis: y}
solver: {t_end: 1}
)";
    const Model model = test::loadYaml(yaml);
    const ModalResult modal = computeModes(model, model.q0, 0.0, 5);
    CHECK(modal.force_residual < 1e-12);
    REQUIRE(modal.free_dofs == 1);
    REQUIRE(modal.frequencies.size() == 1);
    const double expected = std::sqrt(m * g * l / (m * l * l + I)) / (2 * kPi);
    std::printf("[modes] point-mass pendulum: %.9f Hz (√(mgl/(ml²+I))/2π %.9f Hz), max |λ| %.9g N, asymmetry %.2g\n",
                modal.frequencies(0), expected, modal.lambda.cwiseAbs().maxCoeff(), modal.stiffness_asymmetry);
    CHECK(modal.frequencies(0) == Approx(expected).epsilon(1e-9));
    CHECK(modal.lambda.cwiseAbs().maxCoeff() == Approx(m * g).epsilon(1e-9));

    // Balanced upside down: the same |ω²| with the sign of an unstable equilibrium.
    VecX inverted = model.q0;
    inverted.head<3>() = Vec3(0, 0, l);
    inverted.segment<3>(3) = Vec3(0, kPi, 0);
    const ModalResult up = computeModes(model, inverted, 0.0, 1);
    CHECK(up.force_residual < 1e-9);
    CHECK(up.omega_squared(0) == Approx(-m * g * l / (m * l * l + I)).epsilon(1e-9));
    CHECK(up.frequencies(0) < 0.0);
  }
  SECTION("the compound pendulum of configs/pendulum.yaml, hanging") {
    Scene scene = test::loadScene("pendulum.yaml");
    scene.bodies[0].rotation = Mat3::Identity();
    scene.bodies[0].position = Vec3(0, 0, -0.5);
    const Model model = compileModel(scene);
    const ModalResult modal = computeModes(model, model.q0, 0.0, 1);
    CHECK(modal.force_residual < 1e-12);
    const double d = 0.5, I_pivot = 1.0 / 12.0 + 1.0 * d * d;
    CHECK(modal.frequencies(0) == Approx(std::sqrt(9.81 * d / I_pivot) / (2 * kPi)).epsilon(1e-9));
  }
  SECTION("without gravity the pendulum's one mode is a rigid-body mode") {
    Scene scene = test::loadScene("pendulum.yaml");
    scene.gravity = Vec3::Zero();
    const Model model = compileModel(scene);
    const ModalResult modal = computeModes(model, model.q0, 0.0, 1);
    CHECK(modal.rigid_modes == 1);
    CHECK(modal.rigid[0]);
    CHECK(modal.frequencies(0) == 0.0);
  }
}

TEST_CASE("modes: the cantilever under self-weight (thesis 8.1.2) about its sagged equilibrium", "[modes][timoshenko][spline_beam]") {
  const BeamProperties beam{15.0, 0.15};
  for (const std::string name : {"cantilever_timoshenko.yaml", "cantilever_spline_beam.yaml"}) {
    const Model model = compileModel(test::loadScene(name));
    const StaticResult eq = solveStatics(model, model.q0, 0.0);
    REQUIRE(eq.converged);
    const ModalResult modal = computeModes(model, eq.q, 0.0, 2);
    std::printf("[modes] %s about the sagged equilibrium: f1 = %.6f, %.6f Hz (EB %.6f Hz, thesis 0.9555 Hz), "
                "stiffness asymmetry %.2g, force residual %.2g N\n", name.c_str(), modal.frequencies(0), modal.frequencies(1),
                beam.eulerBernoulli(0), modal.stiffness_asymmetry, modal.force_residual);
    // A conservative system at equilibrium: K is symmetric once the constraint's geometric
    // stiffness is in; the sag of L/36 barely changes the frequency.
    CHECK(modal.stiffness_asymmetry < 1e-9);
    CHECK(std::abs(relativeError(modal.frequencies(0), beam.eulerBernoulli(0))) < 5e-3);
  }
}
