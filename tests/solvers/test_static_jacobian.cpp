// The statics' Jacobian (Element::coordinateJacobian, the assembler's coordinate-only mode): for
// every element kind, ∂r/∂q equals the q columns of the full element Jacobian — at rest, where
// kernels with a force at rest (Timoshenko beam, super truss) differentiate that instead, and
// in motion — and the equilibrium system's Jacobian matches central differences of its residual.

#include <catch2/catch.hpp>

#include "cranesim/solvers/equilibrium_system.hpp"
#include "random_states.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

/// q0 with every coordinate moved by up to `scale` (rotation vectors and slopes alike).
VecX perturbed(const Model& model, test::Rng& rng, double scale) {
  VecX q = model.q0;
  for (int k = 0; k < model.nq; ++k) q(k) += scale * rng();
  return q;
}

VecX randomVector(int n, test::Rng& rng) {
  VecX v(n);
  for (int k = 0; k < n; ++k) v(k) = rng();
  return v;
}

/// max |coordinateJacobian − q columns of jacobian| / max |jacobian's q columns| over the elements.
double worstElementMismatch(const Model& model, const VecX& q, const VecX& v, const VecX& a) {
  const ElementInput in{q.data(), v.data(), a.data(), 0.3, model.gravity};
  double worst = 0.0;
  for (const auto& e : model.elements) {
    const int rows = e->size(), nq = static_cast<int>(e->coordinateIndices().size());
    MatX full(rows, nq + rows), coordinates(rows, nq);
    e->jacobian(in, 0.0, full.data());
    e->coordinateJacobian(in, coordinates.data());
    const double scale = std::max(1.0, full.leftCols(nq).cwiseAbs().maxCoeff());
    worst = std::max(worst, (coordinates - full.leftCols(nq)).cwiseAbs().maxCoeff() / scale);
  }
  return worst;
}

}  // namespace

TEST_CASE("Statics' Jacobian: every element's ∂r/∂q equals the full Jacobian's q columns", "[statics][jacobian]") {
  const char* scene = GENERATE("crane.yaml", "crane_condensed.yaml", "cantilever_timoshenko.yaml",
                               "cantilever_spline_beam.yaml", "truss_type2_cantilever.yaml");
  const Model model = compileModel(test::loadScene(scene));
  test::Rng rng(7);
  INFO(scene);
  for (int trial = 0; trial < 3; ++trial) {
    const VecX q = perturbed(model, rng, 1e-2);
    const VecX rest = VecX::Zero(model.nv);
    CHECK(worstElementMismatch(model, q, rest, rest) < 1e-11);
    CHECK(worstElementMismatch(model, q, randomVector(model.nv, rng), randomVector(model.nv, rng)) < 1e-11);
  }
}

TEST_CASE("Statics' Jacobian: the equilibrium system's Jacobian against central differences", "[statics][jacobian]") {
  const char* scene = GENERATE("crane.yaml", "crane_condensed.yaml", "cantilever_timoshenko.yaml");
  const Model model = compileModel(test::loadScene(scene));
  EquilibriumSystem system(model, 0.0);
  test::Rng rng(11);
  VecX x(system.size());
  x << perturbed(model, rng, 1e-3), 1e3 * randomVector(model.m, rng);
  const MatX J = MatX(system.jacobian(x));
  MatX fd(system.size(), system.size());
  for (int c = 0; c < system.size(); ++c) {
    const double h = 1e-6 * std::max(1.0, std::abs(x(c)));
    VecX up = x, down = x;
    up(c) += h, down(c) -= h;
    fd.col(c) = (system.residual(up) - system.residual(down)) / (2.0 * h);
  }
  INFO(scene);
  CHECK((J - fd).cwiseAbs().maxCoeff() < 1e-6 * J.cwiseAbs().maxCoeff());
}
