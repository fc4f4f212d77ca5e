// The minimum-time lift NLP (a spatial pendulum carried through a static map) against what is
// known without it: with the slewing and the hoist held and a map that moves the suspension
// along a line, it is the line NLP (planning/minimum_time_nlp.hpp) and reaches its optimum; on a
// slewing, luffing and hoisting crane its load follows an independent integration of the
// pendulum (Newton's law in Cartesian coordinates with the rope's tension) under its controls.

#include <catch2/catch.hpp>
#include <tbb/task_arena.h>

#include <cmath>
#include <numbers>

#include "cranesim/math/autodiff.hpp"
#include "cranesim/planning/minimum_time_lift.hpp"
#include "cranesim/planning/minimum_time_nlp.hpp"

using namespace cranesim;

namespace {

constexpr double kG = 9.81;

/// A surface fitted exactly (order 1 in u and v) to values f(u, v) = a + b u + c v.
FittedSurface planeSurface(const std::vector<double>& u, const std::vector<double>& v, double a, double b, double c) {
  GridData data{u, v, Eigen::MatrixXd(u.size(), v.size())};
  for (std::size_t i = 0; i < u.size(); ++i)
    for (std::size_t j = 0; j < v.size(); ++j) data.values(i, j) = a + b * u[i] + c * v[j];
  return FittedSurface::fit(data, {SurfaceKind::Polynomial, 1, 1});
}

/// A pendulum of length L whose suspension the first coordinate moves along x (x = u, the
/// "luffing" drive equal to u), the hoist and slewing held.
LiftProblem linePendulum(double length, double distance, double speed, double acceleration) {
  const std::vector<double> u = {-10.0, 0.0, 20.0, 50.0}, v = {-1.0, 0.0, 1.0};
  LiftProblem problem;
  problem.crane.end_x = planeSurface(u, v, 0.0, 1.0, 0.0);
  problem.crane.end_z = planeSurface(u, v, 5.0, 0.0, 0.0);
  problem.crane.luffing = planeSurface(u, v, 0.0, 1.0, 0.0);
  problem.crane.hoist_length = 30.0;
  problem.crane.along_length = problem.crane.across_length = planeSurface(u, v, length, 0.0, 0.0);
  problem.crane.gravity = kG;
  problem.end = Eigen::Vector3d(distance, 0.0, 0.0);
  problem.q_min = Eigen::Vector3d(-10.0, 0.0, 0.0);
  problem.q_max = Eigen::Vector3d(50.0, 0.0, 0.0);
  problem.drives[kLuffingDrive] = {speed, acceleration};
  return problem;
}

/// A luffing crane slewing about the z axis: a 40 m boom at u degrees hinged at the axis, the
/// load at rest (25 − v) m below the head, the luffing rope shortening as the boom rises; the
/// map fitted as crane-opt fits it (order 5 in u, 2 in v).
LiftProblem slewingCrane(double pendulum_length) {
  GridData x, z, luffing;
  for (GridData* d : {&x, &z, &luffing}) {
    for (double u = 40.0; u <= 80.0; u += 2.0) d->u.push_back(u);
    for (double v = 0.0; v <= 10.0; v += 1.0) d->v.push_back(v);
    d->values.resize(d->u.size(), d->v.size());
  }
  for (std::size_t i = 0; i < x.u.size(); ++i)
    for (std::size_t j = 0; j < x.v.size(); ++j) {
      const double angle = x.u[i] * std::numbers::pi / 180.0;
      x.values(i, j) = -40.0 * std::cos(angle);
      z.values(i, j) = 40.0 * std::sin(angle) - (25.0 - x.v[j]);
      luffing.values(i, j) = 2.0 * 30.0 * std::sin(0.5 * (std::numbers::pi / 2 - angle)) + 10.0;
    }
  const SurfaceSpec spec{SurfaceKind::Polynomial, 5, 2};
  LiftProblem problem;
  LiftKinematics& crane = problem.crane;
  crane.end_x = FittedSurface::fit(x, spec);
  crane.end_z = FittedSurface::fit(z, spec);
  crane.luffing = FittedSurface::fit(luffing, spec);
  crane.hoist_length = 60.0;
  crane.plane = SlewingPlane(Vec3::Zero(), 0.0, -1.0);
  crane.along_length = crane.across_length = planeSurface(x.u, x.v, pendulum_length, 0.0, 0.0);
  crane.gravity = kG;
  problem.start = Eigen::Vector3d(70.0, 0.0, 0.0);
  problem.end = Eigen::Vector3d(55.0, 6.0, 0.5);
  problem.q_min = Eigen::Vector3d(40.0, 0.0, -1.0);
  problem.q_max = Eigen::Vector3d(80.0, 10.0, 1.0);
  problem.drives[kLuffingDrive] = {0.8, 0.2};
  problem.drives[kHoistDrive] = {0.5, 0.2};
  problem.drives[kSlewingDrive] = {0.08, 0.03};
  problem.jerk_limit = Eigen::Vector3d(2.0, 0.5, 0.05);
  problem.intervals = 100;
  return problem;
}

/// slewingCrane with its parts' sizes and a 20 m pillar at 18 m from the axis, half-way through
/// the turn: where the straight lift takes the load.
LiftProblem aroundPillar(LiftProblem problem, double margin) {
  LiftBody& body = problem.crane.body;  // slewingCrane's 40 m boom hinged on the axis, the load 25 − v below its head
  body.boom_length = 40.0, body.boom_radius = 0.5;
  body.load_radius = 1.0;
  body.rope_longest = 26.0;
  const Vec3 centre = Eigen::AngleAxisd(0.25, Vec3::UnitZ()) * Vec3(-18.0, 0.0, 0.0);
  problem.obstacles = {Obstacle{"pillar", CylinderShape{Vec3(centre.x(), centre.y(), 0.0), 1.5, 20.0}, {}}};
  problem.clearance_margin = margin;
  return problem;
}

/// The controls between nodes: the quintic Hermite interpolant of q, q̇, q̈ (C², as the chain's
/// nodes describe it).
Eigen::Vector3d controlsAt(const LiftTrajectory& plan, double t) {
  const double h = plan.t[1];
  const std::size_t k = std::min(static_cast<std::size_t>(std::max(t, 0.0) / h), plan.t.size() - 2);
  const double s = std::clamp(t / h - static_cast<double>(k), 0.0, 1.0);
  const double s2 = s * s, s3 = s2 * s, s4 = s3 * s, s5 = s4 * s;
  const double h00 = 1 - 10 * s3 + 15 * s4 - 6 * s5, h01 = 10 * s3 - 15 * s4 + 6 * s5;
  const double h10 = s - 6 * s3 + 8 * s4 - 3 * s5, h11 = -4 * s3 + 7 * s4 - 3 * s5;
  const double h20 = 0.5 * (s2 - 3 * s3 + 3 * s4 - s5), h21 = 0.5 * (s3 - 2 * s4 + s5);
  const LiftNode &a = plan.nodes[k], &b = plan.nodes[k + 1];
  return h00 * a.q + h01 * b.q + h * (h10 * a.rate + h11 * b.rate) + h * h * (h20 * a.acceleration + h21 * b.acceleration);
}

/// The suspension point c = r + ℓ ẑ of controls q (an isotropic pendulum: ℓ_a = ℓ_c = ℓ(u, v)).
Vec3 suspension(const LiftKinematics& crane, const Eigen::Vector3d& q) {
  return crane.plane.place(crane.end_x(q(0), q(1)), crane.end_z(q(0), q(1)), q(2)) + crane.along(q(0), q(1)) * Vec3::UnitZ();
}

/// The load on a rope of length ℓ(t) = ℓ(u(t), v(t)) from c(t), integrated by RK4 in Cartesian
/// coordinates: p̈ = −λ (p − c) − g ẑ with λ from d²/dt² ‖p − c‖² = d²/dt² ℓ². Returns the load at
/// every plan node.
std::vector<Vec3> integrateLoad(const LiftProblem& problem, const LiftTrajectory& plan) {
  const auto c = [&](double t) { return suspension(problem.crane, controlsAt(plan, t)); };
  const auto squared = [&](double t) {
    const Eigen::Vector3d q = controlsAt(plan, t);
    return std::pow(problem.crane.along(q(0), q(1)), 2);
  };
  constexpr double d = 1e-3;
  const auto second = [d](const auto& f, double t) { return (f(t + d) - 2.0 * f(t) + f(t - d)) / (d * d); };
  using State = Eigen::Matrix<double, 6, 1>;
  const auto rate = [&](double t, const State& y) {
    const Vec3 r = y.head<3>() - c(t);
    const Vec3 cd = (c(t + 1e-4) - c(t - 1e-4)) / 2e-4;
    const Vec3 rd = y.tail<3>() - cd;
    const Vec3 g(0.0, 0.0, kG);
    const Vec3 cdd = second(c, t);
    const double lambda = (rd.squaredNorm() - 0.5 * second(squared, t) - r.dot(g + cdd)) / r.squaredNorm();
    State f;
    f << y.tail<3>(), -lambda * r - g;
    return f;
  };
  State y;
  y << plan.load.front(), Vec3::Zero();
  std::vector<Vec3> loads = {y.head<3>()};
  const int substeps = 40;
  const double dt = plan.t[1] / substeps;
  for (std::size_t k = 0; k + 1 < plan.t.size(); ++k) {
    for (int i = 0; i < substeps; ++i) {
      const double t = plan.t[k] + i * dt;
      const State k1 = rate(t, y), k2 = rate(t + dt / 2, y + dt / 2 * k1), k3 = rate(t + dt / 2, y + dt / 2 * k2),
                  k4 = rate(t + dt, y + dt * k3);
      y += dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    }
    loads.push_back(y.head<3>());
  }
  return loads;
}

/// Checks that the plan's load follows the Cartesian pendulum under its controls.
void checkAgainstIntegration(const LiftProblem& problem, const LiftTrajectory& plan) {
  const std::vector<Vec3> integrated = integrateLoad(problem, plan);
  double largest = 0.0, excursion = 0.0;
  for (int k = 0; k <= problem.intervals; ++k) {
    largest = std::max(largest, (integrated[k] - plan.load[k]).norm());
    const Eigen::Vector3d& q = plan.nodes[k].q;
    const Vec3 c = suspension(problem.crane, q);
    excursion = std::max(excursion, (plan.load[k] - (c - problem.crane.along(q(0), q(1)) * Vec3::UnitZ())).head<2>().norm());
  }
  INFO("largest sway from the resting point " << excursion << " m, collocation vs integration " << largest << " m");
  CHECK(excursion >= 0.05);               // the motion does swing the load
  CHECK(largest <= 0.02 * excursion);     // O(h²) of the trapezoidal rule: measured 1.1 %
  const Vec3 arrival = suspension(problem.crane, problem.end) - problem.crane.along(problem.end(0), problem.end(1)) * Vec3::UnitZ();
  CHECK((integrated.back() - arrival).norm() <= 0.02 * excursion);
}

}  // namespace

TEST_CASE("minimum-time lift: slewing and hoist held, it is the line NLP", "[minimum_time]") {
  const double length = 10.0, distance = 40.0, acceleration = 0.5, speed = 3.17;
  const LiftProblem lift = linePendulum(length, distance, speed, acceleration);
  const LiftTrajectory plan = solveMinimumTimeLift(lift, restToRestGuess(lift, 30.0));

  MinimumTimeProblem line;
  line.distance = distance;
  line.rope_length = length;
  line.gravity = kG;
  line.speed_limit = speed;
  line.acceleration_limit = acceleration;
  line.jerk_limit = 1e6;  // only to start and end at a = 0, as the lift's drives do
  line.intervals = lift.intervals;
  const MinimumTimeTrajectory reference = solveMinimumTime(line);

  CHECK(plan.final_time == Approx(reference.final_time).epsilon(1e-6));
  double largest = 0.0;
  for (int k = 0; k <= lift.intervals; ++k) {
    largest = std::max(largest, std::abs(plan.nodes[k].q(0) - reference.position[k]));
    largest = std::max(largest, std::abs(plan.nodes[k].swing(0) - reference.angle[k]));
    CHECK(plan.nodes[k].swing(1) == Approx(0.0).margin(1e-9));  // nothing swings it across
  }
  CHECK(largest <= 1e-3);  // m and rad: the same optimum (measured 1.0e-4, both solved to 1e-8)
}

TEST_CASE("minimum-time lift: a slewing, luffing, hoisting crane against an integration of its pendulum", "[minimum_time]") {
  const double length = 10.0;
  const LiftProblem problem = slewingCrane(length);
  const LiftTrajectory plan = solveMinimumTimeLift(problem, restToRestGuess(problem, 60.0));
  const int N = problem.intervals;
  INFO("t_f " << plan.final_time << " s in " << plan.iterations << " iterations, " << plan.solve_time_s << " s");

  SECTION("rest to rest: the load hangs at its resting points at both ends") {
    for (int k : {0, N}) {
      const Eigen::Vector3d& q = k == 0 ? problem.start : problem.end;
      const Vec3 resting = problem.crane.plane.place(problem.crane.end_x(q(0), q(1)), problem.crane.end_z(q(0), q(1)), q(2));
      CHECK((plan.load[k] - resting).norm() <= 1e-6);
      CHECK(plan.nodes[k].swing.norm() <= 1e-6);
      CHECK(plan.drives[k].speed.norm() <= 1e-6);
    }
  }
  SECTION("every drive keeps its limits at every node") {
    for (const DriveState& d : plan.drives)
      for (int i = 0; i < 3; ++i) {
        CHECK(std::abs(d.speed(i)) <= problem.drives[i].speed * (1 + 1e-6));
        CHECK(std::abs(d.acceleration(i)) <= problem.drives[i].acceleration * (1 + 1e-6));
      }
  }
  SECTION("the load follows the Cartesian pendulum under the planned controls") { checkAgainstIntegration(problem, plan); }
}

TEST_CASE("minimum-time lift: the same lift solved twice is the same plan to the last bit", "[minimum_time]") {
  // Ipopt factors its KKT systems with MUMPS, whose fill-reducing ordering must not depend on
  // chance: a randomised one (SCOTCH's) rounds each solve differently, and the iterates drift
  // apart. The nodes are evaluated on threads, so the second solve runs on one thread.
  const LiftProblem problem = aroundPillar(slewingCrane(10.0), 0.5);
  const LiftGuess guess = waypointGuess(problem, {problem.start, Eigen::Vector3d(70.0, 0.0, 0.5), problem.end});
  const LiftTrajectory first = solveMinimumTimeLift(problem, guess);
  LiftTrajectory second;
  tbb::task_arena(1).execute([&] { second = solveMinimumTimeLift(problem, guess); });
  CHECK(first.iterations == second.iterations);
  CHECK(first.final_time == second.final_time);
  for (std::size_t k = 0; k < first.nodes.size(); ++k) {
    CHECK(first.nodes[k].q == second.nodes[k].q);
    CHECK(first.nodes[k].swing == second.nodes[k].swing);
  }
}

TEST_CASE("minimum-time lift: a pendulum whose length changes over the map", "[minimum_time]") {
  // ℓ(u, v) = 10 m + 0.1 m/° (u − 60°) − 0.3 (v − 5 m): longer with the boom up and the rope paid
  // out, as a crane's is; the rope's length changes by about 2 m during the lift.
  LiftProblem problem = slewingCrane(10.0);
  GridData length{{40.0, 60.0, 80.0}, {0.0, 5.0, 10.0}, Eigen::MatrixXd(3, 3)};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) length.values(i, j) = 10.0 + 0.1 * (length.u[i] - 60.0) - 0.3 * (length.v[j] - 5.0);
  problem.crane.along_length = problem.crane.across_length = FittedSurface::fit(length, {SurfaceKind::Polynomial, 1, 1});
  const LiftTrajectory plan = solveMinimumTimeLift(problem, restToRestGuess(problem, 60.0));
  INFO("t_f " << plan.final_time << " s in " << plan.iterations << " iterations, " << plan.solve_time_s << " s");
  checkAgainstIntegration(problem, plan);
}

TEST_CASE("minimum-time lift: the luffing rope's jerk through the map keeps its limit at every node", "[minimum_time]") {
  LiftProblem problem = slewingCrane(10.0);
  const LiftTrajectory free = solveMinimumTimeLift(problem, restToRestGuess(problem, 60.0));
  double free_peak = 0.0;
  for (const DriveState& d : free.drives) free_peak = std::max(free_peak, std::abs(d.jerk(kLuffingDrive)));
  // The free lift's node jerks zig-zag (the trapezoidal rule constrains only their neighbours'
  // means), so its peak says little; 8 % of it lies below the smooth part and lengthens the lift
  // (measured 14.91 → 16.35 s).
  problem.luffing_jerk_limit = 0.08 * free_peak;
  const LiftTrajectory plan = solveMinimumTimeLift(problem, restToRestGuess(problem, 60.0));
  INFO("t_f " << plan.final_time << " s (" << free.final_time << " s with the luffing rope's jerk up to " << free_peak << " m/s³)");
  CHECK(plan.final_time > free.final_time + 0.1);

  // The drives' accelerations at the nodes change by the trapezoidal rule of their jerks: exactly
  // for the hoist rope (−v̈), to O(h²) for the luffing rope through the map.
  const double h = plan.t[1];
  double peak = 0.0, luffing_mismatch = 0.0, hoist_mismatch = 0.0;
  for (std::size_t k = 0; k < plan.drives.size(); ++k) {
    const DriveState& d = plan.drives[k];
    peak = std::max(peak, std::abs(d.jerk(kLuffingDrive)));
    if (k + 1 == plan.drives.size()) break;
    const DriveState& e = plan.drives[k + 1];
    for (const auto& [drive, mismatch] : {std::pair{kLuffingDrive, &luffing_mismatch}, std::pair{kHoistDrive, &hoist_mismatch}})
      *mismatch = std::max(*mismatch, std::abs((e.acceleration(drive) - d.acceleration(drive)) / h - 0.5 * (d.jerk(drive) + e.jerk(drive))));
  }
  INFO("peak " << peak << " m/s³ against the limit " << problem.luffing_jerk_limit << "; trapezoidal mismatch luffing "
               << luffing_mismatch << ", hoist " << hoist_mismatch << " m/s³");
  CHECK(peak <= problem.luffing_jerk_limit * (1 + 1e-6));
  CHECK(peak >= 0.99 * problem.luffing_jerk_limit);  // the limit shapes the lift
  CHECK(hoist_mismatch <= 1e-6);
  CHECK(luffing_mismatch <= 0.02 * problem.luffing_jerk_limit);
}

TEST_CASE("minimum-time lift: bad sizes and limits are refused", "[minimum_time]") {
  LiftProblem problem = linePendulum(10.0, 40.0, 3.0, 0.5);
  const LiftGuess guess = restToRestGuess(problem, 30.0);
  problem.intervals = 1;
  CHECK_THROWS_WITH(solveMinimumTimeLift(problem, guess), Catch::Contains("intervals must be ≥ 2"));
  problem.intervals = 100;
  problem.drives[kHoistDrive].speed = 0.0;
  CHECK_THROWS_WITH(solveMinimumTimeLift(problem, guess), Catch::Contains("drive limits must be > 0"));
  CHECK_THROWS_WITH(solveMinimumTimeLift(problem, LiftGuess{}), Catch::Contains("the guess needs nodes"));
}

TEST_CASE("minimum-time lift: around a pillar that the obstacle-free lift runs into", "[minimum_time][obstacles]") {
  const double margin = 0.5;
  const LiftProblem free = slewingCrane(10.0);
  const LiftProblem problem = aroundPillar(free, margin);
  const LiftBody& body = problem.crane.body;

  const LiftTrajectory straight = solveMinimumTimeLift(free, restToRestGuess(free, 60.0));
  double straight_clearance = 1e9;
  for (const LiftNode& node : straight.nodes) straight_clearance = std::min(straight_clearance, clearanceAt(problem, node).clearance);
  CHECK(straight_clearance < -1.0);  // it runs through the pillar

  // Slewed with the boom up (the load 13.7 m out, the pillar's face at 16.5 m), then luffed out.
  const LiftGuess guess = waypointGuess(problem, {problem.start, Eigen::Vector3d(70.0, 0.0, 0.5), problem.end});
  for (const LiftNode& node : guess.nodes) REQUIRE(clearanceAt(problem, node).clearance >= margin);
  const LiftTrajectory plan = solveMinimumTimeLift(problem, guess);
  INFO("t_f " << plan.final_time << " s (" << straight.final_time << " s through the pillar) in " << plan.iterations
              << " iterations, " << plan.solve_time_s << " s");
  CHECK(plan.final_time > straight.final_time);

  // Every part at every node, by the exact distances: the boom's and the rope's capsules, the load's sphere.
  const ObstacleShape& pillar = problem.obstacles[0].shape;
  double nearest = 1e9;
  for (int k = 0; k <= problem.intervals; ++k) {
    const LiftNode& node = plan.nodes[k];
    const BoomPoints<double> boom = boomPoints(body, problem.crane.plane, node.q(0), node.q(2));
    const auto at = [](const LiftPoint<double>& x) { return Vec3(x[0], x[1], x[2]); };
    for (const Capsule& part : {Capsule{at(boom.foot), at(boom.head), body.boom_radius}, Capsule{at(boom.sheave), plan.load[k], 0.0},
                                Capsule{plan.load[k], plan.load[k], body.load_radius}})
      nearest = std::min(nearest, signedDistance(pillar, part));
    CHECK(plan.clearance[k] >= margin - 1e-6);
  }
  CHECK(nearest >= margin - 1e-6);
  CHECK(nearest <= margin + 0.05);  // the pillar shapes the lift: its clearance is active
}

TEST_CASE("minimum-time lift: a wall across the whole turn blocks it, and the failure names it", "[minimum_time][obstacles]") {
  LiftProblem problem = slewingCrane(10.0);
  problem.crane.body.boom_length = 40.0, problem.crane.body.load_radius = 1.0, problem.crane.body.rope_longest = 26.0;
  // A 100 m wall from 1 m to 60 m out, half-way through the turn; the slewing may not go the other way round.
  const Vec3 centre = Eigen::AngleAxisd(0.25, Vec3::UnitZ()) * Vec3(-30.5, 0.0, 0.0);
  problem.obstacles = {Obstacle{"wall", BoxShape{Vec3(centre.x(), centre.y(), 50.0), Vec3(59.0, 0.5, 100.0), 0.25}, {}}};
  problem.clearance_margin = 0.5;
  problem.q_min(2) = 0.0, problem.q_max(2) = 0.5;
  problem.max_iterations = 200;
  try {
    solveMinimumTimeLift(problem, restToRestGuess(problem, 60.0));
    FAIL("the lift went through the wall");
  } catch (const LiftBlocked& blocked) {
    CHECK(blocked.closest.obstacle == 0);
    CHECK(blocked.closest.clearance < problem.clearance_margin - 1e-3);
    CHECK(blocked.t > 0.0);
  }
}
