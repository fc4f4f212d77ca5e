// A session driven step by step (session/session.hpp): inputs commanded at every sample do not
// restart the integrator, the run is as accurate as its tolerances, a reset starts the same run
// again, and bad names and commands are refused with messages that say what exists.

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <vector>

#include "cranesim/io/results_writer.hpp"
#include "cranesim/io/scene_reader.hpp"
#include "cranesim/model/compile.hpp"
#include "cranesim/session/session.hpp"
#include "cranesim/solvers/scene_equilibrium.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

const std::string kCraneInputs = std::string(CRANESIM_SOURCE_DIR) + "/configs/crane_inputs.yaml";

/// The commands of one sample: slewing rate (°/s), hoist and luffing rope speeds (m/s).
struct Commands {
  double slewing = 0.0, hoist = 0.0, luffing = 0.0;
};

/// A lift on the thesis crane commanded at 50 Hz: the hoist rope reels in, the luffing rope
/// out and the crane slews at speeds that start smoothly, and the slewing rate also follows the
/// load's sway across the boom (the head moves at 0.44 1/s × the hook's offset across it, which
/// damps the swing).
struct Lift {
  Session& session;
  int slewing, hoist, luffing, hook, head;
  explicit Lift(Session& s)
      : session(s), slewing(s.input("slewing")), hoist(s.input("hoist_rope")), luffing(s.input("luffing_rope")),
        hook(s.joint("load.origin")), head(s.joint("head.sheave")) {}

  Commands feedback(double t) const {
    const double ramp = 0.5 - 0.5 * std::cos(std::numbers::pi * std::min(t / 5.0, 1.0));
    const Vec3 r = session.jointPosition(head);
    const double radius = std::hypot(r.x(), r.y());
    const Vec3 across(-r.y() / radius, r.x() / radius, 0.0);
    const double sway = (session.jointPosition(hook) - r).dot(across);
    return {2.0 * ramp + 0.44 * sway / radius * 180.0 / std::numbers::pi, -0.4 * ramp, 0.1 * ramp};
  }
  void apply(const Commands& c) {
    session.setInput(slewing, c.slewing);
    session.setInput(hoist, c.hoist);
    session.setInput(luffing, c.luffing);
  }
};

}  // namespace

TEST_CASE("Inputs commanded at every sample move the crane without restarting the integrator, as "
          "accurately as its tolerances", "[session]") {
  const double dt = 0.02, t_end = 12.0;
  Session session(kCraneInputs);
  Lift lift(session);
  std::vector<Commands> commands;
  std::vector<Vec3> hook_path;
  while (session.time() < t_end - 1e-9) {
    commands.push_back(lift.feedback(session.time()));
    lift.apply(commands.back());
    REQUIRE(session.step(dt));
    CHECK(session.time() == Approx(commands.size() * dt).margin(1e-12));
    hook_path.push_back(session.jointPosition(lift.hook));
  }
  const SimulationOutcome outcome = session.outcome();
  INFO("steps " << outcome.statistics.steps << ", Jacobians " << outcome.statistics.jacobian_evaluations
                << ", error-test failures " << outcome.statistics.error_test_failures);
  CHECK(outcome.statistics.restarts == 0);
  CHECK(outcome.statistics.steps < 3 * static_cast<long>(commands.size()));
  // The crane did move: slewed, hoisted, luffed.
  CHECK(session.inputValue(lift.slewing) > 10.0);
  // Reeled in at 0.4 m/s after a 5 s cosine start, behind the commands by the two lags' 2 × 50 ms
  // and half a sample.
  CHECK(session.inputValue(lift.hoist) == Approx(53.9937 - 0.4 * (t_end - 2.5 - 0.1 - 0.01)).margin(0.002));
  CHECK(session.inputRate(lift.hoist) == Approx(-0.4).margin(1e-6));

  // The same commands at rtol 1e-8: the hook's path within the error rtol 1e-4 allows.
  Scene tight = readScene(kCraneInputs);
  tight.solver.rtol = 1e-8;
  tight.solver.atol = AbsoluteTolerance::uniform(1e-9);
  Session reference(tight);
  Lift replay(reference);
  double largest = 0.0;
  for (std::size_t k = 0; k < commands.size(); ++k) {
    replay.apply(commands[k]);
    REQUIRE(reference.step(dt));
    largest = std::max(largest, (reference.jointPosition(replay.hook) - hook_path[k]).norm());
  }
  INFO("largest hook distance " << largest << " m");
  CHECK(largest < 0.01);
  CHECK(reference.outcome().statistics.restarts == 0);
}

TEST_CASE("A session reset runs the same run again, bit for bit", "[session]") {
  Session session(kCraneInputs);
  Lift lift(session);
  std::vector<Vec3> first;
  for (int k = 0; k < 100; ++k) {
    lift.apply(lift.feedback(session.time()));
    session.step(0.02);
    first.push_back(session.jointPosition(lift.hook));
  }
  session.reset();
  CHECK(session.time() == 0.0);
  CHECK(session.inputValue(lift.hoist) == 53.9937);
  CHECK(session.inputRate(lift.slewing) == 0.0);
  for (int k = 0; k < 100; ++k) {
    lift.apply(lift.feedback(session.time()));
    session.step(0.02);
    REQUIRE(session.jointPosition(lift.hook) == first[static_cast<std::size_t>(k)]);
  }
}

TEST_CASE("A joint's velocity is the rate of its position", "[session]") {
  Session session(kCraneInputs);
  Lift lift(session);
  const double dt = 0.005;
  std::vector<Vec3> head, head_velocity, hook, hook_velocity;
  std::vector<Session::Sway> sway;
  const Session::Sway at_rest = session.sway(lift.hook, lift.head);
  CHECK(std::abs(at_rest.radial) < 1e-9);  // the rope hangs plumb in equilibrium
  CHECK(std::abs(at_rest.across) < 1e-9);
  for (int k = 0; k < 800; ++k) {
    lift.apply(lift.feedback(session.time()));
    session.step(dt);
    sway.push_back(session.sway(lift.hook, lift.head));
    head.push_back(session.jointPosition(lift.head));
    head_velocity.push_back(session.jointVelocity(lift.head));
    hook.push_back(session.jointPosition(lift.hook));
    hook_velocity.push_back(session.jointVelocity(lift.hook));
  }
  // Central differences over ±5 ms, from 3 s on (the head slews at about 0.35 m/s, off its body's
  // origin: the ω × r term).
  for (std::size_t k = 600; k + 1 < head.size(); k += 20) {
    const Vec3 head_rate = (head[k + 1] - head[k - 1]) / (2.0 * dt), hook_rate = (hook[k + 1] - hook[k - 1]) / (2.0 * dt);
    CHECK((head_rate - head_velocity[k]).norm() < 1e-3 * head_velocity[k].norm());
    CHECK((hook_rate - hook_velocity[k]).norm() < 1e-3 * hook_velocity[k].norm());
    const double radial_rate = (sway[k + 1].radial - sway[k - 1].radial) / (2.0 * dt),
                 across_rate = (sway[k + 1].across - sway[k - 1].across) / (2.0 * dt);
    CHECK(radial_rate == Approx(sway[k].radial_rate).epsilon(1e-3).margin(1e-6));
    CHECK(across_rate == Approx(sway[k].across_rate).epsilon(1e-3).margin(1e-6));
    // The across angle is the hook's offset across the boom over the rope's drop.
    const Vec3 r = head[k], across_boom = Vec3(-r.y(), r.x(), 0.0).normalized();
    CHECK(std::tan(sway[k].across) == Approx((hook[k] - r).dot(across_boom) / (r.z() - hook[k].z())).epsilon(1e-12));
  }
  CHECK(head_velocity.back().norm() > 0.1);
  CHECK(std::abs(sway.back().across) > 1e-3);  // the slewing swings the load
}

TEST_CASE("A session refuses unknown names and commands that are not numbers", "[session]") {
  Session session(kCraneInputs);
  CHECK_THROWS_WITH(session.input("hoist"), Catch::Contains("no input named 'hoist'") &&
                                                Catch::Contains("the scene's inputs: luffing_rope, hoist_rope, slewing"));
  CHECK_THROWS_WITH(session.input("hoist_rop"), Catch::Contains("did you mean 'hoist_rope'?"));
  CHECK_THROWS_WITH(session.joint("load.orign"), Catch::Contains("did you mean 'load.origin'?"));
  CHECK_THROWS_WITH(session.setInput(session.input("slewing"), std::numeric_limits<double>::quiet_NaN()),
                    Catch::Contains("input 'slewing' (drive)") && Catch::Contains("not a finite number"));
  // The limits clip: the slewing drive's 6 °/s (its ramp then keeps it within 2 °/s²).
  CHECK(session.setInput(session.input("slewing"), 100.0) == 6.0);
}

TEST_CASE("A scene's input is checked where it is written", "[session]") {
  const auto scene = [](const std::string& length) {
    return "name: winch\nground:\n  joints: [{name: top}]\nbodies:\n  - {name: ball, mass: 1, inertia: [1, 1, 1], "
           "position: [0, 0, -1]}\nmembers:\n  - {name: rope, type: rope, start: [0, 0, 0], end: [0, 0, -1], "
           "section: {radius: 0.01}, material: {density: 7800, youngs_modulus: 2.0e11}, length: " + length + "}\nconstraints:\n  - {name: top, type: spherical, joints: "
           "[ground.top, rope.start]}\n  - {name: hook, type: spherical, joints: [rope.end, ball.origin]}\nsolver: {t_end: 1}\n";
  };
  CHECK_NOTHROW(parseScene(scene("{type: input, value: 1, command: speed}"), "winch.yaml"));
  CHECK_THROWS_WITH(parseScene(scene("{type: input, value: 1, command: value}"), "winch.yaml"),
                    Catch::Contains("members[0].length") && Catch::Contains("needs order: 2"));
  CHECK_THROWS_WITH(parseScene(scene("{type: input, value: 1, order: 3}"), "winch.yaml"),
                    Catch::Contains("members[0].length.order") && Catch::Contains("order is 1 or 2"));
  CHECK_THROWS_WITH(parseScene(scene("{type: input, value: 1, command: value, order: 2, limits: {acceleration: 1}}"),
                               "winch.yaml"),
                    Catch::Contains("limits.acceleration") && Catch::Contains("belongs to a speed command"));
  CHECK_THROWS_WITH(parseScene(scene("{type: input, value: 1, limits: {min: 2}}"), "winch.yaml"),
                    Catch::Contains("members[0].length.value") && Catch::Contains("outside limits"));
}

TEST_CASE("Save, step, restore, step again: the same continuation, bit for bit", "[session]") {
  Session session(kCraneInputs);
  Lift lift(session);
  for (int k = 0; k < 100; ++k) {
    lift.apply(lift.feedback(session.time()));
    session.step(0.02);
  }
  const double hoist_at_save = session.inputValue(lift.hoist);
  const SimulationState saved = session.save();
  CHECK(saved.t == Approx(2.0).margin(1e-12));
  const auto continuation = [&] {
    std::vector<Vec3> path;
    for (int k = 0; k < 100; ++k) {
      lift.apply(lift.feedback(session.time()));
      session.step(0.02);
      path.push_back(session.jointPosition(lift.hook));
    }
    return path;
  };
  const std::vector<Vec3> first = continuation();
  session.restore(saved);
  CHECK(session.time() == saved.t);
  CHECK(session.inputValue(lift.hoist) == hoist_at_save);
  REQUIRE(continuation() == first);
}

TEST_CASE("A state saved to a file goes on in another session within the integrator's error", "[session]") {
  Scene scene = readScene(kCraneInputs);
  scene.solver.rtol = 1e-9;
  scene.solver.atol = AbsoluteTolerance::uniform(1e-10);
  // Commands that depend on time only, so that every run gets the same.
  const auto commands = [](Session& s) {
    const double t = s.time();
    s.setInput(s.input("slewing"), 3.0 * std::sin(0.5 * t));
    s.setInput(s.input("hoist_rope"), -0.3 * std::sin(0.7 * t));
  };
  const auto run = [&](Session& s, double until, std::vector<Vec3>* path) {
    const int hook = s.joint("load.origin");
    while (s.time() < until - 1e-9) {
      commands(s);
      REQUIRE(s.step(0.02));
      if (path) path->push_back(s.jointPosition(hook));
    }
  };
  std::vector<Vec3> uninterrupted, continued;
  {
    Session whole(scene);
    run(whole, 1.0, nullptr);
    run(whole, 2.5, &uninterrupted);
  }
  const std::string file = "session_state_test.h5";
  {
    Session first(scene);
    run(first, 1.0, nullptr);
    first.saveFile(file);
  }
  Session second(scene);
  second.restoreFile(file);
  CHECK(second.time() == Approx(1.0).margin(1e-12));
  run(second, 2.5, &continued);
  REQUIRE(continued.size() == uninterrupted.size());
  double largest = 0.0;
  for (std::size_t k = 0; k < continued.size(); ++k) largest = std::max(largest, (continued[k] - uninterrupted[k]).norm());
  INFO("largest hook distance " << largest << " m");
  CHECK(largest < 1e-6);
  CHECK(largest > 0.0);  // a restart, not a copy of the integrator's history

  // Another model's state is refused, naming the file.
  Session other(std::string(CRANESIM_SOURCE_DIR) + "/configs/crane_condensed.yaml");
  CHECK_THROWS_WITH(other.restoreFile(file), Catch::Contains(file) && Catch::Contains("inputs"));
  CHECK_THROWS_WITH(second.restoreFile("no_such_state.h5"), Catch::Contains("no_such_state.h5"));
  std::remove(file.c_str());
}

TEST_CASE("A session of a scene without inputs, stepped every 20 ms, is its crane-sim run at the output "
          "times, bit for bit", "[session]") {
  Scene scene = readScene(std::string(CRANESIM_SOURCE_DIR) + "/configs/crane_combined.yaml");
  scene.solver.t_end = 12.0;  // across the slewing's start (a breakpoint, a restart)
  const Model model = compileModel(scene);
  const Assembler assembler(model);
  ResultsRecorder recorder(assembler);
  const SimulationOutcome whole = simulate(assembler, runInitialState(scene, model, assembler, true), recorder);
  REQUIRE(whole.complete);

  Session session(scene);
  const int hook = session.joint("load.origin");
  const std::vector<double>& recorded = recorder.jointPositions(hook);
  REQUIRE(recorded.size() == 3 * recorder.samples());
  for (std::size_t k = 1; k < recorder.samples(); ++k) {
    const double from = recorder.time()[k - 1], to = recorder.time()[k];
    for (int j = 1; j < 5; ++j) session.advanceTo(from + (to - from) * j / 5.0);  // output every 0.1 s
    session.advanceTo(to);
    REQUIRE(session.time() == recorder.time()[k]);
    const Vec3 p = session.jointPosition(hook);
    REQUIRE(p == Vec3(recorded[3 * k], recorded[3 * k + 1], recorded[3 * k + 2]));
  }
  CHECK(session.outcome().complete);
  CHECK(session.outcome().statistics.steps == whole.statistics.steps);
}

TEST_CASE("A session observes the times a step passed on its way to a breakpoint, bit for bit", "[session]") {
  // A load whose scale has a knot 3 ms after an output time: the step that passes the output
  // times 0.49 and 0.50 ends on the knot, where the integrator restarts. The restart waits for the
  // next advance, so the step's history still interpolates both times.
  Scene scene = readScene(std::string(CRANESIM_SOURCE_DIR) + "/configs/pendulum.yaml");
  scene.solver.t_end = 1.0;
  scene.solver.rtol = 1e-3;
  scene.solver.atol = AbsoluteTolerance::uniform(1e-6);
  LoadSpec push;
  push.name = "push";
  push.joint = "rod.tip";
  push.force = Vec3(0.0, 0.0, -5.0);
  push.scale = Profile(TableProfile{{0.0, 0.503, 1.0}, {1.0, 1.0, 0.0}, {}, Interpolation::Linear});
  scene.loads.push_back(push);
  const Model model = compileModel(scene);
  const Assembler assembler(model);
  ResultsRecorder recorder(assembler);
  REQUIRE(simulate(assembler, runInitialState(scene, model, assembler, true), recorder).complete);

  Session session(scene);
  const int tip = session.joint("rod.tip");
  const std::vector<double>& recorded = recorder.jointPositions(tip);
  bool passed_two = false;  // the case this checks: two output times within the step to the knot
  for (std::size_t k = 1; k < recorder.samples(); ++k) {
    const long restarts = session.outcome().statistics.restarts;
    session.advanceTo(recorder.time()[k]);
    if (std::abs(session.time() - 0.49) < 1e-9) passed_two = session.outcome().t_reached == 0.503 && restarts == 0;
    INFO("t = " << session.time());
    REQUIRE(session.jointPosition(tip) == Vec3(recorded[3 * k], recorded[3 * k + 1], recorded[3 * k + 2]));
  }
  CHECK(passed_two);
}

TEST_CASE("A recording session keeps the samples before a restored state and records on from there",
          "[session]") {
  Session session(kCraneInputs, true);
  Lift lift(session);
  const auto drive = [&](double until) {
    while (session.time() < until - 1e-9) {
      lift.apply(lift.feedback(session.time()));
      session.step(0.02);
    }
  };
  drive(1.0);
  const SimulationState saved = session.save();
  drive(2.0);
  const ResultsRecorder& recorder = *session.recorder();
  const std::vector<double> first_time = recorder.time(), first_q = recorder.stateColumn(0);
  REQUIRE(first_time.size() == 21);  // 0, 0.1, …, 2 s
  session.restore(saved);
  CHECK(recorder.samples() == 11);   // up to the saved 1 s
  drive(2.0);
  CHECK(recorder.time() == first_time);
  CHECK(recorder.stateColumn(0) == first_q);

  const std::string file = "session_results_test.h5";
  session.writeResults(file);
  CHECK(std::remove(file.c_str()) == 0);
  Session unrecorded(kCraneInputs);
  CHECK(unrecorded.recorder() == nullptr);
  CHECK_THROWS_AS(unrecorded.writeResults(file), std::logic_error);
}

TEST_CASE("A session's loads and energies are those of statics and of the results file", "[session]") {
  Session session(kCraneInputs, true);
  Lift lift(session);
  const Scene& scene = session.scene();
  const auto load = std::find_if(scene.bodies.begin(), scene.bodies.end(), [](const RigidBodySpec& b) { return b.name == "load"; });
  REQUIRE(load != scene.bodies.end());
  const double weight = load->mass * scene.gravity.norm();

  // In equilibrium the hook carries the load's weight, which is the hoist rope's tension there.
  const ConstraintReaction hook = session.constraintLoad(session.constraint("hook"));
  CHECK(hook.force.norm() == Approx(weight).epsilon(1e-9));
  const std::vector<double> tension = session.ropeTensions("hoist_rope");
  REQUIRE(tension.size() % kTensionPoints == 0);
  CHECK(tension.back() == Approx(weight).epsilon(1e-6));
  CHECK(tension.front() > tension.back());  // the rope's own weight above the hook
  CHECK(session.kineticEnergy() == 0.0);

  // Moving, at a sample time: the recorder's energies.
  for (int k = 1; k <= 150; ++k) {
    lift.apply(lift.feedback(session.time()));
    session.advanceTo(0.02 * k);
  }
  const ResultsRecorder& recorder = *session.recorder();
  REQUIRE(recorder.time().back() == Approx(session.time()).epsilon(1e-15));
  CHECK(session.kineticEnergy() == Approx(recorder.kineticEnergy().back()).epsilon(1e-12));
  CHECK(session.potentialEnergy() == Approx(recorder.potentialEnergy().back()).epsilon(1e-12));
  CHECK(session.kineticEnergy() > 1e3);
  CHECK(session.constraintLoad(session.constraint("hook")).force.norm() != Approx(weight).epsilon(1e-3));

  CHECK_THROWS_WITH(session.constraint("hok"), Catch::Contains("did you mean 'hook'"));
  CHECK_THROWS_WITH(session.ropeTensions("hoist"), Catch::Contains("hoist_rope"));
}

TEST_CASE("The drives' and winches' powers, integrated along a lift, are the energy books' work", "[session]") {
  // The books integrate λ·Φ_t and the elements' explicit time power as IDAS quadratures; the
  // powers sampled every 20 ms by the trapezoidal rule must give the same work to its O(h²).
  Session session(kCraneInputs, true);
  Lift lift(session);
  const int slewing = session.constraint("slewing");
  const auto powers = [&] {
    return std::array<double, 3>{session.drivePower(slewing), session.winchPower("hoist_rope"),
                                 session.winchPower("luffing_rope")};
  };
  std::array<double, 3> before = powers(), work{};
  CHECK(before == std::array<double, 3>{});  // at rest
  for (int k = 1; k <= 400; ++k) {
    lift.apply(lift.feedback(session.time()));
    session.advanceTo(0.02 * k);
    const std::array<double, 3> now = powers();
    for (int d = 0; d < 3; ++d) work[d] += 0.5 * 0.02 * (before[d] + now[d]);
    before = now;
  }
  const ResultsRecorder& recorder = *session.recorder();
  REQUIRE(recorder.time().back() == Approx(session.time()).epsilon(1e-15));
  INFO("slewing " << work[0] << " J, hoist " << work[1] << " J, luffing " << work[2] << " J; books: drives "
                  << recorder.driveWork().back() << " J, winches " << recorder.winchWork().back() << " J");
  CHECK(work[0] == Approx(recorder.driveWork().back()).epsilon(1e-3));
  CHECK(work[1] + work[2] == Approx(recorder.winchWork().back()).epsilon(1e-3));
  CHECK(work[1] > 5e6);  // the hoist lifts the 390 t load by 2.2 m: 8.3 MJ (books 2e-4 from the sampled work)
  CHECK(std::abs(work[0]) > 1e3);
  CHECK_THROWS_WITH(session.winchPower("hoist"), Catch::Contains("hoist_rope"));
}

TEST_CASE("A reeved rope's part tensions and winch power, its sheaves' losses in the winch's work", "[session][reeving]") {
  // configs/hook_block.yaml: a 10 t hook block hoisted 1 m on 4 falls over sheaves of efficiency
  // 0.98; the winch reels 4 m in 9 s. Stepped every 10 ms (the run's steps do not depend on it).
  Session session(std::string(CRANESIM_SOURCE_DIR) + "/configs/hook_block.yaml", true);
  constexpr double kWeight = 1.0e4 * 9.81, kEta = 0.98;
  const int falls = 4, block = session.joint("hook_block.origin");

  // At rest, with the drawing's grips, every part carries the same tension: W/4 on
  // falls leaning 0.1 m in 10 m (cos = 1 − 5e-5).
  std::vector<double> tension = session.ropeTensions("hoist");
  REQUIRE(tension.size() == 5 * kTensionPoints);  // the lead line and 4 falls
  for (const double T : tension) CHECK(T == Approx(kWeight / falls).epsilon(2e-4));
  CHECK(*std::max_element(tension.begin(), tension.end()) - *std::min_element(tension.begin(), tension.end()) <
        1e-9 * kWeight);
  CHECK(session.winchPower("hoist") == 0.0);

  const double start = session.jointPosition(block).z();
  double before = 0.0, work = 0.0, steady_pull = 0.0;
  for (int k = 1; k <= 1200; ++k) {
    session.advanceTo(0.01 * k);
    const double now = session.winchPower("hoist");
    work += 0.5 * 0.01 * (before + now);
    before = now;
    if (k == 500) steady_pull = session.ropeTensions("hoist").front();  // mid-lift at 0.5 m/s
  }
  const ResultsRecorder& recorder = *session.recorder();
  REQUIRE(recorder.time().back() == Approx(session.time()).epsilon(1e-15));
  const double lift = session.jointPosition(block).z() - start;
  INFO("winch work " << work << " J, books " << recorder.winchWork().back() << " J, lift " << lift << " m");
  CHECK(work == Approx(recorder.winchWork().back()).epsilon(1e-5));  // measured 4e-7
  // Hoisting steadily the line pull is W (1 − η) / (η (1 − η⁴)) (elements/reeved_rope.hpp), so
  // the winch pays 4 × that per metre of lift, 5.2 % more than the load's W: the sheaves' loss.
  const double pull = kWeight * (1.0 - kEta) / (kEta * (1.0 - std::pow(kEta, falls)));
  CHECK(steady_pull == Approx(pull).epsilon(2e-4));
  // 4 m of 48 m of rope reeled, the strain ε₀ = (W/4)/EA before and ε₁ = T₀/EA after (the
  // sheaves' grips hold the tensions they stopped with, the lead line's higher): the chords'
  // Σℓ = L (1 + ε) shrink by 4 per metre of lift, so the block rises 1 + ε₁ − 48 (ε₁ − ε₀)/4.
  const double EA = 1.0e11 * std::numbers::pi * 0.008 * 0.008;
  const double strain = kWeight / falls / EA, held_strain = session.ropeTensions("hoist").front() / EA;
  INFO("strain before " << strain << ", after " << held_strain);
  CHECK(held_strain > strain);
  // Within 0.1 mm (the falls lean, the block still sways); equal strains would give 0.3 mm more.
  CHECK(lift == Approx(1.0 + held_strain - 48.0 * (held_strain - strain) / falls).epsilon(1e-4));
  CHECK(work / (kWeight * lift) == Approx(falls * pull / kWeight).epsilon(1e-3));

  // The last sample's part tensions are the results file's.
  tension = session.ropeTensions("hoist");
  const std::vector<double>& recorded = recorder.partTensions(0);
  REQUIRE(recorded.size() == 5 * recorder.samples());
  for (int part = 0; part < 5; ++part)
    CHECK(tension[static_cast<std::size_t>(part * kTensionPoints)] ==
          Approx(recorded[recorded.size() - 5 + static_cast<std::size_t>(part)]).epsilon(1e-12));
}

TEST_CASE("Commands at times summed from a sample period pass a breakpoint within rounding of them",
          "[session]") {
  // A load that gusts from 2 s to 5 s: breakpoints at 2 and 5 s, which a caller adding 0.02 s to
  // the time reaches within rounding (1.9999999999999998 s), not exactly.
  Session session(test::craneInputsWithGust());
  double t = 0.0;
  for (int k = 0; k < 300; ++k) {
    t += 0.02;
    REQUIRE(session.advanceTo(t));
    REQUIRE(session.time() == Approx(t).margin(1e-12));
  }
  CHECK(session.outcome().statistics.restarts == 2);
  CHECK(std::abs(session.jointPosition(session.joint("load.origin")).y()) > 0.05);  // the gust pushed the load
}

TEST_CASE("A restored run goes on with the sheaves' grips it was saved with", "[session][reeving][grip]") {
  // configs/hook_block.yaml: hoisting steadily at 5 s every sheave slips (grip −1); by 12 s the
  // winch has stopped and the block's settling has turned the grips part of the way back. Restored
  // to 5 s after that, the run must take up the 5 s grips, not the 12 s ones (from where the rope
  // stood at 12 s, the 5 s state lies 1 m of lowering back: grips +1, the ratios reversed).
  Session session(std::string(CRANESIM_SOURCE_DIR) + "/configs/hook_block.yaml", false);
  session.advanceTo(5.0);
  const SimulationState saved = session.save();
  const std::vector<double> straight = session.ropeTensions("hoist");
  session.advanceTo(12.0);
  const std::vector<double> stopped = session.ropeTensions("hoist");
  session.restore(saved);
  const std::vector<double> restored = session.ropeTensions("hoist");
  double apart = 0.0, moved = 0.0;
  for (std::size_t k = 0; k < straight.size(); ++k) {
    apart = std::max(apart, std::abs(restored[k] / straight[k] - 1.0));
    moved = std::max(moved, std::abs(stopped[k] / straight[k] - 1.0));
  }
  INFO("restored tensions off the straight run's by " << apart << "; the stopped run's grips moved them by " << moved);
  CHECK(moved > 1e-3);
  CHECK(apart < 1e-6);
}
