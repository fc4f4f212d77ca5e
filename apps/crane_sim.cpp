// crane-sim: simulate a multibody scene written in YAML and write HDF5 results.
//   crane-sim run SCENE [-o results.h5] [--quiet]
//   crane-sim check SCENE
//   crane-sim modes SCENE [--count N] [-o modes.h5]
//   crane-sim study STUDY [-o table.h5] [--jobs N] [--resume]
//   crane-sim info RESULTS
// Exit codes: 0 success, 1 solver failure (results kept, marked incomplete), 2 bad input.

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <memory>

#include "cranesim/control/closed_loop.hpp"
#include "cranesim/crane/crane_figures.hpp"
#include "cranesim/crane/stated_equilibrium_search.hpp"
#include "cranesim/crane/mode_labels.hpp"
#include "cranesim/crane/support_reading.hpp"
#include "cranesim/io/command_line.hpp"
#include "cranesim/io/modes_writer.hpp"
#include "cranesim/io/results_info.hpp"
#include "cranesim/io/results_writer.hpp"
#include "cranesim/io/scene_reader.hpp"
#include "cranesim/model/compile.hpp"
#include "cranesim/model/summary.hpp"
#include "cranesim/solvers/modes.hpp"
#include "cranesim/solvers/scene_equilibrium.hpp"
#include "cranesim/study/study_command.hpp"
#include "cranesim/version.hpp"

namespace {

using namespace cranesim;

std::atomic<bool> g_interrupted{false};
std::atomic<int> g_signal{0};

/// SIGINT (Ctrl-C), SIGTERM (a batch system's stop) and SIGHUP (a closed terminal) end a run
/// cleanly: the time loop stops at its next step and the results so far are written, marked
/// incomplete; the exit code is then 128 + the signal's number, as the shell's.
void stopOnSignals() {
  struct sigaction action {};
  action.sa_handler = [](int signal) {
    g_signal = signal;
    g_interrupted = true;
  };
  sigemptyset(&action.sa_mask);
  for (const int signal : {SIGINT, SIGTERM, SIGHUP}) sigaction(signal, &action, nullptr);
}

/// A one-line progress display on a terminal: simulated time, percent, real-time factor.
class ProgressLine {
 public:
  ProgressLine(bool enabled, double t0, double t1) : enabled_(enabled), t0_(t0), t1_(t1) {}
  void update(double t) {
    if (!enabled_) return;
    const auto now = std::chrono::steady_clock::now();
    if (now - last_ < std::chrono::milliseconds(200)) return;
    last_ = now;
    const double wall = std::chrono::duration<double>(now - start_).count();
    fmt::print(stderr, "\r  t = {:9.4f} s  ({:5.1f} %)  real-time factor {:8.3g}   ", t, 100.0 * (t - t0_) / (t1_ - t0_),
               (t - t0_) / std::max(wall, 1e-9));
  }
  void finish() {
    if (enabled_) fmt::print(stderr, "\r{:70}\r", "");
  }

 private:
  bool enabled_;
  double t0_, t1_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now(), last_{};
};

/// When a run writes its results so far (ResultsRecorder::writeCheckpoint): 10 s of wall time
/// after its start and after every checkpoint, or 20 times as long as the last checkpoint took,
/// whichever is later, so that checkpoints cost at most 5 % of a run. A failed checkpoint is
/// reported once and the run goes on (its final write reports again).
class CheckpointClock {
 public:
  bool due() const { return seconds(std::chrono::steady_clock::now() - last_) >= wait_; }
  template <class Write> void write(const Write& write) {
    const auto start = std::chrono::steady_clock::now();
    try {
      write(seconds(start - begin_));
    } catch (const std::exception& e) {
      if (!failed_) fmt::print(stderr, "warning: checkpoint not written: {}\n", e.what());
      failed_ = true;
    }
    last_ = std::chrono::steady_clock::now();
    wait_ = std::max(kMinimumWait, 20.0 * seconds(last_ - start));
  }

 private:
  static constexpr double kMinimumWait = 10.0;  // s
  static double seconds(std::chrono::steady_clock::duration d) { return std::chrono::duration<double>(d).count(); }
  std::chrono::steady_clock::time_point begin_ = std::chrono::steady_clock::now(), last_ = begin_;
  double wait_ = kMinimumWait;
  bool failed_ = false;
};

/// The equilibrium as an engineer reads it: where the bodies are, and what each joint carries
/// (the force of its x, y, z rows; the norm of its other rows: moments, or a drive's force or
/// torque). A rope's tension is the force of the joint at its end.
void printEquilibriumReport(const Model& model, const StaticResult& eq) {
  fmt::print("{:<24} {:>12} {:>12} {:>12}\n", "body", "x [m]", "y [m]", "z [m]");
  for (std::size_t n = 0; n < model.nodes.size(); ++n) {
    if (!model.nodes[n].member.empty()) continue;
    const Vec3 r = model.nodeFrame(eq.q.data(), static_cast<int>(n)).r;
    fmt::print("{:<24} {:>12.4f} {:>12.4f} {:>12.4f}\n", model.nodes[n].name, r.x(), r.y(), r.z());
  }
  fmt::print("{:<24} {:>12} {:>22}\n", "constraint", "force [N]", "moment or drive");
  for (const Constraint& c : model.constraints) {
    const ConstraintLoad load = constraintLoad(c, eq.lambda.data());
    fmt::print("{:<24} {:>12.5g} {:>22.5g}\n", c.name, load.force, load.other);
  }
  if (const auto& supports = model.envelope.supports) {
    const VecX rest = VecX::Zero(model.nv);
    const ElementInput in{eq.q.data(), rest.data(), rest.data(), eq.t, model.gravity};
    fmt::print("{}", describeSupportReading(*supports, readSupports(model, *supports, in)));
  }
}

/// How far the energy balance may drift, relative to the run's energy scale, in units of rtol
/// before `run` warns. Integrated with error control, the books drift by 14–47 rtol on the free
/// triple jib pendulum from rtol 1e-3 to 1e-8 and by less than 0.05 rtol on the crane's motions;
/// a quadrature outside the error test can miss a short pulse of power (a damped rope snapping
/// taut: 1700 rtol, 3.4 rtol with solver.work_error_control).
constexpr double kBalanceWarning = 100.0;

/// Whether the balance drifts by more than the tolerances explain (kBalanceWarning), in a run
/// that moves energy at all: T + V themselves are known to about rtol of their size (V's origin
/// is arbitrary), so a run at rest, whose energy scale is rounding, has nothing to warn about.
bool balanceOff(const ResultsRecorder& recorder, double rtol) {
  double size = 0.0;
  for (std::size_t s = 0; s < recorder.samples(); ++s)
    size = std::max(size, std::abs(recorder.kineticEnergy()[s] + recorder.potentialEnergy()[s]));
  const double drift = recorder.relativeBalanceDrift();
  return drift > kBalanceWarning * rtol && drift * recorder.energyScale() > rtol * size;
}

int run(const std::string& scene_path, std::string out, bool quiet) {
  stopOnSignals();
  const Scene scene = sceneAtStatedEquilibrium(readScene(scene_path), quiet);
  out = outputPath(scene_path, out, ".h5");
  const Model model = compileModel(scene);
  requireResultsFit(scene, model);
  const Assembler assembler(model);
  // A scene with feedback runs as a session that its controller steps (control/closed_loop.hpp).
  const std::unique_ptr<Session> session = scene.feedback ? std::make_unique<Session>(scene, true) : nullptr;
  ResultsRecorder open_loop(assembler);
  const ResultsRecorder& recorder = session ? *session->recorder() : open_loop;
  const ResultsRecorder::Metadata meta{scene_path, scene.text,
                                       model.solver.formulation == Formulation::GGL ? "ggl" : "baumgarte",
                                       model.solver.t_end};
  ProgressLine progress(!quiet && isatty(STDERR_FILENO), model.solver.t_start, model.solver.t_end);
  CheckpointClock checkpoints;
  SimulationControl control;
  // A scene that asks to stop outside the envelope is stopped as a signal would stop it; so is
  // a carriage that has tipped (past its tipping point a run follows a crash the model does not
  // describe, and slowly).
  std::atomic<bool> stop{false};
  bool left_envelope_at_step = false, tipped_at_step = false;
  control.on_step = [&](double t) {
    progress.update(t);
    if (recorder.samples() > 0 && checkpoints.due()) checkpoints.write([&](double wall) { recorder.writeCheckpoint(out, meta, wall); });
    if (model.solver.stop_outside_envelope && recorder.envelope().lastSampleOutside()) left_envelope_at_step = stop = true;
    if (recorder.envelope().lastSampleTipped()) tipped_at_step = stop = true;
    if (g_interrupted) stop = true;
  };
  control.stop_requested = &stop;
  SimulationOutcome outcome = session ? runClosedLoop(*session, *scene.feedback, control)
                                      : simulate(assembler, runInitialState(scene, model, assembler, quiet), open_loop, control);
  progress.finish();
  const double stopped_at = recorder.time().empty() ? outcome.t_reached : recorder.time().back();
  if (tipped_at_step && !g_interrupted)
    outcome.message = fmt::format("stopped at t = {:.6g} s: the carriage '{}' has tipped; a run ends where its carriage tips", stopped_at,
                                  model.envelope.supports->body);
  else if (left_envelope_at_step && !g_interrupted)
    outcome.message = fmt::format("stopped at t = {:.6g} s: the run left the crane's envelope (solver.outside_envelope: stop)", stopped_at);
  recorder.write(out, meta, outcome);

  const SolverStatistics& st = outcome.statistics;
  const double drift = recorder.relativeBalanceDrift();
  const auto& rp = recorder.positionResidual();
  const std::vector<EnvelopeEvent> envelope = recorder.envelope().events();
  const bool left_envelope = leavesEnvelope(envelope);
  if (!quiet || !outcome.complete) {
    fmt::print(stderr, "{}{} t = {:g} … {:g} s in {:.3g} s wall (real-time factor {:.3g})\n",
               outcome.complete ? "completed" : "stopped", left_envelope ? ", leaving the crane's envelope," : "",
               model.solver.t_start, outcome.t_reached, st.wall_time_s,
               (outcome.t_reached - model.solver.t_start) / std::max(st.wall_time_s, 1e-9));
    fmt::print(stderr, "  steps {}, residual evaluations {}, Jacobians {}, error-test failures {}, "
                       "nonlinear failures {}, restarts {}\n",
               st.steps, st.residual_evaluations, st.jacobian_evaluations, st.error_test_failures,
               st.nonlinear_failures, st.restarts);
    fmt::print(stderr, "  max |Φ| {:.3g} at steps, {:.3g} at samples; energy balance drift {:.2g} of the run's energy "
                       "scale ({:.3g} J)\n",
               st.max_step_constraint_residual, rp.empty() ? 0.0 : *std::max_element(rp.begin(), rp.end()), drift,
               recorder.energyScale());
    fmt::print(stderr, "  results: {}{}\n", out, outcome.complete ? "" : " (incomplete)");
  }
  if (const auto& supports = model.envelope.supports; supports && !quiet)
    fmt::print(stderr, "{}", summarizeSupportReadings(*supports, recorder.envelope().time(), recorder.envelope().supports()));
  if (left_envelope || (!quiet && !envelope.empty())) {
    fmt::print(stderr, "{}\n", left_envelope ? "warning: the run left the crane's envelope:" : "envelope: within; contacts:");
    std::string lines = describeEnvelopeEvents(envelope);
    for (std::size_t at = 0; at < lines.size();) {
      const std::size_t end = lines.find('\n', at);
      fmt::print(stderr, "  {}\n", lines.substr(at, end - at));
      at = end + 1;
    }
  }
  if (balanceOff(recorder, model.solver.rtol))
    fmt::print(stderr, "warning: the energy balance drifts by {:.2g} of the run's energy scale, more than {:g} × rtol = {:.2g}: "
                       "the run is less accurate than solver.rtol asks{}; tighten solver.rtol and compare\n",
               drift, kBalanceWarning, kBalanceWarning * model.solver.rtol,
               model.solver.work_error_control ? "" : ", or the works' integration missed a short pulse of power (set "
                                                       "solver.work_error_control: true to keep it in the error test)");
  if (!outcome.complete) {
    fmt::print(stderr, "error: {}\n", outcome.message);
    return g_interrupted ? 128 + g_signal : kExitSolverFailure;
  }
  return 0;
}

/// The equilibrium `static` and `modes` start from, solved from the scene's consistent initial
/// state and reported.
StaticResult reportedEquilibrium(const Scene& scene, const Model& model, const Assembler& assembler) {
  locateCrane(scene, model);
  const StaticResult eq = sceneEquilibrium(scene, model, assembler, false);
  printEquilibriumReport(model, eq);
  fmt::print("{}", describeCraneFigures(craneFigures(scene, model, eq.q.data(), eq.t)));
  return eq;
}

int statics(const std::string& scene_path, std::string out) {
  const Scene scene = sceneAtStatedEquilibrium(readScene(scene_path), false);
  out = outputPath(scene_path, out, "_static.h5");
  const Model model = compileModel(scene);
  const Assembler assembler(model);
  const StaticResult eq = reportedEquilibrium(scene, model, assembler);
  const std::string unstable = equilibriumInstability(model, eq, false);
  const CraneFigures figures = craneFigures(scene, model, eq.q.data(), eq.t);
  writeEquilibriumResults(out, assembler, eq, scene_path, scene.text, unstable, &figures);
  fmt::print(stderr, "  results: {}{}\n", out, unstable.empty() ? "" : " (incomplete)");
  if (unstable.empty()) return 0;
  fmt::print(stderr, "error: {}\n", unstable);
  return kExitSolverFailure;
}

/// Small-vibration modes about the static equilibrium: a table on stdout, frequencies and
/// shapes in the HDF5 file.
int modes(const std::string& scene_path, std::string out, int count) {
  const Scene scene = sceneAtStatedEquilibrium(readScene(scene_path), false);
  out = outputPath(scene_path, out, "_modes.h5");
  const Model model = compileModel(scene);
  const Assembler assembler(model);
  const StaticResult eq = reportedEquilibrium(scene, model, assembler);
  const ModalResult modal = computeModes(model, eq.q, eq.t, count);
  fmt::print("degrees of freedom: {}, rigid-body modes: {}, stiffness asymmetry: {:.2g}\n", modal.free_dofs,
             modal.rigid_modes, modal.stiffness_asymmetry);
  std::vector<std::string> labels;
  if (scene.crane)
    for (const ModeLabel& label : labelModes(scene, model, eq.q, eq.t, modal)) labels.push_back(label.label);
  fmt::print("{:>5}  {:>14}  {:>12}  {:>14}{}\n", "mode", "frequency (Hz)", "period (s)", "ω² (rad²/s²)",
             labels.empty() ? "" : "  moves");
  for (int k = 0; k < modal.frequencies.size(); ++k) {
    const double f = modal.frequencies(k), w2 = modal.omega_squared(k);
    const std::string moves = labels.empty() ? "" : "  " + labels[static_cast<std::size_t>(k)];
    if (modal.rigid[k]) fmt::print("{:>5}  {:>14}  {:>12}  {:>14.6g}{}\n", k + 1, "rigid", "-", w2, moves);
    else if (w2 < 0.0) fmt::print("{:>5}  {:>14}  {:>12}  {:>14.6g}{}\n", k + 1, "unstable", "-", w2, moves);
    else fmt::print("{:>5}  {:>14.6f}  {:>12.6g}  {:>14.6g}{}\n", k + 1, f, 1.0 / f, w2, moves);
  }
  writeModes(out, model, eq.q, modal, {scene_path, scene.text, eq.t, labels});
  fmt::print(stderr, "  results: {}\n", out);
  return 0;
}

/// Each truss section with its type and fidelity, marked where the fidelity is the scene's
/// defaults.truss_fidelity.
void printTrussFidelities(const Scene& scene) {
  const auto word = [](TrussFidelity f) {
    switch (f) {
      case TrussFidelity::SuperTruss: return "super_truss";
      case TrussFidelity::Condensed: return "condensed";
      case TrussFidelity::Beam: return "beam";
      case TrussFidelity::Members: return "members";
    }
    return "";
  };
  bool header = false;
  for (const MemberSpec& m : scene.members) {
    if (m.type != MemberType::Truss) continue;
    if (!header) fmt::print("{:<24} {:<12} {}\n", "truss section", "type", "fidelity");
    header = true;
    fmt::print("{:<24} {:<12} {}{}\n", m.name, m.truss, word(m.fidelity), m.fidelity_by_default ? " (defaults.truss_fidelity)" : "");
  }
}

int check(const std::string& scene_path) {
  const Scene scene = sceneAtStatedEquilibrium(readScene(scene_path), false);
  const Model model = compileModel(scene);
  locateCrane(scene, model);
  requireResultsFit(scene, model);
  const Assembler assembler(model);
  AssemblyMove move;
  assembledInitialState(assembler, model.solver.t_start, model.q0, model.v0, model.solver.assembly_tolerance, &move);
  fmt::print("{}", modelSummary(assembler));
  printTrussFidelities(scene);
  if (move.visible())
    fmt::print("initial state: assembled; largest move {} (solver.assembly_tolerance = {:g})\n", move.describe(),
               model.solver.assembly_tolerance);
  else
    fmt::print("initial state: consistent as drawn (solver.assembly_tolerance = {:g})\n", model.solver.assembly_tolerance);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{fmt::format("cranesim {} — rigid-flexible multibody simulation of lattice boom cranes", kVersion)};
  app.set_version_flag("--version", std::string(kVersion));
  app.require_subcommand(1);

  std::string scene_path, out_path, results_path;
  bool quiet = false;
  auto* run_cmd = app.add_subcommand("run", "simulate a scene and write HDF5 results");
  run_cmd->add_option("scene", scene_path, "scene file (YAML)")->required();
  run_cmd->add_option("-o,--output", out_path, "results file (default: <scene name>.h5 in the current directory)");
  run_cmd->add_flag("-q,--quiet", quiet, "no progress line and no summary");
  auto* static_cmd = app.add_subcommand("static", "solve the static equilibrium and write it as a one-sample results file");
  static_cmd->add_option("scene", scene_path, "scene file (YAML)")->required();
  static_cmd->add_option("-o,--output", out_path, "results file (default: <scene name>_static.h5 in the current directory)");
  auto* check_cmd = app.add_subcommand("check", "validate a scene and print the model summary");
  check_cmd->add_option("scene", scene_path, "scene file (YAML)")->required();
  int mode_count = 10;
  auto* modes_cmd = app.add_subcommand("modes", "small-vibration modes about the static equilibrium");
  modes_cmd->add_option("scene", scene_path, "scene file (YAML)")->required();
  modes_cmd->add_option("-n,--count", mode_count, "number of lowest modes (0: all)")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  modes_cmd->add_option("-o,--output", out_path, "modes file (default: <scene name>_modes.h5 in the current directory)");
  StudyCommand study;
  auto* study_cmd = app.add_subcommand("study", "run a study: one analysis per case over parameter grids or random draws");
  study_cmd->add_option("study", study.study_path, "study file (YAML)")->required();
  study_cmd->add_option("-o,--output", study.out, "case table (default: <study name>.h5 in the current directory)");
  study_cmd->add_option("-j,--jobs", study.jobs, "cases computed at once by this process (threads)")
      ->check(CLI::Range(1, 1024))->capture_default_str();
  study_cmd->add_flag("--resume", study.resume, "continue a stopped study from its checkpoint (<output>.checkpoint)");
  study_cmd->add_flag("-q,--quiet", study.quiet, "no progress and no summary");
  auto* info_cmd = app.add_subcommand("info", "describe what a results file holds");
  info_cmd->add_option("results", results_path, "results file (HDF5)")->required();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kExitBadInput;
  }
  try {
    if (*run_cmd) return run(scene_path, out_path, quiet);
    if (*check_cmd) return check(scene_path);
    if (*static_cmd) return statics(scene_path, out_path);
    if (*modes_cmd) return modes(scene_path, out_path, mode_count);
    if (*study_cmd) {
      stopOnSignals();
      study.stop = &g_interrupted;
      study.signal = &g_signal;
      return runStudyCommand(study);
    }
    if (*info_cmd) {
      fmt::print("{}", describeResults(results_path));
      return 0;
    }
  } catch (const SceneError& e) {
    fmt::print(stderr, "error: {}: {}\n", *study_cmd ? study.study_path : scene_path, e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return *info_cmd ? kExitBadInput : kExitSolverFailure;
  }
  return 0;
}
