// SparseLU (math/sparse_lu.hpp): when it may reuse the old pivots. A DAE Jacobian of heavy
// masses and constraints has min|u_ii| / max|u_ii| far below ε^(2/3) whatever the pivots; its
// refactorisations must be kept (one pivoted factorisation for a run of Jacobians), while a
// matrix whose old pivots have become unstable must be pivoted anew. Both must solve accurately.
#include <catch2/catch.hpp>

#include <Eigen/Sparse>

#include <cmath>
#include <random>
#include <vector>

#include "cranesim/math/sparse_lu.hpp"

namespace {

using Sparse = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

/// ‖A x − b‖∞ / (‖A‖∞ ‖x‖∞) after factorising A and solving for b.
double relativeResidual(cranesim::SparseLU& lu, Sparse A, const Eigen::VectorXd& b) {
  A.makeCompressed();
  REQUIRE(lu.factorise(static_cast<int>(A.rows()), A.outerIndexPtr(), A.innerIndexPtr(), A.valuePtr()));
  Eigen::VectorXd x = b;
  lu.solve(x.data());
  double norm_A = 0.0;
  for (int i = 0; i < A.rows(); ++i) norm_A = std::max(norm_A, Eigen::RowVectorXd(A.row(i)).cwiseAbs().sum());
  return (A * x - b).cwiseAbs().maxCoeff() / (norm_A * x.cwiseAbs().maxCoeff());
}

/// [c M + K, Gᵀ; G, 0]: masses 10²…10⁷, a stiffness coupling neighbours, two constraints on all.
Sparse saddlePoint(double c, double stiffness, std::mt19937& rng) {
  const int n = 6, m = 2;
  std::uniform_real_distribution<double> u(0.5, 1.5);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, c * std::pow(10.0, 2 + i) + 2.0 * stiffness);
    if (i + 1 < n) t.emplace_back(i, i + 1, -stiffness), t.emplace_back(i + 1, i, -stiffness);
  }
  for (int k = 0; k < m; ++k)
    for (int i = 0; i < n; ++i) {
      const double g = (k == 0 ? 1.0 : (i % 2 ? -1.0 : 1.0)) * u(rng);
      t.emplace_back(n + k, i, g), t.emplace_back(i, n + k, g);
    }
  Sparse A(n + m, n + m);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

}  // namespace

TEST_CASE("SparseLU keeps the pivots of a badly scaled saddle-point matrix through its refactorisations", "[sparse_lu]") {
  // c = c_j² of steps 10⁻⁵…10⁻⁶ s: the constraints' Schur pivots ~ 1/(c · 10²) ≤ 10⁻¹², so
  // min|u_ii| / max|u_ii| is far below ε^(2/3) ≈ 3.7e-11 at every factorisation.
  std::mt19937 rng(7);
  cranesim::SparseLU lu;
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(8, 1.0, 8.0);
  for (int step = 0; step < 20; ++step) {
    const double c = std::pow(10.0, 10.0 + std::sin(0.7 * step));
    CHECK(relativeResidual(lu, saddlePoint(c, 1e6 * (1.0 + 0.1 * step), rng), b) < 1e-13);
  }
  CHECK(lu.pivotedFactorisations() == 1);
}

TEST_CASE("SparseLU pivots anew when the old pivots have become unstable", "[sparse_lu]") {
  // [a 1; 1 1]: pivoted on a = 2, then refactorised on a = 1e-14, whose diagonal pivot would
  // grow U's second column to 10¹⁴ (relative residual ~1e-2 on the old pivots).
  cranesim::SparseLU lu;
  const Eigen::VectorXd b(Eigen::Vector2d(1.0, 2.0));
  const auto matrix = [](double a) {
    Sparse A(2, 2);
    std::vector<Eigen::Triplet<double>> t{{0, 0, a}, {1, 0, 1.0}, {0, 1, 1.0}, {1, 1, 1.0}};
    A.setFromTriplets(t.begin(), t.end());
    return A;
  };
  CHECK(relativeResidual(lu, matrix(2.0), b) < 1e-14);
  CHECK(lu.pivotedFactorisations() == 1);
  CHECK(relativeResidual(lu, matrix(1e-14), b) < 1e-14);
  CHECK(lu.pivotedFactorisations() == 2);
  CHECK(relativeResidual(lu, matrix(1e-14 * 1.01), b) < 1e-14);  // the new pivots serve again
  CHECK(lu.pivotedFactorisations() == 2);
}
