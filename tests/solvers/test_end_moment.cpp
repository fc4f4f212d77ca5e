// Thesis 8.1.1: a cantilever bent by an end moment M = K·2πEI/L (8-1), solved with
// solveStatics for 1, 3, 5, 10 segments and K from 0.05 to 1, against the exact circular arc
// (tests/fixtures/end_moment_arc.hpp; numbers in benchmarks/README.md, "Static bending").
//
// Timoshenko beam: the moment is constant along the beam, so every element carries it exactly:
// its end sections turn by Δθ = κL/n and its chord keeps the length L/n (no axial force). The
// nodes therefore lie on the regular polygon with sides L/n, and the tip is the arc's tip
// scaled by (Δθ/2)/sin(Δθ/2) — an error of ≈ Δθ²/24, second order in 1/n — while the tip
// rotation is exact. Cubic spline beam: a cubic Hermite curve does not bend at constant
// curvature, so the arc is not exact; the error is of fourth order in the bend per segment,
// and beyond 90° per segment (the Cardan limit, 3-65) the element cannot represent the shape.

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include "cranesim/solvers/statics.hpp"
#include "end_moment_arc.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

struct BentBeam {
  double K = 0.0;
  double bend_per_segment = 0.0;  // Δθ = κL/n, rad
  test::EndMomentArc arc;
  Frame tip;
  test::ArcError error;
};

/// Equilibria for ascending K, each solved from the previous one (K continuation).
std::vector<BentBeam> bendSweep(const std::string& type, int segments, const std::vector<double>& ks) {
  std::vector<BentBeam> out;
  VecX q;
  for (double K : ks) {
    const Scene scene = test::endMomentScene(test::configPath("end_moment_" + type + ".yaml"), segments, K);
    const Model model = compileModel(scene);
    const StaticResult eq = solveStatics(model, q.size() ? q : model.q0, 0.0);
    INFO(type << ", " << segments << " segments, K = " << K << ": " << eq.message);
    REQUIRE(eq.converged);
    q = eq.q;
    BentBeam b;
    b.K = K;
    b.arc = test::endMomentArc(scene);
    b.bend_per_segment = b.arc.curvature() * b.arc.L / segments;
    b.tip = model.jointFrame(q.data(), model.findJoint("beam.end"));
    b.error = test::arcError(model, q, b.arc);
    out.push_back(b);
  }
  return out;
}

constexpr double kDeg = std::numbers::pi / 180.0;

/// Where n Timoshenko elements put the tip: the arc's tip scaled by (Δθ/2)/sin(Δθ/2).
Vec3 chordPolygonTip(const test::EndMomentArc& arc, int n) {
  const double half = arc.curvature() * arc.L / n / 2.0;
  return half / std::sin(half) * arc.tip();
}

}  // namespace

TEST_CASE("Timoshenko beam bent by an end moment: exact rotations, nodes on the chord polygon",
          "[scenes][timoshenko][statics][end_moment]") {
  // Up to 180° per element (the relative rotation of its ends is a logarithm) and K = 0.5: the
  // polygon identity does not depend on K, and K = 1 costs 250–320 Newton iterations
  // (benchmarks/README.md).
  const std::vector<double> all{0.05, 0.1, 0.25, 0.5};
  for (int n : {1, 3, 5, 10}) {
    std::vector<double> ks;
    for (double K : all)
      if (360.0 * K / n < 180.0) ks.push_back(K);
    for (const BentBeam& b : bendSweep("timoshenko", n, ks)) {
      INFO(n << " segments, K = " << b.K << ": tip error " << b.error.tip << " L, rotation error "
             << b.error.rotation << " rad");
      CHECK(b.error.rotation < 1e-9);
      CHECK((b.tip.r - chordPolygonTip(b.arc, n)).norm() < 1e-9 * b.arc.L);
      // The thesis' advice, at most 15° per segment, keeps the tip within 0.3 % of L.
      if (b.bend_per_segment <= 15.0 * kDeg + 1e-12) CHECK(b.error.tip < 3e-3);
    }
  }
}

TEST_CASE("Cubic spline beam bent by an end moment: fourth order, more accurate than Timoshenko",
          "[scenes][spline_beam][statics][end_moment]") {
  const std::vector<double> all{0.05, 0.1, 0.25, 0.5, 0.75, 1.0};
  std::vector<std::vector<BentBeam>> by_segments;
  const std::vector<int> segments{1, 3, 5, 10};
  for (int n : segments) {
    std::vector<double> ks;
    for (double K : all)
      if (360.0 * K / n <= 60.0) ks.push_back(K);
    by_segments.push_back(bendSweep("spline_beam", n, ks));
  }
  // Measured up to 60° per segment (Δθ in rad): tip error / Δθ⁴ = 1.6e-3 … 1.1e-2, rotation
  // error / Δθ⁴ = 1.3e-3 … 2.8e-2; up to 36° per segment the tip error is 4e-5 … 0.09 times
  // that of as many Timoshenko elements (the chord polygon; at K = 1 that one closes exactly).
  for (std::size_t s = 0; s < segments.size(); ++s)
    for (const BentBeam& b : by_segments[s]) {
      INFO(segments[s] << " segments, K = " << b.K << ": tip error " << b.error.tip << " L, rotation error "
                       << b.error.rotation << " rad");
      CHECK(b.error.tip < 2.5e-2 * std::pow(b.bend_per_segment, 4));
      CHECK(b.error.rotation < 7e-2 * std::pow(b.bend_per_segment, 4));
      const double timoshenko_error = (chordPolygonTip(b.arc, segments[s]) - b.arc.tip()).norm() / b.arc.L;
      if (b.bend_per_segment <= 36.0 * kDeg + 1e-12 && b.K < 1.0) CHECK(b.error.tip < 0.25 * timoshenko_error);
    }
  // Order of convergence at K = 0.25 (90° in all): measured 4.4 from 3 to 5 segments, 4.0 from 5 to 10.
  const auto errorAt = [&](std::size_t s, double K) {
    for (const BentBeam& b : by_segments[s])
      if (b.K == K) return b.error.tip;
    FAIL("K = " << K << " not solved with " << segments[s] << " segments");
    return 0.0;
  };
  for (std::size_t s = 1; s + 1 < segments.size(); ++s) {
    const double order = std::log(errorAt(s, 0.25) / errorAt(s + 1, 0.25)) /
                         std::log(double(segments[s + 1]) / segments[s]);
    INFO(segments[s] << " → " << segments[s + 1] << " segments: order " << order);
    CHECK(order > 3.5);
  }
}
