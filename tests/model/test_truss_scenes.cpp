// The super truss element and the condensed truss element against the full-member model of the
// same truss (thesis 8.2): the type 2 cantilever's static tip deflection under
// self-gravity and under end loads, and its first eigenfrequencies. Scene level only (no kernel is
// instantiated in this file).
//
// The super truss moves the tubes of the full-member model on a restricted set of shapes (the
// internal nodes follow the chord splines of the end sections), so by Rayleigh–Ritz it can only
// be stiffer: smaller static deflections, higher frequencies. How much stiffer is the measure
// of the reduction's error; the target is 5 %, the thesis' assumptions give about 30 %
// on this truss (the lacing's shear compliance is lost: docs/truss.md). The lower
// brackets (half the deflection, 1.5× the frequency) only catch a broken kernel.

#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <utility>

#include "cranesim/assembly/assembler.hpp"
#include "cranesim/solvers/statics.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

const char* const kFullMembers = "truss_type2_cantilever.yaml";
const char* const kSuperTruss = "truss_type2_super.yaml";
const char* const kCondensed = "truss_type2_condensed.yaml";

/// Static displacement and turn of the free end section (joint boom.end).
struct TipMotion {
  Vec3 offset, turn;
};

TipMotion tipMotion(const Scene& scene) {
  const Model model = compileModel(scene);
  const StaticResult eq = solveStatics(model, model.q0, 0.0);
  REQUIRE(eq.converged);
  return {test::jointOffset(model, eq.q, "boom.end"), test::jointTurn(model, eq.q, "boom.end")};
}

/// The lowest eigenfrequencies (Hz) of the scene linearised about its undeformed initial state
/// (all node rotation vectors zero there, so ∂F/∂q is the stiffness along dq), gravity off:
/// K and M restricted to the null space of the constraint Jacobian.
Eigen::VectorXd lowestFrequencies(Scene scene, int count) {
  scene.gravity = Vec3::Zero();
  const Model model = compileModel(scene);
  REQUIRE(model.nq == model.nv);
  for (const Node& node : model.nodes)
    if (node.hasRotation()) REQUIRE(model.q0.segment<3>(node.q + 3).norm() == 0.0);
  const Assembler assembler(model);
  const VecX q0 = model.q0, v0 = VecX::Zero(model.nv);
  MatX K(model.nv, model.nv);
  for (int j = 0; j < model.nv; ++j) {
    const double h = 1e-6;
    VecX qp = q0, qm = q0;
    qp(j) += h, qm(j) -= h;
    K.col(j) = (assembler.appliedForces(0.0, qp.data(), v0.data()) - assembler.appliedForces(0.0, qm.data(), v0.data())) / (2.0 * h);
  }
  const MatX M = MatX(assembler.massMatrix(0.0, q0.data()));
  const MatX G = MatX(assembler.constraints(0.0, q0.data(), v0.data()).G);
  const MatX N = Eigen::FullPivLU<MatX>(G).kernel();
  const MatX Kr = N.transpose() * K * N, Mr = N.transpose() * M * N;
  const Eigen::GeneralizedSelfAdjointEigenSolver<MatX> eig(0.5 * (Kr + Kr.transpose()), 0.5 * (Mr + Mr.transpose()));
  return eig.eigenvalues().head(count).cwiseSqrt() / (2.0 * std::numbers::pi);
}

/// The three lowest frequencies of the full-member model and of a reduced one, printed side by side.
std::pair<Eigen::VectorXd, Eigen::VectorXd> frequencies(const char* reduced, const char* label) {
  const Eigen::VectorXd a = lowestFrequencies(test::loadScene(kFullMembers), 3);
  const Eigen::VectorXd b = lowestFrequencies(test::loadScene(reduced), 3);
  for (int k = 0; k < 3; ++k)
    std::printf("type 2 cantilever mode %d: full-member %.4f Hz, %s %.4f Hz, relative difference %.2f %%\n", k + 1, a(k), label, b(k),
                100.0 * (b(k) - a(k)) / a(k));
  return {a, b};
}

}  // namespace

TEST_CASE("Super truss vs full-member model: static cantilever deflection", "[super_truss][scenes][statics]") {
  const Scene full = test::loadScene(kFullMembers), reduced = test::loadScene(kSuperTruss);
  SECTION("self-gravity") {
    const Vec3 a = tipMotion(full).offset, b = tipMotion(reduced).offset;
    std::printf("type 2 cantilever, self-gravity: tip z full-member %.5e m, super truss %.5e m, relative difference %.2f %%\n", a.z(),
                b.z(), 100.0 * (b.z() - a.z()) / a.z());
    CHECK(std::abs(b.z()) <= std::abs(a.z()) * (1.0 + 1e-6));
    CHECK(std::abs(b.z()) >= 0.5 * std::abs(a.z()));
  }
  SECTION("end force, vertical and lateral") {
    for (const Vec3& force : {Vec3(0.0, 0.0, -1e5), Vec3(0.0, 1e5, 0.0)}) {
      const Vec3 a = tipMotion(test::withEndLoad(full, force)).offset, b = tipMotion(test::withEndLoad(reduced, force)).offset;
      const int k = force.z() != 0.0 ? 2 : 1;
      std::printf("type 2 cantilever, end force along %c: tip full-member %.5e m, super truss %.5e m, relative difference %.2f %%\n",
                  "xyz"[k], a(k), b(k), 100.0 * (b(k) - a(k)) / a(k));
      CHECK(std::abs(b(k)) <= std::abs(a(k)) * (1.0 + 1e-6));
      CHECK(std::abs(b(k)) >= 0.5 * std::abs(a(k)));
    }
  }
}

TEST_CASE("Super truss vs full-member model: first eigenfrequencies", "[super_truss][scenes]") {
  const auto [a, b] = frequencies(kSuperTruss, "super truss");
  for (int k = 0; k < 3; ++k) {
    CHECK(b(k) >= a(k) * (1.0 - 1e-6));
    CHECK(b(k) <= 1.5 * a(k));
  }
}

TEST_CASE("Super truss vs full-member model: cost per DAE evaluation and of a released cantilever", "[super_truss][scenes][.timing]") {
  using Clock = std::chrono::steady_clock;
  for (const char* name : {kFullMembers, kSuperTruss, kCondensed}) {
    Scene scene = test::loadScene(name);
    const Model model = compileModel(scene);
    const Assembler assembler(model);
    std::vector<double> y(assembler.size(), 0.0), yp(assembler.size(), 0.0), res(assembler.size());
    std::vector<double> values(assembler.pattern().nonZeros());
    for (int i = 0; i < model.nq; ++i) y[i] = model.q0(i);
    const int n = 200;
    const auto t0 = Clock::now();
    for (int i = 0; i < n; ++i) assembler.residual(0.0, y.data(), yp.data(), res.data());
    const auto t1 = Clock::now();
    for (int i = 0; i < n / 10; ++i) assembler.jacobian(0.0, 1.0, y.data(), yp.data(), values.data());
    const auto t2 = Clock::now();
    scene.solver.t_end = 1.0;
    const test::SimulationRun run(scene);
    const SolverStatistics& s = run.outcome.statistics;
    std::printf("%s: %d unknowns, residual %.1f us, jacobian %.1f us; 1 s released under gravity: %.2f s wall, %ld steps, "
                "%ld residuals, %ld jacobians, tip z at 1 s %.5e m\n",
                name, assembler.size(), std::chrono::duration<double, std::micro>(t1 - t0).count() / n,
                std::chrono::duration<double, std::micro>(t2 - t1).count() / (n / 10), s.wall_time_s, s.steps,
                s.residual_evaluations, s.jacobian_evaluations, run.jointPositions("boom.end").back() - 0.0);
    CHECK(run.outcome.complete);
  }
}

// The condensed truss carries the full-member model's linear stiffness between its end sections
// exactly (condensed_truss.hpp): in the linear range the end-section response must agree to the
// geometric nonlinearity of the loads (≤ 1e-4 here); under gravity the load is spread by the
// element's mass interpolation instead of over the full model's nodes.
TEST_CASE("Condensed truss vs full-member model: static end-section response", "[condensed_truss][scenes][statics]") {
  const Scene full = test::loadScene(kFullMembers), reduced = test::loadScene(kCondensed);
  SECTION("self-gravity") {
    const Vec3 a = tipMotion(full).offset, b = tipMotion(reduced).offset;
    std::printf("type 2 cantilever, self-gravity: tip z full-member %.5e m, condensed %.5e m, relative difference %.3f %%\n", a.z(), b.z(),
                100.0 * (b.z() - a.z()) / a.z());
    CHECK(b.z() == Approx(a.z()).epsilon(1e-3));
  }
  SECTION("end forces along and across the axis") {
    for (const Vec3& force : {Vec3(1e5, 0.0, 0.0), Vec3(0.0, 1e4, 0.0), Vec3(0.0, 0.0, -1e4)}) {
      const Vec3 a = tipMotion(test::withEndLoad(full, force)).offset, b = tipMotion(test::withEndLoad(reduced, force)).offset;
      const int k = force.x() != 0.0 ? 0 : force.y() != 0.0 ? 1 : 2;
      std::printf("type 2 cantilever, end force along %c: tip full-member %.6e m, condensed %.6e m\n", "xyz"[k], a(k), b(k));
      CHECK(b(k) == Approx(a(k)).epsilon(1e-4));
    }
  }
  SECTION("end torque about the axis") {
    const Vec3 torque(1e5, 0.0, 0.0);
    const double a = tipMotion(test::withEndLoad(full, Vec3::Zero(), torque)).turn.x();
    const double b = tipMotion(test::withEndLoad(reduced, Vec3::Zero(), torque)).turn.x();
    std::printf("type 2 cantilever, end torque: twist full-member %.6e rad, condensed %.6e rad\n", a, b);
    CHECK(b == Approx(a).epsilon(1e-4));
  }
}

// Its mass rides on rigid cross-sections between the end sections: the bending frequencies are
// within 2 % (measured +1.7 / +1.8 %), the torsion frequency +9.7 %: without diaphragms inside the
// section the full-member box distorts in its torsion mode, which no reduction onto the end
// sections represents (the Guyan-consistent mass gives +8.4 %: docs/truss.md).
TEST_CASE("Condensed truss vs full-member model: first eigenfrequencies", "[condensed_truss][scenes]") {
  const auto [a, b] = frequencies(kCondensed, "condensed");
  for (int k = 0; k < 2; ++k) {
    CHECK(b(k) >= 0.99 * a(k));
    CHECK(b(k) <= 1.025 * a(k));
  }
  CHECK(b(2) >= 0.99 * a(2));
  CHECK(b(2) <= 1.12 * a(2));
}
