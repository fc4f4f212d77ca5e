// Rest-to-rest paths (planning/rest_to_rest_path.hpp): the polynomial transition, the cruising
// path's derivatives and ends, and the ramps fitted to speed and acceleration bounds.

#include <catch2/catch.hpp>

#include <cmath>

#include "cranesim/planning/rest_to_rest_path.hpp"

using namespace cranesim;

TEST_CASE("Rest-to-rest transition: ends, symmetry and derivatives", "[planning][flatness]") {
  CHECK(restToRest(0.0) == 0.0);
  CHECK(restToRest(1.0) == 1.0);
  CHECK(restToRest(-1.0) == 0.0);
  CHECK(restToRest(2.0) == 1.0);
  // Near the start s ≈ 126 τ⁵: the k-th derivative vanishes like 126 · 5!/(5 − k)! · τ^(5 − k).
  const double tau0 = 1e-4;
  double falling = 126.0;
  for (int k = 1; k <= 4; ++k) {
    falling *= 6 - k;
    CHECK(restToRest(tau0, k) == Approx(falling * std::pow(tau0, 5 - k)).epsilon(2e-3));
  }
  const double h = 1e-5;
  for (double tau : {0.1, 0.37, 0.5, 0.81}) {
    // s(τ) + s(1 − τ) = 1, so s^(k)(1 − τ) = (−1)^(k+1) s^(k)(τ): the end mirrors the start.
    CHECK(restToRest(tau) + restToRest(1.0 - tau) == Approx(1.0).epsilon(1e-14));
    for (int k = 1; k <= 4; ++k)
      CHECK(restToRest(1.0 - tau, k) == Approx((k % 2 == 1 ? 1.0 : -1.0) * restToRest(tau, k)).epsilon(1e-12).margin(1e-12));
    for (int k = 1; k <= 4; ++k)
      CHECK(restToRest(tau, k) ==
            Approx((restToRest(tau + h, k - 1) - restToRest(tau - h, k - 1)) / (2 * h)).epsilon(1e-6).margin(1e-6));
  }
  CHECK_THROWS_AS(restToRest(0.5, 5), std::invalid_argument);
}

TEST_CASE("Rest-to-rest path: at rest at both ends, its derivatives consistent, peaks as designed", "[planning][flatness]") {
  const Eigen::Vector2d start(-10.0, 0.0), end(-35.0, 10.0);
  const double duration = 40.0, ramp = 15.0;  // Table 8-2's fit: 10 s of cruise at 1 m/s in x
  const RestToRestPath path(start, end, duration, ramp);
  CHECK((path.derivative(0.0, 0) - start).norm() < 1e-12);
  CHECK((path.derivative(duration, 0) - end).norm() < 1e-12);
  CHECK((path.derivative(-1.0, 0) - start).norm() == 0.0);
  CHECK((path.derivative(duration + 1.0, 0) - end).norm() == 0.0);
  // Derivatives 1 … 4 vanish at both ends, near them like the ramp's leading term: σ ≈ V T_r · 7 τ⁵
  // with τ = t / T_r, V = 1 / (T − T_r), so σ^(k) ≈ V T_r^(1 − k) · 7 · 5!/(5 − k)! · τ^(5 − k).
  const double t_near = 1e-2, tau = t_near / ramp, speed = 1.0 / (duration - ramp);
  double falling = 7.0;
  for (int k = 1; k <= 4; ++k) {
    falling *= 6 - k;
    CHECK(path.derivative(0.0, k).norm() == 0.0);
    CHECK(path.derivative(duration, k).norm() == 0.0);
    const double leading = speed * std::pow(ramp, 1 - k) * falling * std::pow(tau, 5 - k);
    CHECK(path.derivative(t_near, k).norm() == Approx(leading * (end - start).norm()).epsilon(1e-2));
    CHECK(path.derivative(duration - t_near, k).norm() == Approx(leading * (end - start).norm()).epsilon(1e-2));
  }
  // Each derivative is the central difference of the one below, in the ramps, across their ends
  // (the fourth is continuous there: S''' vanishes) and in the cruise.
  const double h = 1e-4;
  for (double t : {0.3, 7.5, 14.9, 15.0, 15.1, 20.0, 25.0, 33.2, 39.7})
    for (int k = 1; k <= 4; ++k) {
      const Eigen::Vector2d difference = (path.derivative(t + h, k - 1) - path.derivative(t - h, k - 1)) / (2 * h);
      INFO("t = " << t << ", k = " << k);
      CHECK((path.derivative(t, k) - difference).norm() < 1e-6 * (1.0 + difference.norm()));
    }
  // Cruise at V = 1 / (T − T_r) of the distance; the acceleration peaks mid-ramp at (35/16) V / T_r.
  const Eigen::Vector2d distance = end - start;
  CHECK((path.derivative(20.0, 1) - distance / 25.0).norm() < 1e-12);
  CHECK((path.derivative(20.0, 2)).norm() < 1e-12);
  CHECK((path.derivative(7.5, 2) - 35.0 / 16.0 / 25.0 / 15.0 * distance).norm() < 1e-12);
  CHECK((path.derivative(32.5, 2) + 35.0 / 16.0 / 25.0 / 15.0 * distance).norm() < 1e-12);
  CHECK_THROWS_AS(RestToRestPath(start, end, 10.0, 6.0), std::invalid_argument);
  CHECK_THROWS_AS(path.derivative(1.0, 5), std::invalid_argument);
}

TEST_CASE("Rest-to-rest path fitted to bounds: the longest ramps within the speed bound", "[planning][flatness]") {
  const Eigen::Vector2d v_min(-0.5, -0.5), v_max(0.5, 0.5), a_min(-0.2, -0.2), a_max(0.2, 0.2);
  const Eigen::Vector2d start(-10.0, 7.5), end(-14.0, 10.0);  // target_luffing_jib.yaml
  // 15 s: x moves 4 m, at 0.5 m/s at most it cruises at least 8 s: ramps of 7 s.
  CHECK(RestToRestPath::fitting(start, end, 15.0, v_min, v_max, a_min, a_max).ramp() == Approx(7.0).epsilon(1e-14));
  // 30 s: no cruise needed, ramps of half the duration.
  CHECK(RestToRestPath::fitting(start, end, 30.0, v_min, v_max, a_min, a_max).ramp() == Approx(15.0).epsilon(1e-14));
  // 12 s: the ramps of 4 s would accelerate x at (35/16)·4 m/(8 s · 4 s) = 0.27 m/s² > 0.2. The
  // shortest duration: (35/16)·4 / (8 (T − 8)) = 0.2 → T = 8 + 5.46875 s.
  try {
    RestToRestPath::fitting(start, end, 12.0, v_min, v_max, a_min, a_max);
    FAIL("a 12 s horizon must be infeasible");
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    INFO(message);
    CHECK(message.find("infeasible horizon") != std::string::npos);
    CHECK(message.find("at least 13.5 s") != std::string::npos);
    CHECK(message.find("acceleration in x") != std::string::npos);
  }
  // 8 s cannot even cruise at 0.5 m/s.
  CHECK_THROWS_WITH(RestToRestPath::fitting(start, end, 8.0, v_min, v_max, a_min, a_max),
                    Catch::Contains("speed bounds") && Catch::Contains("at least 13.5 s"));
  CHECK_THROWS_WITH(RestToRestPath::fitting(start, end, 20.0, v_min, Eigen::Vector2d(0.5, 0.0), a_min, a_max),
                    Catch::Contains("z cannot move"));
  // The sampled trajectory ends exactly at the path's end, at rest.
  const QrTrajectory sampled = sampleTrajectory(RestToRestPath(start, end, 15.0, 7.0), 0.1);
  REQUIRE(sampled.t.size() == 151);
  CHECK(sampled.t.back() == 15.0);
  CHECK((sampled.states.back() - (EndState() << end, 0.0, 0.0).finished()).norm() < 1e-12);
  CHECK(sampled.controls.size() == 150);
}
