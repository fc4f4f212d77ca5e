// crane-opt: quasi-static optimal control of a crane (thesis chapter 6, 8.4).
//   crane-opt plan TARGET [-o plan.h5] [--threads N] [--quiet]
//       static map → fitted surface → QR end-point trajectory (Ipopt) → control trajectory →
//       verification by simulation (its full results beside the plan: <plan>_simulation.h5); with
//       the target's feedback:, each case open loop and tracked by anti-sway feedback
//   crane-opt map TARGET [-o map.h5] [--threads N] [--quiet]
//       the static map alone
//   mpirun -n N crane-opt plan|map …: the static map's rows farmed out to N ranks
// Exit codes: 0 success, 1 solver failure, 2 bad input (the message names the YAML path and line),
// 3 the verified motion comes closer to an obstacle than the target's clearance margin.

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <filesystem>
#include <optional>

#include "cranesim/io/command_line.hpp"
#include "cranesim/io/plan_writer.hpp"
#include "cranesim/parallel/task_farm.hpp"
#include "cranesim/planning/plan_tracking.hpp"
#include "cranesim/planning/quasi_static_plan.hpp"
#ifdef CRANESIM_WITH_MPI
#include "cranesim/parallel/mpi_farm.hpp"
#endif

namespace {

using namespace cranesim;

/// Whether this process is rank 0 of an MPI job, or runs without one (`mpi` null).
bool isRankZero(const MpiSession* mpi) {
#ifdef CRANESIM_WITH_MPI
  return !mpi || mpi->rank() == 0;
#else
  return mpi == nullptr;
#endif
}

/// Reads the target on every rank; only rank 0 reports a bad one (agreeOnVerdict).
std::optional<TargetSpec> readTargetOnEveryRank(const std::string& target_path, MpiSession* mpi, int& verdict) {
  std::optional<TargetSpec> target;
  verdict = agreeOnVerdict(mpi, inputVerdict(target_path, isRankZero(mpi), [&] { target = readTarget(target_path); }));
  return target;
}

int plan(const std::string& target_path, const std::string& out_arg, int threads, bool quiet, bool map_only,
         MpiSession* mpi) {
  int verdict = 0;
  std::optional<TargetSpec> target = readTargetOnEveryRank(target_path, mpi, verdict);
  if (verdict != 0) return verdict;
  if (threads > 0) target->map.threads = threads;
#ifdef CRANESIM_WITH_MPI
  if (!isRankZero(mpi)) {  // this rank computes rows of the map, then its part is over
    computeStaticMapRowsForRank0(target->scene, target->controls, target->map, *mpi);
    return 0;
  }
#endif
  const std::string out = outputPath(target_path, out_arg, map_only ? "_map.h5" : "_plan.h5");
  const PlanLog log = [quiet](const std::string& line) {
    if (!quiet) fmt::print(stderr, "{}\n", line);
  };
  QuasiStaticPlan result;
  StaticMap map = computeStaticMap(target->scene, target->controls, target->map, log, mpi);
#ifdef CRANESIM_WITH_MPI
  if (mpi) mpi->finish();  // the map was the farmed part; rank 0 goes on alone
#endif
  if (map_only) {
    result.map = std::move(map);
    result.map_s = result.map.time_s;
    writePlan(out, *target, result, true);
    log(fmt::format("static map: {} × {} points, {} failed, rows {:.1f} s on {}; written to {}", result.map.rows(),
                    result.map.columns(), result.map.failures.size(), result.map.sweep_time_s, result.map.execution, out));
    return result.map.failures.empty() ? 0 : kExitSolverFailure;
  }
  result = planQuasiStatic(*target, std::move(map), log);
  const std::string simulation = std::filesystem::path(out).replace_extension().string() + "_simulation.h5";
  try {
    verifyPlan(*target, result, simulation, log);
    if (target->feedback) verifyTracking(*target, result, log);
  } catch (const std::runtime_error& e) {
    writePlan(out, *target, result);
    fmt::print(stderr, "error: {}\n  plan written to {} (verification incomplete)\n", e.what(), out);
    return kExitSolverFailure;
  }
  writePlan(out, *target, result);
  if (const auto& c = result.clearance) {
    const std::string closest = c->part >= 0 ? fmt::format("{} to {} at t = {:.1f} s", c->parts[c->part], c->obstacles[c->obstacle], c->t)
                                             : std::string("no parts");
    fmt::print("minimum clearance {:.2f} m: {}\n", c->distance, closest);
    if (c->failed()) {
      fmt::print(stderr, "error: the verified motion comes closer than the clearance margin {:.3g} m: {} is {:.3g} m from "
                         "obstacle '{}' at t = {:.2f} s\n  plan written to {} (clearance failed)\n",
                 c->margin, c->parts[c->part], c->distance, c->obstacles[c->obstacle], c->t, out);
      return kExitClearanceFailure;
    }
  }
  log(fmt::format("plan written to {}; verification run in {}", out, simulation));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"crane-opt: quasi-static optimal control of a crane (static map, QR trajectory, verification)"};
  app.require_subcommand(1);
  std::string target_path, out_path;
  int threads = 0;
  bool quiet = false;
  CLI::App* plan_cmd = app.add_subcommand("plan", "plan and verify the motion of a target file");
  CLI::App* map_cmd = app.add_subcommand("map", "compute the static map of a target file");
  for (CLI::App* cmd : {plan_cmd, map_cmd}) {
    cmd->add_option("target", target_path, "target file (YAML)")->required()->check(CLI::ExistingFile);
    cmd->add_option("-o,--output", out_path, "results file (HDF5)");
    cmd->add_option("--threads", threads,
                    "threads of the map sweep (default: the target's, else all cores; one per rank under mpirun)")
        ->check(CLI::NonNegativeNumber);
    cmd->add_flag("-q,--quiet", quiet, "no progress lines");
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kExitBadInput;
  }
  // Under mpirun (or srun) the static map's rows are farmed out to every rank; rank 0 does the rest.
  MpiSession* mpi = nullptr;
#ifdef CRANESIM_WITH_MPI
  std::optional<MpiSession> session;
  if (startedByMpiLauncher()) mpi = &session.emplace();
#else
  if (startedByMpiLauncher()) {
    fmt::print(stderr, "error: mpirun: this crane-opt was built without MPI (install libopenmpi-dev and rebuild), so "
                       "its ranks would each compute the whole plan: run it without mpirun, with --threads\n");
    return kExitBadInput;
  }
#endif
  const bool master = isRankZero(mpi);
  try {
    return plan(target_path, out_path, threads, quiet, map_cmd->parsed(), mpi);
  } catch (const SceneError& e) {
    if (master) fmt::print(stderr, "error: {}: {}\n", target_path, e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    if (master) fmt::print(stderr, "error: {}\n", e.what());
    return kExitSolverFailure;
  }
}
