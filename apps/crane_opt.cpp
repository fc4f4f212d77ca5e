// crane-opt: quasi-static optimal control of a crane (thesis chapter 6, 8.4).
//   crane-opt plan TARGET [-o plan.h5] [--threads N] [--quiet]
//       static map → fitted surface → QR end-point trajectory (Ipopt) → control trajectory →
//       verification by simulation (its full results beside the plan: <plan>_simulation.h5)
//   crane-opt map TARGET [-o map.h5] [--threads N] [--quiet]
//       the static map alone
// Exit codes: 0 success, 1 solver failure, 2 bad input (the message names the YAML path and line).

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <filesystem>

#include "cranesim/io/command_line.hpp"
#include "cranesim/io/plan_writer.hpp"
#include "cranesim/planning/quasi_static_plan.hpp"

namespace {

using namespace cranesim;

int plan(const std::string& target_path, const std::string& out_arg, int threads, bool quiet, bool map_only) {
  TargetSpec target = readTarget(target_path);
  if (threads > 0) target.map.threads = threads;
  const std::string out = outputPath(target_path, out_arg, map_only ? "_map.h5" : "_plan.h5");
  const PlanLog log = [quiet](const std::string& line) {
    if (!quiet) fmt::print(stderr, "{}\n", line);
  };
  QuasiStaticPlan result;
  if (map_only) {
    result.map = computeStaticMap(target.scene, target.controls, target.map, log);
    result.map_s = result.map.start_time_s + result.map.sweep_time_s;
    writePlan(out, target, result, true);
    fmt::print(stderr, "static map: {} × {} points, {} failed, sweep {:.1f} s on {} threads; written to {}\n",
               result.map.rows(), result.map.columns(), result.map.failures.size(), result.map.sweep_time_s,
               result.map.threads, out);
    return result.map.failures.empty() ? 0 : kExitSolverFailure;
  }
  result = planQuasiStatic(target, log);
  const std::string simulation = std::filesystem::path(out).replace_extension().string() + "_simulation.h5";
  try {
    verifyPlan(target, result, simulation, log);
  } catch (const std::runtime_error& e) {
    writePlan(out, target, result);
    fmt::print(stderr, "error: {}\n  plan written to {} (verification incomplete)\n", e.what(), out);
    return kExitSolverFailure;
  }
  writePlan(out, target, result);
  fmt::print(stderr, "plan written to {}; verification run in {}\n", out, simulation);
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
    cmd->add_option("--threads", threads, "threads of the map sweep (default: the target's, else all cores)")
        ->check(CLI::NonNegativeNumber);
    cmd->add_flag("-q,--quiet", quiet, "no progress lines");
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kExitBadInput;
  }
  try {
    return plan(target_path, out_path, threads, quiet, map_cmd->parsed());
  } catch (const SceneError& e) {
    fmt::print(stderr, "error: {}: {}\n", target_path, e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return kExitSolverFailure;
  }
}
