// bench_pendulum_chain: work-precision study of the GGL and Baumgarte formulations on planar
// pendulum chains of N links (see benchmarks/README.md and chain_scene.hpp).
//
// For every N a reference run (GGL, rtol 1e-10, atol 1e-12) gives the tip trajectory of the
// last link; every case (N, formulation, rtol) is then run `repetitions` times and one CSV row
// records the median wall time, the solver counters and the accuracy measures. A failed or
// timed-out run is recorded with completed = 0 and never stops the study;
// the exit status is 1 when any run failed.

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "chain_scene.hpp"
#include "cranesim/assembly/assembler.hpp"
#include "cranesim/io/scene_reader.hpp"
#include "cranesim/model/compile.hpp"
#include "cranesim/solvers/dynamics.hpp"
#include "cranesim/solvers/initial_conditions.hpp"
#include "run_statistics.hpp"

namespace {

using cranesim_bench::ChainSolver;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Options {
  bool quick = false;
  std::string out = "benchmarks/results/pendulum_chain.csv";
  std::vector<int> links{2, 4, 8, 16, 32, 64};
  std::vector<double> rtols{1e-3, 1e-4, 1e-5, 1e-6, 1e-7};
  std::vector<std::string> formulations{"ggl", "baumgarte"};
  int repetitions = 3;
  /// Further repetitions of a case only while its accumulated wall time stays below this
  /// (long runs are less noisy relatively, and the machine has 2 cores). 0: always repeat.
  double repetition_budget_s = 60.0;
  double timeout_s = 600.0;      // per run; a run beyond it is stopped and recorded as failed
  double ref_timeout_s = 3600.0;  // per reference run
  bool reference_check = true;   // also run GGL at rtol 1e-9 to estimate the reference's own error
  int reference_check_max_links = 64;
  // Optional cap for slow machines: chains with N ≥ cap_links run only `cap_rtols`.
  int cap_links = 0;             // 0: no cap (the default: every N runs every rtol)
  std::vector<double> cap_rtols{1e-4, 1e-6};
  int cap_repetitions = 0;       // 0: as `repetitions`
};

/// Records what the study needs from every output sample: tip position of the last link,
/// the energy balance and max |Φ|. Kept light so that it adds little to the timed run.
class ChainSink final : public cranesim::SampleSink {
 public:
  ChainSink(const cranesim::Assembler& assembler, int tip_joint) : assembler_(assembler), tip_(tip_joint) {}

  void sample(double t, const double* y, const cranesim::WorkTerms& w) override {
    const cranesim::Model& model = assembler_.model();
    const double* q = y;
    const double* v = y + assembler_.vOffset();
    time.push_back(t);
    const cranesim::Frame f = model.jointFrame(q, tip_);
    tip.insert(tip.end(), f.r.data(), f.r.data() + 3);
    energy.push_back(assembler_.kineticEnergy(t, q, v) + assembler_.potentialEnergy(t, q) - w.drive - w.load - w.winch + w.dissipated);
    phi.push_back(assembler_.constraintResidual(t, y));
  }

  std::vector<double> time, tip, energy, phi;

 private:
  const cranesim::Assembler& assembler_;
  int tip_;
};

struct RunResult {
  bool completed = false;
  std::string message;
  cranesim::SolverStatistics stats;
  double wall_s = kNaN;  // simulate() only: excludes parsing, compilation and initial conditions
  double energy_scale = kNaN;  // V(0) − V(hanging straight down): the energy available for motion
  std::vector<double> time, tip, energy, phi;
};

/// Potential energy of the chain hanging straight down from the pivot (its minimum).
double hangingPotential(const cranesim::Assembler& assembler, int n) {
  const cranesim::Model& model = assembler.model();
  cranesim::VecX q = cranesim::VecX::Zero(model.nq);
  const double L = cranesim_bench::chainLinkLength(n);
  for (std::size_t k = 0; k < model.nodes.size(); ++k) q[model.nodes[k].q + 2] = -(static_cast<double>(k) + 0.5) * L;
  return assembler.potentialEnergy(0.0, q.data());
}

RunResult runChain(int n, const ChainSolver& solver, double timeout_s) {
  RunResult r;
  try {
    const std::string yaml = cranesim_bench::chainSceneYaml(n, solver);
    const cranesim::Scene scene = cranesim::parseScene(yaml, fmt::format("<chain {}>", n));
    const cranesim::Model model = cranesim::compileModel(scene);
    const cranesim::Assembler assembler(model);
    const int tip = model.findJoint(cranesim_bench::chainTipJoint(n));
    if (tip < 0) throw std::runtime_error("tip joint not found in the generated scene");
    const cranesim::DynamicState initial = cranesim::consistentInitialState(
        assembler, model.solver.t_start, model.q0, model.v0, model.solver.assembly_tolerance);
    r.energy_scale = assembler.potentialEnergy(initial.t, initial.q.data()) - hangingPotential(assembler, n);

    ChainSink sink(assembler, tip);
    std::atomic<bool> stop{false};
    cranesim::SimulationControl control;
    const auto start = std::chrono::steady_clock::now();
    control.on_step = [&](double) {
      if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > timeout_s)
        stop.store(true);
    };
    control.stop_requested = &stop;
    const cranesim::SimulationOutcome outcome = cranesim::simulate(assembler, initial, sink, control);
    r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.completed = outcome.complete;
    r.message = outcome.message;
    if (stop.load()) r.message = fmt::format("timeout after {:.0f} s ({})", timeout_s, outcome.message);
    r.stats = outcome.statistics;
    r.time = std::move(sink.time);
    r.tip = std::move(sink.tip);
    r.energy = std::move(sink.energy);
    r.phi = std::move(sink.phi);
  } catch (const std::exception& e) {
    r.completed = false;
    r.message = fmt::format("exception: {}", e.what());
  } catch (...) {
    r.completed = false;
    r.message = "unknown exception";
  }
  return r;
}

/// max over common samples of |tip − tip_ref|; NaN if there is nothing to compare or the
/// sample times disagree.
double tipError(const RunResult& run, const RunResult& ref) {
  const std::size_t count = std::min(run.time.size(), ref.time.size());
  if (count == 0 || ref.tip.size() < 3 * count) return kNaN;
  double worst = 0.0;
  for (std::size_t s = 0; s < count; ++s) {
    if (std::abs(run.time[s] - ref.time[s]) > 1e-9) return kNaN;
    double d2 = 0.0;
    for (int c = 0; c < 3; ++c) d2 += std::pow(run.tip[3 * s + c] - ref.tip[3 * s + c], 2);
    worst = std::max(worst, std::sqrt(d2));
  }
  return worst;
}

double maxOf(const std::vector<double>& x) {
  if (x.empty()) return kNaN;
  double m = 0.0;
  for (double v : x) m = std::isnan(v) ? v : std::max(m, v);
  return m;
}

/// max over samples of |E(t) − E(0)| divided by the energy available for motion.
double energyDrift(const RunResult& run) {
  if (run.energy.empty() || !(run.energy_scale > 0.0)) return kNaN;
  double worst = 0.0;
  for (double e : run.energy) worst = std::max(worst, std::abs(e - run.energy.front()));
  return worst / run.energy_scale;
}

using cranesim_bench::median;

std::string num(double x) { return std::isnan(x) ? std::string("nan") : fmt::format("{:.6g}", x); }

std::vector<double> parseList(const std::string& text) {
  std::vector<double> out;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t comma = text.find(',', pos);
    const std::string item = text.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
    if (!item.empty()) out.push_back(std::stod(item));
    if (comma == std::string::npos) break;
    pos = comma + 1;
  }
  return out;
}

void usage(std::FILE* to) {
  std::fprintf(to,
               "usage: bench_pendulum_chain [--quick] [--out PATH] [--reps K] [--links 2,4,...]\n"
               "                            [--rtols 1e-3,...] [--formulations ggl,baumgarte]\n"
               "                            [--rep-budget SECONDS] [--timeout SECONDS] [--no-ref-check]\n"
               "                            [--full | --cap-links N --cap-rtols 1e-4,1e-6 [--cap-reps K]]\n"
               "  --quick         smoke test: N in {2, 8}, rtol in {1e-4, 1e-6}, 1 repetition\n"
               "  --out PATH      CSV to write (default benchmarks/results/pendulum_chain.csv)\n"
               "  --reps K        repetitions per case; the median wall time is reported (default 3)\n"
               "  --rep-budget S  repeat a case only while its accumulated wall time is below S (60; 0: always)\n"
               "  --timeout S     per-run wall-time limit; beyond it the run is recorded as failed (600)\n"
               "  --no-ref-check  skip the GGL rtol 1e-9 run that estimates the reference's own error\n"
               "  --cap-links N   chains with N or more links run only --cap-rtols (default 1e-4,1e-6),\n"
               "                  with --cap-reps repetitions (default: no cap)\n"
               "  --full          no cap: every N runs every rtol (the default)\n");
}

Options parseOptions(int argc, char** argv) {
  Options o;
  bool quick = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "bench_pendulum_chain: %s needs a value\n", a.c_str());
        usage(stderr);
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--quick") quick = true;
    else if (a == "--out") o.out = value();
    else if (a == "--reps") o.repetitions = std::max(1, std::stoi(value()));
    else if (a == "--links") {
      o.links.clear();
      for (double x : parseList(value())) o.links.push_back(static_cast<int>(x));
    } else if (a == "--rtols") o.rtols = parseList(value());
    else if (a == "--formulations") {
      o.formulations.clear();
      std::string s = value() + ",";
      for (std::size_t p = 0, c; (c = s.find(',', p)) != std::string::npos; p = c + 1)
        if (c > p) o.formulations.push_back(s.substr(p, c - p));
    } else if (a == "--timeout") o.timeout_s = std::stod(value());
    else if (a == "--no-ref-check") o.reference_check = false;
    else if (a == "--rep-budget") o.repetition_budget_s = std::stod(value());
    else if (a == "--cap-links") o.cap_links = std::stoi(value());
    else if (a == "--full") o.cap_links = 0;
    else if (a == "--cap-rtols") o.cap_rtols = parseList(value());
    else if (a == "--cap-reps") o.cap_repetitions = std::stoi(value());
    else if (a == "-h" || a == "--help") {
      usage(stdout);
      std::exit(0);
    } else {
      std::fprintf(stderr, "bench_pendulum_chain: unknown option '%s'\n", a.c_str());
      usage(stderr);
      std::exit(2);
    }
  }
  if (quick) {
    o.quick = true;
    o.cap_links = 0;
    o.links = {2, 8};
    o.rtols = {1e-4, 1e-6};
    o.repetitions = 1;
    o.reference_check = false;
    o.timeout_s = std::min(o.timeout_s, 40.0);
    o.ref_timeout_s = 40.0;
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  try {
    opt = parseOptions(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_pendulum_chain: bad option value (%s)\n", e.what());
    return 2;
  }
  const std::filesystem::path out_path(opt.out);
  std::error_code ec;
  if (out_path.has_parent_path()) std::filesystem::create_directories(out_path.parent_path(), ec);
  std::ofstream csv(out_path);
  if (!csv) {
    std::fprintf(stderr, "bench_pendulum_chain: cannot write %s\n", opt.out.c_str());
    return 1;
  }
  csv << "n_links,formulation,rtol,wall_time_s_median,steps,residual_evals,jacobian_evals,"
         "tip_error_m,max_constraint_residual,energy_drift_rel,completed\n";
  csv.flush();

  int total = 0;
  for (int n : opt.links) {
    const bool capped = opt.cap_links > 0 && n >= opt.cap_links && !opt.cap_rtols.empty();
    total += static_cast<int>(opt.formulations.size() * (capped ? opt.cap_rtols.size() : opt.rtols.size()));
  }
  int done = 0, failed = 0;
  const auto study_start = std::chrono::steady_clock::now();

  for (int n : opt.links) {
    const bool capped = opt.cap_links > 0 && n >= opt.cap_links && !opt.cap_rtols.empty();
    const std::vector<double>& rtols = capped ? opt.cap_rtols : opt.rtols;
    const int reps = capped && opt.cap_repetitions > 0 ? opt.cap_repetitions : opt.repetitions;

    ChainSolver ref_solver;
    ref_solver.formulation = "ggl";
    ref_solver.rtol = 1e-10;
    ref_solver.atol = 1e-12;
    const RunResult ref = runChain(n, ref_solver, opt.ref_timeout_s);
    std::fprintf(stderr, "reference N=%d (ggl rtol 1e-10): %s, %.2f s, %ld steps, max|Phi| %.3g, drift %.3g%s%s\n", n,
                 ref.completed ? "ok" : "FAILED", ref.wall_s, ref.stats.steps, maxOf(ref.phi), energyDrift(ref),
                 ref.message.empty() ? "" : " - ", ref.message.c_str());
    if (opt.reference_check && ref.completed && n <= opt.reference_check_max_links) {
      ChainSolver check = ref_solver;
      check.rtol = 1e-9;
      check.atol = 1e-11;
      const RunResult chk = runChain(n, check, opt.ref_timeout_s);
      std::fprintf(stderr, "reference check N=%d (ggl rtol 1e-9 vs 1e-10): tip difference %.3g m (%s, %.2f s)\n", n,
                   tipError(chk, ref), chk.completed ? "ok" : "FAILED", chk.wall_s);
    }

    for (const std::string& form : opt.formulations) {
      for (double rtol : rtols) {
        ChainSolver s;
        s.formulation = form;
        s.rtol = rtol;
        s.atol = rtol * 1e-2;
        std::vector<double> walls;
        RunResult first;
        bool consistent = true;
        double spent = 0.0;
        for (int k = 0; k < reps; ++k) {
          if (k > 0 && opt.repetition_budget_s > 0.0 && spent >= opt.repetition_budget_s) break;
          RunResult run = runChain(n, s, opt.timeout_s);
          walls.push_back(run.wall_s);
          spent += std::isnan(run.wall_s) ? 0.0 : run.wall_s;
          if (k == 0) {
            first = std::move(run);
            if (!first.completed) break;  // a failure is deterministic: do not repeat it
          } else if (run.stats.steps != first.stats.steps || run.completed != first.completed) {
            consistent = false;
          }
        }
        const double wall = median(walls);
        const double err = ref.completed ? tipError(first, ref) : kNaN;
        const double phi = maxOf(first.phi), drift = energyDrift(first);
        csv << n << ',' << form << ',' << fmt::format("{:g}", rtol) << ',' << num(wall) << ','
            << first.stats.steps << ',' << first.stats.residual_evaluations << ','
            << first.stats.jacobian_evaluations << ',' << num(err) << ',' << num(phi) << ',' << num(drift) << ','
            << (first.completed ? 1 : 0) << '\n';
        csv.flush();
        ++done;
        if (!first.completed) ++failed;
        std::fprintf(stderr,
                     "[%2d/%2d] N=%-2d %-9s rtol=%-6g %s wall %8.3f s (median of %zu), steps %6ld, res %7ld, jac %5ld, "
                     "tip err %.3g m, max|Phi| %.3g, drift %.3g, Newton fails %ld, error-test fails %ld, restarts %ld%s%s%s\n",
                     done, total, n, form.c_str(), rtol, first.completed ? "ok    " : "FAILED", wall, walls.size(),
                     first.stats.steps, first.stats.residual_evaluations, first.stats.jacobian_evaluations, err, phi,
                     drift, first.stats.nonlinear_failures, first.stats.error_test_failures, first.stats.restarts,
                     consistent ? "" : " [repetitions disagree]", first.message.empty() ? "" : " - ",
                     first.message.c_str());
      }
    }
  }
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - study_start).count();
  std::fprintf(stderr, "done: %d cases, %d failed, %.1f s; wrote %s\n", done, failed, elapsed, opt.out.c_str());
  return failed == 0 ? 0 : 1;
}
