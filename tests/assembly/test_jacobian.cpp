// The assembled DAE Jacobian ∂F/∂y + cj ∂F/∂ẏ against central finite differences of the
// residual, at random states, for both formulations and every constraint type.

#include <catch2/catch.hpp>

#include <fmt/format.h>

#include <array>
#include <random>

#include "cranesim/assembly/assembler.hpp"
#include "cranesim/assembly/constraint_second_derivatives.hpp"
#include "cranesim/model/compile.hpp"
#include "scene_fixtures.hpp"
#include "spread_blocks.hpp"

using namespace cranesim;

namespace {

MatX denseJacobian(const Assembler& a, double t, double cj, const VecX& y, const VecX& yp) {
  VecX values(a.pattern().nonZeros());
  a.jacobian(t, cj, y.data(), yp.data(), values.data());
  MatX J = MatX::Zero(a.size(), a.size());
  const auto& cp = a.pattern().columnPointers();
  const auto& ri = a.pattern().rowIndices();
  for (int c = 0; c < a.size(); ++c)
    for (int k = cp[c]; k < cp[c + 1]; ++k) J(ri[k], c) = values[k];
  return J;
}

MatX finiteDifferenceJacobian(const Assembler& a, double t, double cj, const VecX& y, const VecX& yp) {
  const int n = a.size();
  MatX J(n, n);
  VecX rp(n), rm(n);
  for (int c = 0; c < n; ++c) {
    const double h = 1e-6;
    VecX y1 = y, y2 = y, yp1 = yp, yp2 = yp;
    y1(c) += h, y2(c) -= h, yp1(c) += cj * h, yp2(c) -= cj * h;
    a.residual(t, y1.data(), yp1.data(), rp.data());
    a.residual(t, y2.data(), yp2.data(), rm.data());
    J.col(c) = (rp - rm) / (2 * h);
  }
  return J;
}

const char* kScene = R"(
name: jacobian check
gravity: [0.3, -0.2, -9.81]
ground:
  joints:
    - {name: a, position: [0, 0, 1], rotation: {axis: [1, 2, 3], angle_deg: 20}}
    - {name: b, position: [2, 0, 0]}
bodies:
  - name: b1
    mass: 2.0
    centroid: [0.1, 0.2, -0.3]
    inertia: [0.5, 0.4, 0.3, 0.01, 0.02, -0.03]
    position: [0, 0, 1]
    rotation: {axis: [1, 2, 3], angle_deg: 20}
    joints:
      - {name: j, position: [0, 0, 0]}
      - {name: k, position: [0.5, 0.1, 0.2], rotation: {axis: [0, 1, 1], angle_deg: 30}}
  - name: b2
    mass: 1.0
    inertia: [0.2, 0.3, 0.4]
    position: [1, 1, 1]
    rotation: {rotation_vector: [0.3, -0.2, 2.5]}
    joints:
      - {name: j, position: [0.1, 0, 0]}
  - name: b3
    mass: 1.5
    inertia: [0.2, 0.3, 0.4]
    position: [2, 0, 0]
    joints:
      - {name: j, position: [0, 0, 0]}
constraints:
  - {name: c1, type: revolute, joints: [ground.a, b1.j], axis: z, drive: {type: cosine_step, from: 0, to: 1, t_start: 0, t_end: 2}}
  - {name: c2, type: spherical, joints: [b1.k, b2.j]}
  - {name: c3, type: prismatic, joints: [ground.b, b3.j], axis: x, drive: {type: tanh, from: 0, to: 1, t_start: 0, t_end: 2}}
  - {name: c4, type: distance, joints: [b2.j, b3.j], length: {type: ramp, value: 1.5, rate: 0.1}}
  - {name: c5, type: fixed, joints: [b1.j, b3.j]}
  - {name: c6, type: revolute, joints: [b2.j, b3.j], axis: x}
loads:
  - {name: l1, joint: b2.j, force: [1, 2, 3], torque: [0.1, 0.2, 0.3], frame: joint}
  - {name: l2, joint: b1.k, force: [3, 2, 1], torque: [0.3, 0.2, 0.1], frame: inertial}
solver: {formulation: FORM, t_end: 1}
)";

void checkJacobian(const std::string& formulation) {
  std::string yaml = kScene;
  yaml.replace(yaml.find("FORM"), 4, formulation);
  const Model model = test::loadYaml(yaml);
  const Assembler a(model);
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 3; ++trial) {
    VecX y(a.size()), yp(a.size());
    for (int k = 0; k < a.size(); ++k) y(k) = u(rng), yp(k) = u(rng);
    const double t = 0.7, cj = 13.0;
    const MatX J = denseJacobian(a, t, cj, y, yp);
    MatX Jfd = finiteDifferenceJacobian(a, t, cj, y, yp);
    if (formulation == "baumgarte") {
      // ∂Γ/∂q is left out of the analytic Jacobian (third derivatives); compare the rest.
      for (int r = a.lambdaOffset(); r < a.size(); ++r)
        for (int c = 0; c < model.nq; ++c) Jfd(r, c) = J(r, c);
    }
    INFO("max deviation " << (J - Jfd).cwiseAbs().maxCoeff() << " at scale " << Jfd.cwiseAbs().maxCoeff());
    CHECK((J - Jfd).cwiseAbs().maxCoeff() < 1e-6 * std::max(1.0, Jfd.cwiseAbs().maxCoeff()));
  }
}

}  // namespace

TEST_CASE("GGL Jacobian equals finite differences of the residual", "[jacobian]") { checkJacobian("ggl"); }

TEST_CASE("A sparse element's blocks assemble to the Jacobian: the massive reeved rope", "[jacobian][reeving][massive]") {
  // The spread blocks (both bodies free, turned) on a massive rope with a capstan: every cable's
  // block, summed where blocks share a block's node or a material coordinate.
  const Model model = test::spreadBlocks(0.96, true, "    fidelity: massive\n    elements_per_part: 3\n");
  const Assembler a(model);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 2; ++trial) {
    VecX y(a.size()), yp(a.size());
    for (int k = 0; k < a.size(); ++k) y(k) = (k < model.nq ? model.q0(k) + 1e-2 * u(rng) : 0.1 * u(rng)), yp(k) = 0.1 * u(rng);
    const double t = 1.3, cj = 13.0;
    const MatX J = denseJacobian(a, t, cj, y, yp), Jfd = finiteDifferenceJacobian(a, t, cj, y, yp);
    INFO("max deviation " << (J - Jfd).cwiseAbs().maxCoeff() << " at scale " << Jfd.cwiseAbs().maxCoeff());
    CHECK((J - Jfd).cwiseAbs().maxCoeff() < 1e-6 * Jfd.cwiseAbs().maxCoeff());
    Assembler statics(model);
    statics.setCoordinateJacobianOnly(true);
    const MatX Jq = denseJacobian(statics, t, cj, y, yp);
    CHECK((Jq.leftCols(model.nq) - J.leftCols(model.nq)).cwiseAbs().maxCoeff() == 0.0);
  }
}

TEST_CASE("A massive reeved rope's Jacobian grows with its cables, not with their square", "[jacobian][reeving][massive]") {
  // Four parts on the spread blocks: 4 and 16 cables per part, 4 times the cables. One dense
  // block of the rope's values would have about 16 times the non-zeros.
  const auto nonZeros = [](int cables) {
    const Model model = test::spreadBlocks(0.96, false, fmt::format("    fidelity: massive\n    elements_per_part: {}\n", cables));
    return Assembler(model).pattern().nonZeros();
  };
  const int few = nonZeros(4), many = nonZeros(16);
  INFO("non-zeros: " << few << " with 4 cables per part, " << many << " with 16");
  CHECK(many < 4.5 * few);
  CHECK(many > 2.5 * few);  // the cables, not the blocks and the winch, make most of them
}

TEST_CASE("Baumgarte Jacobian equals finite differences except for the documented ∂Γ/∂q term", "[jacobian]") {
  checkJacobian("baumgarte");
}

TEST_CASE("Constraint quantities Φ_q, Φ̇ and Γ equal finite differences", "[jacobian][constraints]") {
  std::string yaml = kScene;
  yaml.replace(yaml.find("FORM"), 4, "ggl");
  const Model model = test::loadYaml(yaml);
  const Assembler a(model);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 3; ++trial) {
    VecX q(model.nq), v(model.nv);
    for (int k = 0; k < model.nq; ++k) q(k) = u(rng);
    for (int k = 0; k < model.nv; ++k) v(k) = u(rng);
    const double t = 0.7, h = 1e-6;
    const ConstraintState C = a.constraints(t, q.data(), v.data());
    MatX Phi_q_fd(model.m, model.nq);
    for (int k = 0; k < model.nq; ++k) {
      VecX qp = q, qm = q;
      qp(k) += h, qm(k) -= h;
      Phi_q_fd.col(k) = (a.constraints(t, qp.data(), v.data()).phi - a.constraints(t, qm.data(), v.data()).phi) / (2.0 * h);
    }
    // Along the motion: q(ε) = q + ε q̇, t + ε; Φ̇ = dΦ/dε, Γ = d(G v + Φ_t)/dε at fixed v
    // (Φ̈ = G v̇ + Γ).
    const VecX qdot = a.coordinateRates(q.data(), v.data());
    const VecX qp = q + h * qdot, qm = q - h * qdot;
    const ConstraintState Cp = a.constraints(t + h, qp.data(), v.data()), Cm = a.constraints(t - h, qm.data(), v.data());
    const VecX phi_dot_fd = (Cp.phi - Cm.phi) / (2.0 * h);
    const VecX gamma_fd = (Cp.G * v + Cp.phi_t - Cm.G * v - Cm.phi_t) / (2.0 * h);
    INFO("Φ_q " << (MatX(C.Phi_q) - Phi_q_fd).cwiseAbs().maxCoeff() << ", Φ̇ " << (C.phi_dot - phi_dot_fd).cwiseAbs().maxCoeff()
                << ", Γ " << (C.gamma - gamma_fd).cwiseAbs().maxCoeff() << " (scale " << gamma_fd.cwiseAbs().maxCoeff() << ")");
    CHECK((MatX(C.Phi_q) - Phi_q_fd).cwiseAbs().maxCoeff() < 1e-8);
    CHECK((C.phi_dot - phi_dot_fd).cwiseAbs().maxCoeff() < 1e-8);
    CHECK((C.gamma - gamma_fd).cwiseAbs().maxCoeff() < 1e-7 * std::max(1.0, gamma_fd.cwiseAbs().maxCoeff()));
  }
}


namespace {

/// The worst deviation of ConstraintSecondDerivatives from nested forward AD over all entries of
/// one constraint and over its contractions with random weights and vectors, and the largest
/// reference entry.
std::pair<double, double> closedFormDeviation(const Model& model, const Constraint& c, const VecX& q, double t) {
  const ConstraintSecondDerivatives closed(model, c, q.data(), t);
  const ConstraintDerivatives<ConstraintQDual> nested = evaluateConstraint<ConstraintQDual>(model, c, q.data(), t);
  double worst = 0.0, scale = 0.0;
  const auto compare = [&](double x, double reference) {
    worst = std::max(worst, std::abs(x - reference));
    scale = std::max(scale, std::abs(reference));
  };
  using Mat13 = ConstraintSecondDerivatives::Mat13;
  std::array<Mat13, kMaxConstraintRows> reference;  // ∂G_ij/∂[q, t]_k
  for (int i = 0; i < c.rows; ++i) {
    for (int j = 0; j < kConstraintDirections; ++j)
      reference[i].row(j) = nested.G(i, j).derivatives().transpose();
    const Mat13 dG = closed.secondDerivative(i);
    compare(closed.phi(i), nested.phi(i).value());
    for (int k = 0; k < 12; ++k) compare(closed.phi_q(i, k), nested.phi(i).derivatives()(k));
    for (int j = 0; j < kConstraintDirections; ++j) {
      compare(closed.G(i, j), nested.G(i, j).value());
      for (int k = 0; k < kConstraintDirections; ++k) compare(dG(j, k), reference[i](j, k));
    }
  }
  // The contractions the DAE Jacobian takes, with random weights and vectors.
  std::mt19937 rng(c.rows + 7 * c.joint1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  ConstraintSecondDerivatives::Vec13 x, z;
  double w[kMaxConstraintRows];
  for (int k = 0; k < kConstraintDirections; ++k) x(k) = u(rng), z(k) = u(rng);
  for (double& wi : w) wi = u(rng);
  Mat13 weighted = Mat13::Zero();
  for (int i = 0; i < c.rows; ++i) weighted += w[i] * reference[i];
  const Mat13 closed_weighted = closed.weighted(w);
  const ConstraintSecondDerivatives::Rows13 directions = closed.directionContractions(x),
                                            coordinates = closed.coordinateContractions(z);
  for (int j = 0; j < kConstraintDirections; ++j)
    for (int k = 0; k < kConstraintDirections; ++k) compare(closed_weighted(j, k), weighted(j, k));
  for (int i = 0; i < c.rows; ++i) {
    const Eigen::Matrix<double, 1, kConstraintDirections> along_directions = x.transpose() * reference[i];
    const ConstraintSecondDerivatives::Vec13 along_coordinates = reference[i] * z;
    for (int k = 0; k < kConstraintDirections; ++k) {
      compare(directions(i, k), along_directions(k));
      compare(coordinates(i, k), along_coordinates(k));
    }
  }
  return {worst, scale};
}

}  // namespace

TEST_CASE("Closed-form constraint second derivatives equal nested forward AD of the equations", "[jacobian][constraints]") {
  std::string yaml = kScene;
  yaml.replace(yaml.find("FORM"), 4, "ggl");
  const Model model = test::loadYaml(yaml);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 4; ++trial) {
    VecX q(model.nq);
    for (int k = 0; k < model.nq; ++k) q(k) = 2.0 * u(rng);
    const double t = 0.3 + 0.4 * trial;  // inside and after the drives' transitions
    for (const Constraint& c : model.constraints) {
      const auto [worst, scale] = closedFormDeviation(model, c, q, t);
      INFO(c.name << ": worst deviation " << worst << " at scale " << scale);
      CHECK(scale > 0.1);
      CHECK(worst < 1e-13 * scale);
    }
  }
}

TEST_CASE("Closed-form constraint second derivatives hold on the crane's joints, rope ends on point nodes included",
          "[jacobian][constraints]") {
  const Model model = compileModel(test::loadScene("crane.yaml"));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  VecX q = model.q0;
  for (int k = 0; k < model.nq; ++k) q(k) += 0.05 * u(rng);  // off the drawn state: no term vanishes by symmetry
  int point_sides = 0;
  for (const Constraint& c : model.constraints) {
    for (const int joint : {c.joint1, c.joint2}) {
      const int node = model.joints[joint].node;
      point_sides += node >= 0 && !model.nodes[node].hasRotation();
    }
    const auto [worst, scale] = closedFormDeviation(model, c, q, 0.0);
    INFO(c.name << ": worst deviation " << worst << " at scale " << scale);
    CHECK(worst < 1e-13 * scale);
  }
  CHECK(point_sides >= 8);
}
