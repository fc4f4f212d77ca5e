// bench_session_stepping: the thesis crane (condensed lattice sections) driven step by step at
// 50 Hz through a session (benchmarks/README.md). The 60 s combined motion of 8.3.2 is commanded
// sample by sample: each drive's speed is its trapezoid's speed at the sample (held for 20 ms) and
// the slewing rate adds a sway-damping feedback on the load's swing across the boom, so every
// command differs from the last. Side by side, in one run:
//   - profiles:   the combined motion's trapezoids as the drives' profiles, integrated as
//                 `crane-sim run` integrates them;
//   - inputs:     the session with the drives as inputs (configs/crane_inputs.yaml), a first-
//                 and a second-order lag;
//   - tables:     the same commands written into the scene beforehand as piecewise-linear
//                 length and angle tables (what a user had to do without inputs): every knot is
//                 a breakpoint that restarts the integrator.
// All on the condensed crane (crane_inputs.yaml). For each: wall time (median of --reps),
// real-time factor, steps, Jacobians, restarts, and the hook's largest distance over the run from
// the same commands at --ref-rtol (not for the tables).

#include <fmt/format.h>


#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "cranesim/io/scene_reader.hpp"
#include "cranesim/session/session.hpp"
#include "run_statistics.hpp"

namespace {

using namespace cranesim;

struct Options {
  std::string configs = "configs";
  std::string out = "benchmarks/results/session_stepping.csv";
  double t_end = 60.0;
  double dt = 0.02;
  double rtol = 1e-4;
  double ref_rtol = 1e-8;
  int reps = 3;
  std::string only;       // one row: profiles, inputs1, inputs2 or tables
  bool reference = true;  // the runs at ref_rtol, for the error
};

/// The drives' commands of one sample: slewing rate (°/s), hoist and luffing rope speeds (m/s).
struct Commands {
  double slewing = 0.0, hoist = 0.0, luffing = 0.0;
};

/// The speed of a trapezoid profile (E-1..E-5) at t.
double trapezoidSpeed(const TrapezoidProfile& p, double t) {
  return Profile(p)(seeded<double, 1>(t, 0)).derivatives()(0);
}

/// The combined motion of crane_combined.yaml as speeds, the slewing rate with a sway-damping
/// term: the boom head moves across the boom at c · (the hook's offset from the head across
/// it), c = 0.44 1/s ≈ the pendulum's ω at 50 m, which damps the swing.
Commands combinedMotion(const Session& s, int hook, int head) {
  const double t = s.time();
  static const TrapezoidProfile hoist{53.9937, -20, 0, 40, 5, 5}, slewing{0, 45, 10, 20, 5, 5},
      luffing{7.0608, 5, 20, 20, 5, 5};
  const Vec3 r = s.jointPosition(head);
  const double radius = std::sqrt(r.x() * r.x() + r.y() * r.y());  // as python_stepping.py rounds it
  const Vec3 across(-r.y() / radius, r.x() / radius, 0.0);
  const double sway = (s.jointPosition(hook) - r).dot(across);
  constexpr double c = 0.44;
  return {trapezoidSpeed(slewing, t) + c * sway / radius * 180.0 / std::numbers::pi, trapezoidSpeed(hoist, t),
          trapezoidSpeed(luffing, t)};
}

struct Run {
  double wall = 0.0;  // s, the stepping only
  SolverStatistics statistics;
  std::vector<Vec3> hook;      // at every sample
  std::vector<Commands> sent;  // the commands as held
  bool complete = true;
};

/// Steps the session to t_end by dt: with inputs, commanding each sample by `law` (or replaying
/// `replay`); without, as the scene's profiles run.
template <class Law> Run stepped(Session& s, const Options& o, const Law& law, const std::vector<Commands>* replay) {
  const int hook = s.joint("load.origin");
  const bool inputs = !s.model().inputs.empty();
  const int slew = inputs ? s.input("slewing") : -1, hoist = inputs ? s.input("hoist_rope") : -1,
            luff = inputs ? s.input("luffing_rope") : -1;
  Run run;
  const auto start = std::chrono::steady_clock::now();
  const int samples = static_cast<int>(std::lround(o.t_end / o.dt));
  for (int k = 0; k < samples; ++k) {
    if (inputs) {
      const Commands c = replay ? (*replay)[static_cast<std::size_t>(k)] : law(s);
      run.sent.push_back({s.setInput(slew, c.slewing), s.setInput(hoist, c.hoist), s.setInput(luff, c.luffing)});
    }
    if (!s.advanceTo((k + 1) * o.dt) && k + 1 < samples) {
      run.complete = false;
      break;
    }
    run.hook.push_back(s.jointPosition(hook));
  }
  run.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.statistics = s.outcome().statistics;
  return run;
}

Scene withTolerance(Scene scene, double rtol, double t_end) {
  scene.solver.rtol = rtol;
  scene.solver.atol = AbsoluteTolerance::uniform(0.1 * rtol);
  scene.solver.t_end = t_end;
  return scene;
}

Scene withOrder(Scene scene, int order) {
  for (MemberSpec& m : scene.members)
    if (m.length && m.length->input()) m.length->input()->spec.order = order;
  for (ConstraintSpec& c : scene.constraints)
    if (c.drive && c.drive->input()) c.drive->input()->spec.order = order;
  return scene;
}

/// The combined motion's trapezoids (crane_combined.yaml) as the drives' profiles, with its
/// step limit (none): the run `crane-sim run` makes of the condensed crane.
Scene withProfiles(Scene scene) {
  scene.solver.max_step = 0.0;
  for (MemberSpec& m : scene.members) {
    if (m.name == "hoist_rope") m.length = Profile(TrapezoidProfile{53.9937, -20, 0, 40, 5, 5});
    if (m.name == "luffing_rope") m.length = Profile(TrapezoidProfile{7.0608, 5, 20, 20, 5, 5});
  }
  for (ConstraintSpec& c : scene.constraints)
    if (c.name == "slewing") c.drive = Profile(TrapezoidProfile{0, 45, 10, 20, 5, 5}, std::numbers::pi / 180.0);
  return scene;
}

/// The commands as the drives' values: piecewise-linear tables through the integrated speeds.
Scene withTables(Scene scene, const std::vector<Commands>& sent, double dt) {
  TableProfile slew, hoist, luff;
  for (TableProfile* p : {&slew, &hoist, &luff}) p->interpolation = Interpolation::Linear;
  double a = 0.0, h = 53.9937, l = 7.0608;
  for (std::size_t k = 0; k <= sent.size(); ++k) {
    const double t = static_cast<double>(k) * dt;
    slew.t.push_back(t), hoist.t.push_back(t), luff.t.push_back(t);
    slew.y.push_back(a), hoist.y.push_back(h), luff.y.push_back(l);
    if (k < sent.size()) a += sent[k].slewing * dt, h += sent[k].hoist * dt, l += sent[k].luffing * dt;
  }
  for (MemberSpec& m : scene.members) {
    if (m.name == "hoist_rope") m.length = Profile(hoist);
    if (m.name == "luffing_rope") m.length = Profile(luff);
  }
  for (ConstraintSpec& c : scene.constraints)
    if (c.name == "slewing") c.drive = Profile(slew, std::numbers::pi / 180.0);
  return scene;
}

double largestDistance(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double largest = 0.0;
  for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k) largest = std::max(largest, (a[k] - b[k]).norm());
  return a.size() == b.size() ? largest : std::numeric_limits<double>::quiet_NaN();
}

using cranesim_bench::machineName;
using cranesim_bench::median;

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--configs") o.configs = value();
    else if (arg == "--out") o.out = value();
    else if (arg == "--t-end") o.t_end = std::stod(value());
    else if (arg == "--rtol") o.rtol = std::stod(value());
    else if (arg == "--ref-rtol") o.ref_rtol = std::stod(value());
    else if (arg == "--reps") o.reps = std::stoi(value());
    else if (arg == "--only") o.only = value();
    else if (arg == "--no-reference") o.reference = false;
    else if (arg == "--quick") o.t_end = 4.0, o.ref_rtol = 1e-6, o.reps = 1;
    else if (arg == "--help" || arg == "-h") {
      fmt::print("bench_session_stepping [--configs DIR] [--out CSV] [--t-end 60] [--rtol 1e-4] [--ref-rtol 1e-8] "
                 "[--reps 3] [--only profiles|inputs1|inputs2|tables] [--no-reference] [--quick]\n");
      return 0;
    } else {
      fmt::print(stderr, "unknown option {}\n", arg);
      return 2;
    }
  }
  const Scene inputs = readScene(o.configs + "/crane_inputs.yaml");
  const Scene combined = withProfiles(inputs);  // the same condensed crane, its drives as profiles

  std::ofstream csv(o.out);
  csv << "method,order,rtol,t_end,sample_interval,wall_s,real_time_factor,steps,jacobians,error_test_failures,"
         "restarts,hook_error_m,complete,machine\n";
  const std::string machine = machineName();
  bool all_complete = true;
  const auto row = [&](const std::string& method, int order, const std::vector<Run>& runs, const Run& reference) {
    std::vector<double> walls;
    for (const Run& r : runs) walls.push_back(r.wall);
    const Run& r = runs.front();
    const double wall = median(walls);
    const double error = o.reference && !reference.hook.empty() ? largestDistance(r.hook, reference.hook)
                                                                : std::numeric_limits<double>::quiet_NaN();
    const SolverStatistics& st = r.statistics;
    all_complete = all_complete && r.complete && reference.complete;
    csv << fmt::format("{},{},{:g},{:g},{:g},{:.4f},{:.1f},{},{},{},{},{:.3e},{},\"{}\"\n", method, order, o.rtol, o.t_end,
                       o.dt, wall, o.t_end / wall, st.steps, st.jacobian_evaluations, st.error_test_failures, st.restarts,
                       error, r.complete && reference.complete ? 1 : 0, machine);
    fmt::print("{:<9} order {}  {:7.3f} s  {:6.1f}× real time  steps {:6}  Jacobians {:5}  restarts {:5}  hook error {:.2e} m\n",
               method, order, wall, o.t_end / wall, st.steps, st.jacobian_evaluations, st.restarts, error);
    csv.flush();
  };
  const auto noLaw = [](const Session&) { return Commands{}; };
  // The same scene and commands at ref_rtol (an empty run, error NaN, with --no-reference).
  const auto reference = [&](const Scene& scene, const std::vector<Commands>* replay) {
    if (!o.reference) return Run{};
    Session s(scene);
    return stepped(s, o, noLaw, replay);
  };

  const auto wanted = [&](const std::string& row) { return o.only.empty() || o.only == row; };
  if (wanted("profiles")) {  // the scene's smooth profiles, as crane-sim run integrates them
    std::vector<Run> runs;
    for (int k = 0; k < o.reps; ++k) {
      Session s(withTolerance(combined, o.rtol, o.t_end));
      runs.push_back(stepped(s, o, noLaw, nullptr));
    }
    row("profiles", 0, runs, reference(withTolerance(combined, o.ref_rtol, o.t_end), nullptr));
  }
  std::vector<Commands> first_order_commands;
  for (const int order : {1, 2}) {  // the drives as inputs, commanded by the feedback law
    if (!wanted("inputs" + std::to_string(order)) && !(order == 1 && wanted("tables"))) continue;
    std::vector<Run> runs;
    for (int k = 0; k < o.reps; ++k) {
      Session s(withOrder(withTolerance(inputs, o.rtol, o.t_end), order));
      const int hook = s.joint("load.origin"), head = s.joint("head.sheave");
      runs.push_back(stepped(s, o, [&](const Session& at) { return combinedMotion(at, hook, head); }, nullptr));
    }
    if (order == 1) first_order_commands = runs.front().sent;
    if (!wanted("inputs" + std::to_string(order))) continue;
    row("inputs", order, runs, reference(withOrder(withTolerance(inputs, o.ref_rtol, o.t_end), order), &runs.front().sent));
  }
  if (wanted("tables")) {  // the same commands as tables written beforehand
    std::vector<Run> runs;
    for (int k = 0; k < o.reps; ++k) {
      Session s(withTolerance(withTables(combined, first_order_commands, o.dt), o.rtol, o.t_end));
      runs.push_back(stepped(s, o, noLaw, nullptr));
    }
    // No reference: a run at ref_rtol restarting at every one of the tables' knots takes minutes.
    row("tables", 0, runs, Run{});
  }
  fmt::print("results: {}\n", o.out);
  return all_complete ? 0 : 1;
}
