#include "cranesim/study/case_runner.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>

#include "cranesim/control/closed_loop.hpp"
#include "cranesim/crane/stated_equilibrium_search.hpp"
#include "cranesim/io/modes_writer.hpp"
#include "cranesim/io/results_writer.hpp"
#include "cranesim/model/compile.hpp"
#include "cranesim/solvers/scene_equilibrium.hpp"
#include "cranesim/study/capacity_search.hpp"
#include "cranesim/study/case_figures.hpp"
#include "cranesim/study/least_stable_angle.hpp"

namespace cranesim {
namespace {

/// The analysis of one case (at a load of a capacity search, at an angle of a least stable angle
/// search); fills the row's status, message and steps and, when complete, its figures.
void analyse(const Study& study, long index, const CaseSetting& setting, const CaseOptions& options, CaseRow& row) {
  const Scene scene = sceneAtStatedEquilibrium(caseScene(study, index, setting), true);
  const Model model = compileModel(scene);
  if (study.analysis == StudyAnalysis::Run) requireResultsFit(scene, model);
  const Assembler assembler(model);
  ResultsRecorder recorder(assembler);
  std::unique_ptr<Session> session;  // a run with feedback (control/closed_loop.hpp) records in its session
  const bool keep = !options.results_path.empty();
  std::optional<ModalResult> modal;
  bool complete = false;
  if (study.analysis == StudyAnalysis::Run) {
    SimulationControl control;
    control.stop_requested = options.stop;
    if (scene.feedback) session = std::make_unique<Session>(scene, true);
    const SimulationOutcome outcome = session ? runClosedLoop(*session, *scene.feedback, control)
                                              : simulate(assembler, runInitialState(scene, model, assembler, true), recorder, control);
    const ResultsRecorder& run = session ? *session->recorder() : recorder;
    if (keep)
      run.write(options.results_path,
                     {scene.path, scene.text, model.solver.formulation == Formulation::GGL ? "ggl" : "baumgarte", model.solver.t_end},
                     outcome);
    complete = outcome.complete;
    row.steps = static_cast<double>(outcome.statistics.steps);
    row.message = outcome.message;
    if (!complete) row.status = options.stop && *options.stop ? kCaseInterrupted : kCaseFailed;
  } else {
    const StaticResult eq = sceneEquilibrium(scene, model, assembler, true);
    row.steps = eq.iterations;
    recorder.sample(eq.t, equilibriumSample(assembler, eq).data(), WorkTerms{});
    if (study.analysis == StudyAnalysis::Modes) {
      modal = computeModes(model, eq.q, eq.t, study.mode_count);
      if (keep) writeModes(options.results_path, model, eq.q, *modal, {scene.path, scene.text, eq.t, {}});
      complete = true;
    } else {
      row.message = equilibriumInstability(model, eq, true);
      complete = row.message.empty();
      SimulationOutcome outcome;
      outcome.complete = complete;
      outcome.t_reached = eq.t;
      outcome.message = row.message;
      if (keep) recorder.write(options.results_path, {scene.path, scene.text, "static", eq.t}, outcome);
      if (!complete) row.status = kCaseFailed;
    }
  }
  if (!complete) return;
  row.status = kCaseComplete;
  row.figures = caseFigures(study, scene, model, session ? *session->recorder() : recorder, modal ? &*modal : nullptr);
}

/// The row of case `index` analysed once (at a load or an angle of a search).
CaseRow analysedCase(const Study& study, long index, const CaseSetting& setting, const CaseOptions& options) {
  CaseRow row;
  row.index = index;
  row.figures.assign(study.figures.size(), std::numeric_limits<double>::quiet_NaN());
  try {
    analyse(study, index, setting, options, row);
  } catch (const SceneError& e) {
    row.status = kCaseBadInput;
    row.message = e.what();
  } catch (const std::exception& e) {
    row.status = kCaseFailed;
    row.message = e.what();
  }
  return row;
}

/// The case at `angle` (none: the scene's): analysed once, or with `capacity` its capacity
/// by bisection.
CaseRow caseAtAngle(const Study& study, long index, std::optional<double> angle, const CaseOptions& options) {
  if (!study.capacity) return analysedCase(study, index, {std::nullopt, angle}, options);
  CaseOptions bisecting = options;
  bisecting.results_path.clear();
  CaseRow row = searchCapacity(study, [&](double load) { return analysedCase(study, index, {load, angle}, bisecting); });
  // The full results of the row's load: the capacity, or the bracket's end the row is of.
  if (!options.results_path.empty() && row.status == kCaseComplete)
    analysedCase(study, index, {std::isnan(row.capacity) ? study.capacity->from : row.capacity, angle}, options);
  return row;
}

}  // namespace

CaseRow runCase(const Study& study, long index, const CaseOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  CaseRow row;
  if (!study.least_stable) {
    row = caseAtAngle(study, index, std::nullopt, options);
  } else {
    // The search at the case's load (with `capacity`, the bracket's light end), then the case
    // at the angle found: that search's row, or with `capacity` the bisection there.
    CaseOptions searching = options;
    searching.results_path.clear();
    const std::optional<double> load = study.capacity ? std::optional<double>(study.capacity->from) : std::nullopt;
    const CaseRow worst = searchLeastStableAngle(study, [&](double angle) { return analysedCase(study, index, {load, angle}, searching); });
    if (worst.status != kCaseComplete || !study.capacity) {
      row = worst;
      if (!options.results_path.empty() && row.status == kCaseComplete) analysedCase(study, index, {load, row.least_stable_angle}, options);
    } else {
      row = caseAtAngle(study, index, worst.least_stable_angle, options);
      if (row.status != kCaseInterrupted) row.steps += worst.steps;
      row.least_stable_angle = worst.least_stable_angle;
      row.worst_grid_angle = worst.worst_grid_angle;
      row.least_stable_value = worst.least_stable_value;
    }
  }
  row.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return row;
}

}  // namespace cranesim
