// Energy books (element.hpp, WorkTerms): every element's equations give
// dqᵀ(M a + F) = dE/dt − P_time + P_diss, checked for each element kind against a difference
// quotient of its energies along a motion; the winch's power and the damping power of a rope
// against hand computations; and the recorded balance of runs with reeled ropes.

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "cranesim/elements/spline_rope.hpp"
#include "cranesim/solvers/equilibrium_path.hpp"
#include "random_states.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

/// One element's books at (q, dq, a, t): dqᵀ(M a + F), dE/dt along q + τ q̇, dq + τ a, t + τ
/// (fourth-order central difference with step h), P_time and P_diss.
struct Books {
  double virtual_power = 0.0, energy_rate = 0.0, time_power = 0.0, dissipated = 0.0;
  double mismatch() const { return virtual_power - (energy_rate - time_power + dissipated); }
};

Books elementBooks(const Element& e, const Model& model, const VecX& q, const VecX& qdot, const VecX& v, const VecX& a,
                   double t, double h) {
  const auto energy = [&](double tau) {
    const VecX qt = q + tau * qdot, vt = v + tau * a;
    const ElementInput in{qt.data(), vt.data(), nullptr, t + tau, model.gravity};
    return e.kineticEnergy(in) + e.potentialEnergy(in);
  };
  Books b;
  const ElementInput in{q.data(), v.data(), a.data(), t, model.gravity};
  VecX r(e.size());
  e.residual(in, r.data());
  for (int k = 0; k < e.size(); ++k) b.virtual_power += v(e.velocityIndices()[k]) * r(k);
  b.energy_rate = (8.0 * (energy(h) - energy(-h)) - (energy(2.0 * h) - energy(-2.0 * h))) / (12.0 * h);
  b.time_power = e.explicitTimePower(in);
  b.dissipated = e.dissipatedPower(in);
  return b;
}

/// The scene's equilibrium at t, disturbed by δ in every coordinate, with random velocities
/// and accelerations; the books of every element there. Returns the worst mismatch relative
/// to the element's largest term, and sums the elements' P_time and P_diss.
struct SceneBooks {
  double worst = 0.0, time_power = 0.0, dissipated = 0.0, min_dissipated = 0.0;
};
SceneBooks sceneBooks(const Scene& scene, double t, double delta, double speed, double h) {
  const Model model = compileModel(scene);
  const Assembler assembler(model);
  const StaticResult eq = solveEquilibrium(scene, model, t);
  REQUIRE(eq.converged);
  test::Rng rng(7);
  VecX q = eq.q, v(model.nv), a(model.nv);
  for (int k = 0; k < model.nq; ++k) q(k) += delta * rng();
  for (int k = 0; k < model.nv; ++k) v(k) = speed * rng(), a(k) = speed * rng();
  const VecX qdot = assembler.coordinateRates(q.data(), v.data());
  SceneBooks out;
  for (const auto& e : model.elements) {
    const Books b = elementBooks(*e, model, q, qdot, v, a, t, h);
    const double scale = std::abs(b.virtual_power) + std::abs(b.energy_rate) + std::abs(b.time_power) + b.dissipated;
    out.worst = std::max(out.worst, std::abs(b.mismatch()) / scale);
    out.time_power += b.time_power;
    out.dissipated += b.dissipated;
    out.min_dissipated = std::min(out.min_dissipated, b.dissipated);
  }
  return out;
}

}  // namespace

TEST_CASE("Every element kind keeps the books: dqᵀ(M a + F) = dE/dt − P_time + P_diss", "[energy][elements]") {
  struct Case {
    const char* config;
    double t, eta;
    bool reeled, cables = false;  // cables: every rope as two-node cables (element: cable)
  };
  // The crane while both winches reel and the slewing drive turns: super truss booms, the
  // strut-tie stay (with smoothing), ropes, rigid bodies; the beams and trusses of the
  // cantilever scenes; a reeved rope over lossy sheaves on a hook block, massless and massive;
  // every one damped.
  for (const Case c : {Case{"crane_combined.yaml", 25.0, 1e-2, true}, Case{"rope_reeling.yaml", 5.0, 1e-2, true},
                       Case{"cantilever_timoshenko.yaml", 0.0, 1e-2, false},
                       Case{"cantilever_spline_beam.yaml", 0.0, 1e-2, false},
                       Case{"truss_type2_condensed.yaml", 0.0, 1e-2, false},
                       Case{"truss_type2_cantilever.yaml", 0.0, 1e-2, false},
                       Case{"crane_combined.yaml", 25.0, 1e-2, true, true}, Case{"rope_reeling.yaml", 5.0, 1e-2, true, true},
                       Case{"hook_block.yaml", 5.0, 1e-2, true}, Case{"hook_block_massive.yaml", 5.0, 1e-2, true}}) {
    Scene scene = test::loadScene(c.config);
    for (MemberSpec& m : scene.members) {
      m.damping = c.eta;
      if (m.type == MemberType::StrutTie) m.smoothing = 1e-3;
      if (c.cables && m.type == MemberType::Rope) m.rope_element = RopeElement::Cable, m.transverse_damping = 0.0;
    }
    const SceneBooks b = sceneBooks(scene, c.t, 1e-6, 0.1, 1e-4);
    INFO(c.config << (c.cables ? " (cables)" : "") << ": worst |dqᵀr − (dE/dt − P_time + P_diss)| / scale " << b.worst << "; P_time " << b.time_power
                  << " W, P_diss " << b.dissipated << " W");
    // A term missing or of the wrong sign shows as ≥ 1e-2. The difference quotient is only
    // first-order accurate where a rope is nearly slack (max(ε, 0)² has a kink in its second
    // derivative): 1.5e-6 measured on the crane's luffing rope, 1e-9 elsewhere.
    CHECK(b.worst < 1e-5);
    CHECK(b.min_dissipated >= 0.0);
    CHECK(b.dissipated > 0.0);
    if (c.reeled) CHECK(b.time_power != 0.0);
  }
}

namespace {

/// One straight element of a steel rope along e, uniformly stretched by ε, its top node (the
/// reel point) at the origin and at rest; length L(t) = L0 + c t.
struct StraightRope {
  double L0 = 5.0, rate = -0.5, eps = 3e-4, t = 2.0;
  Vec3 e = Vec3(0.0, 0.0, -1.0), gravity = Vec3(0.0, 0.0, -9.81);
  SplineRopeKernel kernel;
  StraightRope() {
    kernel.total_length = Profile(RampProfile{L0, rate, 0.0});
    kernel.section = Section::circular(0.01, 0.0, 0.3);
    kernel.material.density = 7800.0;
    kernel.material.youngs_modulus = 1e11;
  }
  double L() const { return L0 + rate * t; }
  double rhoA() const { return kernel.material.density * kernel.section.area; }
  double EA() const { return kernel.material.youngs_modulus * kernel.section.area; }
  SplineRopeKernel::Q<double> q() const {
    const double stretch = 1.0 + eps;
    SplineRopeKernel::Q<double> out;
    out << Vec3::Zero(), stretch * e, stretch * L() * e, stretch * e;
    return out;
  }
  /// The bottom node moving with velocity u, the slopes held.
  SplineRopeKernel::Q<double> v(const Vec3& u) const {
    SplineRopeKernel::Q<double> out = SplineRopeKernel::Q<double>::Zero();
    out.segment<3>(6) = u;
    return out;
  }
};

}  // namespace

TEST_CASE("A straight rope reeled at constant rate: the winch's power by hand", "[energy][rope]") {
  const StraightRope r;
  const Vec3 u(0.3, -0.2, 0.4);
  // L̇ ∂(T + V)/∂L at fixed nodes, integrated by hand over the cubic Hermite functions:
  // kinetic ½ρA|u|² ∫H₂² = ½ρA|u|² 13/35 (H₂ the bottom node's); strain ½EAε² − EAε(1 + ε), the
  // material brought in unstrained and the tension N = EAε on the stretched reeling speed
  // (1 + ε)L̇; gravity −ρA g·(r¹ + r²)/2, material added along the chord.
  const auto q = r.q();
  const Vec3 r1 = q.segment<3>(0), r2 = q.segment<3>(6);
  const double N = r.EA() * r.eps;
  const double hand = r.rate * (0.5 * r.rhoA() * u.squaredNorm() * 13.0 / 35.0 + 0.5 * N * r.eps - N * (1.0 + r.eps) -
                                r.rhoA() * r.gravity.dot(0.5 * (r1 + r2)));
  const double power = r.kernel.explicitTimePower(q, r.v(u), r.t, r.gravity);
  INFO("winch power " << power << " W, by hand " << hand << " W (tension " << N << " N)");
  CHECK(power == Approx(hand).epsilon(1e-12));
  // The same from the kernel's energies, by a central difference in t.
  const double h = 1e-6;
  const auto energy = [&](double t) {
    return r.kernel.kineticEnergy(q, r.v(u), t) + r.kernel.potentialEnergy(q, t, r.gravity);
  };
  CHECK(power == Approx((energy(r.t + h) - energy(r.t - h)) / (2.0 * h)).epsilon(1e-9));
}

TEST_CASE("A stretched damped rope dissipates EA η ε̇² per unit length, never less than 0", "[energy][rope]") {
  StraightRope r;
  r.kernel.total_length = Profile(ConstantProfile{r.L0});
  r.kernel.damping = 0.01;
  r.t = 0.0;
  const double strain_rate = 0.02;  // the bottom node and the slopes moving as uniform stretching
  SplineRopeKernel::Q<double> v = SplineRopeKernel::Q<double>::Zero();
  v.segment<3>(3) = strain_rate * r.e;
  v.segment<3>(6) = strain_rate * r.L0 * r.e;
  v.segment<3>(9) = strain_rate * r.e;
  const double eta = r.kernel.damping, exact = r.EA() * eta * strain_rate * strain_rate * r.L0;
  CHECK(r.kernel.dissipatedPower(r.q(), v, 0.0, r.gravity) == Approx(exact).epsilon(1e-12));
  CHECK(r.kernel.dissipatedPower(r.q(), SplineRopeKernel::Q<double>(-v), 0.0, r.gravity) == Approx(exact).epsilon(1e-12));
  // Shortening faster than ε/η: the damper slackens the rope and takes the elastic power EAε|ε̇|.
  const double fast = 10.0;
  const double slack = r.EA() * r.eps * fast * strain_rate * r.L0;
  CHECK(r.kernel.dissipatedPower(r.q(), SplineRopeKernel::Q<double>(-fast * v), 0.0, r.gravity) ==
        Approx(slack).epsilon(1e-12));
}

TEST_CASE("A ball reeled up on a damped rope: the recorded balance closes", "[energy][rope][scenes]") {
  const bool cable = GENERATE(false, true);  // the spline rope, and the same rope as a two-node cable
  Scene scene = test::loadScene("rope_reeling.yaml");
  if (cable) scene.members[0].rope_element = RopeElement::Cable;
  scene.solver.rtol = 1e-8;
  scene.solver.atol = AbsoluteTolerance::uniform(1e-10);
  scene.solver.t_end = 4.0;  // at rest, accelerating, reeling at 0.5 m/s
  const test::SimulationRun run(scene);
  REQUIRE(run.outcome.complete);
  const auto& winch = run.recorder.winchWork();
  INFO((cable ? "cable: " : "spline rope: ") << "balance drift " << run.recorder.relativeBalanceDrift() << " of " << run.recorder.energyScale()
                        << " J; winch work " << winch.back() << " J, dissipated " << run.recorder.dissipated().back()
                        << " J; steps " << run.outcome.statistics.steps);
  CHECK(run.recorder.relativeBalanceDrift() < 1e-6);
  CHECK(winch.back() > 0.0);  // the winch lifts the ball
}

TEST_CASE("A free-falling rope reeled out: the reeled mass' energy is booked exactly", "[energy][rope][scenes]") {
  // Nothing holds the ball and the rope: they fall together, the rope straight and slack while
  // it is paid out, every point with q̈ = g. At fixed nodes the new material comes in with the
  // element's velocity g t and its potential −g·(c0 + ½ g t²), c0 the rope's centroid at rest:
  // per metre ½ g²t² − g·c0 − ½ g²t², so the winch's work is −ρA ΔL g·c0 exactly.
  Scene scene = test::loadScene("rope_reeling.yaml");
  scene.constraints.erase(scene.constraints.begin());  // the top
  const double L0 = 10.0, rate = 0.5;
  scene.members[0].length = Profile(RampProfile{L0, rate, 0.0});
  scene.members[0].end = Vec3(0.0, 0.0, -L0);
  scene.bodies[0].position = Vec3(0.0, 0.0, -L0);
  scene.solver.start_from_equilibrium = false;
  scene.solver.rtol = 1e-8;
  scene.solver.atol = AbsoluteTolerance::uniform(1e-10);
  scene.solver.t_end = 2.0;
  const test::SimulationRun run(scene);
  REQUIRE(run.outcome.complete);
  const double rhoA = 7800.0 * std::numbers::pi * 1e-4, t = scene.solver.t_end;
  const Vec3 c0(0.0, 0.0, -L0 / 2.0);
  const double exact = -rhoA * rate * t * scene.gravity.dot(c0);
  const auto& ball = run.jointPositions("ball.origin");
  const double fall = ball[3 * (run.recorder.samples() - 1) + 2] - ball[2];
  INFO("winch work " << run.recorder.winchWork().back() << " J, exact " << exact << " J; ball fell " << fall
                     << " m; balance drift " << run.recorder.relativeBalanceDrift());
  CHECK(fall == Approx(-0.5 * 9.81 * t * t).epsilon(1e-8));
  CHECK(run.recorder.winchWork().back() == Approx(exact).epsilon(1e-8));
  CHECK(run.recorder.relativeBalanceDrift() < 1e-8);
}

TEST_CASE("A rope reeled steadily at constant stretch: damping adds no tension and dissipates nothing", "[energy][rope]") {
  // The bottom node follows the reeling, (1 + ε) L̇ e, the top (the reel point) and the slopes
  // held: the material keeps its stretch, so the Kelvin–Voigt rate is 0 although L changes.
  StraightRope undamped, damped;
  damped.kernel.damping = 1e-3;
  SplineRopeKernel::Q<double> v = SplineRopeKernel::Q<double>::Zero();
  v.segment<3>(6) = (1.0 + undamped.eps) * undamped.rate * undamped.e;
  const auto q = undamped.q();
  const auto F0 = undamped.kernel.force<double>(q, v, undamped.t, undamped.gravity);
  const auto F = damped.kernel.force<double>(q, v, damped.t, damped.gravity);
  const double N = undamped.EA() * undamped.eps;
  INFO("tension " << N << " N; damped − undamped nodal forces " << (F - F0).norm() << " N (a rate L̇/L would add "
                  << undamped.EA() * damped.kernel.damping * std::abs(undamped.rate) / undamped.L() << " N)");
  CHECK((F - F0).norm() < 1e-9 * N);
  CHECK(damped.kernel.dissipatedPower(q, v, damped.t, damped.gravity) == Approx(0.0).margin(1e-9 * N));
  // The winch's power is the undamped one, and the hand computation's.
  CHECK(damped.kernel.explicitTimePower(q, v, damped.t, damped.gravity) ==
        Approx(undamped.kernel.explicitTimePower(q, v, undamped.t, undamped.gravity)).epsilon(1e-12));
}

TEST_CASE("A damped rope reeled in from rest at a constant rate: the jump of L̇ is a restart, not a failure",
          "[energy][rope][scenes]") {
  // The material's stretch rate, and with it the damping tension, jumps by η L̇/L where the ramp
  // starts; the restart there takes the right-sided rate for its accelerations.
  Scene scene = test::loadScene("rope_reeling.yaml");
  scene.members[0].length = Profile(RampProfile{10.0, -0.5, 1.0});
  scene.solver.rtol = 1e-7;
  scene.solver.atol = AbsoluteTolerance::uniform(1e-9);
  scene.solver.t_end = 1.5;
  const test::SimulationRun run(scene);
  INFO(run.outcome.message << "; steps " << run.outcome.statistics.steps << ", balance drift "
                           << run.recorder.relativeBalanceDrift());
  REQUIRE(run.outcome.complete);
  CHECK(run.recorder.relativeBalanceDrift() < 1e-4);
}
