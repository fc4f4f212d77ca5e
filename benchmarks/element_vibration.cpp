// bench_element_vibration: speed against error of the flexible beam elements (Timoshenko,
// cubic spline beam) on the thesis' single-beam experiments (see benchmarks/README.md):
//   vibration  8.1.2, configs/cantilever_<element>.yaml, the cantilever released under gravity
//   rotation   8.1.3, configs/rotation_drive_<element>.yaml, the beam turned by the drive (8-2)
// For every (case, damping) the reference is the 10-segment model of each studied element type
// at a tight rtol; every (element, segments, rtol) is run `repetitions` times and one CSV row records
// the median wall time, the solver counters, and the max over samples of the tip's distance to
// the reference of the same element type and to that of the other type. A failed or timed-out
// run is recorded with completed = 0 and never stops the study; the
// exit status is 1 when any run failed.

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "cranesim/assembly/assembler.hpp"
#include "cranesim/io/scene_reader.hpp"
#include "cranesim/model/compile.hpp"
#include "cranesim/solvers/dynamics.hpp"
#include "cranesim/solvers/initial_conditions.hpp"
#include "run_statistics.hpp"

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
const std::vector<std::string> kElements{"timoshenko", "spline_beam"};

struct Options {
  std::string configs = "configs";
  std::string out = "benchmarks/results/element_vibration.csv";
  std::vector<std::string> cases{"vibration", "rotation"};
  std::vector<std::string> elements = kElements;
  std::vector<int> segments{1, 3, 5, 10};
  std::vector<double> rtols{1e-4, 1e-6, 1e-8};
  std::vector<double> dampings{0.0, 1e-4};  // Kelvin–Voigt η, s
  double vibration_t_end = 3.0;
  double rotation_t_end = 10.0;
  double reference_rtol = 1e-9;
  int reference_segments = 10;
  int repetitions = 3;
  double repetition_budget_s = 60.0;  // repeat a case only while its wall time stays below this
  double timeout_s = 900.0;
  double ref_timeout_s = 3600.0;
};

/// Tip position at every output sample; light, so that it adds little to the timed run.
class TipSink final : public cranesim::SampleSink {
 public:
  TipSink(const cranesim::Model& model, int tip) : model_(model), tip_(tip) {}
  void sample(double t, const double* y, const cranesim::WorkTerms&) override {
    time.push_back(t);
    const cranesim::Frame f = model_.jointFrame(y, tip_);
    tip.insert(tip.end(), f.r.data(), f.r.data() + 3);
  }
  std::vector<double> time, tip;

 private:
  const cranesim::Model& model_;
  int tip_;
};

struct Run {
  bool completed = false;
  std::string message;
  cranesim::SolverStatistics stats;
  double wall_s = kNaN;  // simulate() only
  double cpu_s = kNaN;   // process CPU time of simulate() (all threads)
  std::vector<double> time, tip;
};

struct Case {
  std::string name, element;
  int segments = 10;
  double rtol = 1e-6, damping = 0.0;
};

std::string sceneFile(const Options& o, const Case& c) {
  const std::string stem = c.name == "vibration" ? "cantilever_" : "rotation_drive_";
  return o.configs + "/" + stem + c.element + ".yaml";
}

Run simulateCase(const Options& o, const Case& c, double timeout_s) {
  Run r;
  try {
    cranesim::Scene scene = cranesim::readScene(sceneFile(o, c));
    scene.members.at(0).segments = c.segments;
    scene.members.at(0).damping = c.damping;
    scene.solver.rtol = c.rtol;
    scene.solver.atol = cranesim::AbsoluteTolerance::uniform(c.rtol * 1e-2);
    scene.solver.t_end = c.name == "vibration" ? o.vibration_t_end : o.rotation_t_end;
    scene.output.interval = 0.01;
    const cranesim::Model model = cranesim::compileModel(scene);
    const cranesim::Assembler assembler(model);
    const cranesim::DynamicState initial = cranesim::consistentInitialState(
        assembler, model.solver.t_start, model.q0, model.v0, model.solver.assembly_tolerance);
    TipSink sink(model, model.findJoint(scene.members.at(0).name + ".end"));
    std::atomic<bool> stop{false};
    cranesim::SimulationControl control;
    const auto start = std::chrono::steady_clock::now();
    control.on_step = [&](double) {
      if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > timeout_s) stop.store(true);
    };
    control.stop_requested = &stop;
    const std::clock_t cpu_start = std::clock();
    const cranesim::SimulationOutcome outcome = cranesim::simulate(assembler, initial, sink, control);
    r.cpu_s = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.completed = outcome.complete;
    r.message = stop.load() ? fmt::format("timeout after {:.0f} s", timeout_s) : outcome.message;
    r.stats = outcome.statistics;
    r.time = std::move(sink.time);
    r.tip = std::move(sink.tip);
  } catch (const std::exception& e) {
    r.message = fmt::format("exception: {}", e.what());
  }
  return r;
}

/// max over common samples of ‖tip − tip_ref‖; NaN when there is nothing to compare.
double tipError(const Run& run, const Run& ref) {
  if (!ref.completed) return kNaN;
  const std::size_t count = std::min(run.time.size(), ref.time.size());
  if (count == 0) return kNaN;
  double worst = 0.0;
  for (std::size_t s = 0; s < count; ++s) {
    if (std::abs(run.time[s] - ref.time[s]) > 1e-9) return kNaN;
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k) d2 += std::pow(run.tip[3 * s + k] - ref.tip[3 * s + k], 2);
    worst = std::max(worst, std::sqrt(d2));
  }
  return worst;
}

using cranesim_bench::median;

std::string num(double x) { return std::isnan(x) ? std::string("nan") : fmt::format("{:.6g}", x); }

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> out;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t comma = text.find(',', pos);
    const std::string item = text.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
    if (!item.empty()) out.push_back(item);
    if (comma == std::string::npos) break;
    pos = comma + 1;
  }
  return out;
}

std::vector<double> parseNumbers(const std::string& text) {
  std::vector<double> out;
  for (const std::string& item : splitList(text)) out.push_back(std::stod(item));
  return out;
}

void usage(std::FILE* to) {
  std::fprintf(to,
               "usage: bench_element_vibration [--quick] [--out PATH] [--configs DIR] [--cases vibration,rotation]\n"
               "                               [--elements timoshenko,spline_beam] [--segments 1,3,5,10]\n"
               "                               [--rtols 1e-4,1e-6,1e-8] [--dampings 0,1e-4] [--reps K]\n"
               "                               [--vibration-t-end S] [--rotation-t-end S] [--ref-rtol R]\n"
               "                               [--rep-budget S] [--timeout S]\n"
               "  --quick            smoke test: both cases for 0.3 s, both elements, 1 and 3 segments,\n"
               "                     rtol 1e-4, damping 1e-4, reference 3 segments at rtol 1e-6, 1 repetition\n"
               "  --out PATH         CSV to write (default benchmarks/results/element_vibration.csv)\n"
               "  --configs DIR      where the scenes are (default configs; run from the repository root)\n"
               "  --dampings         Kelvin–Voigt retardation times η (s) to study; 0 = undamped\n"
               "  --reps K           repetitions per case; the median wall time is reported (default 3)\n"
               "  --rep-budget S     repeat a case only while its accumulated wall time is below S (60)\n"
               "  --timeout S        per-run wall-time limit; beyond it the run is recorded as failed (900)\n");
}

Options parseOptions(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "bench_element_vibration: %s needs a value\n", a.c_str());
        usage(stderr);
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--quick") {
      o.elements = kElements;
      o.segments = {1, 3};
      o.rtols = {1e-4};
      o.dampings = {1e-4};
      o.vibration_t_end = o.rotation_t_end = 0.3;
      o.reference_rtol = 1e-6;
      o.reference_segments = 3;
      o.repetitions = 1;
      o.timeout_s = o.ref_timeout_s = 40.0;
    } else if (a == "--out") o.out = value();
    else if (a == "--configs") o.configs = value();
    else if (a == "--cases") o.cases = splitList(value());
    else if (a == "--elements") o.elements = splitList(value());
    else if (a == "--segments") {
      o.segments.clear();
      for (double s : parseNumbers(value())) o.segments.push_back(static_cast<int>(s));
    } else if (a == "--rtols") o.rtols = parseNumbers(value());
    else if (a == "--dampings") o.dampings = parseNumbers(value());
    else if (a == "--reps") o.repetitions = std::max(1, std::stoi(value()));
    else if (a == "--vibration-t-end") o.vibration_t_end = std::stod(value());
    else if (a == "--rotation-t-end") o.rotation_t_end = std::stod(value());
    else if (a == "--ref-rtol") o.reference_rtol = std::stod(value());
    else if (a == "--rep-budget") o.repetition_budget_s = std::stod(value());
    else if (a == "--timeout") o.timeout_s = std::stod(value());
    else if (a == "-h" || a == "--help") {
      usage(stdout);
      std::exit(0);
    } else {
      std::fprintf(stderr, "bench_element_vibration: unknown option '%s'\n", a.c_str());
      usage(stderr);
      std::exit(2);
    }
  }
  for (const std::string& c : o.cases)
    if (c != "vibration" && c != "rotation") throw std::invalid_argument("case '" + c + "' (vibration | rotation)");
  for (const std::string& e : o.elements)
    if (std::find(kElements.begin(), kElements.end(), e) == kElements.end())
      throw std::invalid_argument("element '" + e + "' (timoshenko | spline_beam)");
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  try {
    opt = parseOptions(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_element_vibration: bad option value (%s)\n", e.what());
    return 2;
  }
  const std::filesystem::path out_path(opt.out);
  std::error_code ec;
  if (out_path.has_parent_path()) std::filesystem::create_directories(out_path.parent_path(), ec);
  std::ofstream csv(out_path);
  if (!csv) {
    std::fprintf(stderr, "bench_element_vibration: cannot write %s\n", opt.out.c_str());
    return 1;
  }
  csv << "case,element,segments,rtol,damping,wall_time_s_median,cpu_time_s,steps,residual_evals,jacobian_evals,"
         "error_test_failures,tip_error_m,tip_error_cross_m,completed\n";
  csv.flush();
  const auto study_start = std::chrono::steady_clock::now();
  int done = 0, failed = 0;

  for (const std::string& name : opt.cases) {
    for (double damping : opt.dampings) {
      // References of the studied element types; with both, the cross error compares each run
      // with the other type's reference.
      std::map<std::string, Run> refs;
      for (const std::string& element : opt.elements) {
        const Case rc{name, element, opt.reference_segments, opt.reference_rtol, damping};
        refs[element] = simulateCase(opt, rc, opt.ref_timeout_s);
        const Run& ref = refs[element];
        std::fprintf(stderr, "reference %s %s η=%g (%d segments, rtol %g): %s, %.2f s, %ld steps%s%s\n", name.c_str(),
                     element.c_str(), damping, rc.segments, rc.rtol, ref.completed ? "ok" : "FAILED", ref.wall_s,
                     ref.stats.steps, ref.message.empty() ? "" : " - ", ref.message.c_str());
      }
      for (const std::string& element : opt.elements) {
        const std::string other = element == kElements[0] ? kElements[1] : kElements[0];
        for (int segments : opt.segments) {
          for (double rtol : opt.rtols) {
            const Case c{name, element, segments, rtol, damping};
            std::vector<double> walls;
            Run first;
            double spent = 0.0;
            for (int k = 0; k < opt.repetitions; ++k) {
              if (k > 0 && spent >= opt.repetition_budget_s) break;
              Run run = simulateCase(opt, c, opt.timeout_s);
              walls.push_back(run.wall_s);
              spent += std::isnan(run.wall_s) ? 0.0 : run.wall_s;
              if (k == 0) {
                first = std::move(run);
                if (!first.completed) break;  // a failure is deterministic: do not repeat it
              }
            }
            const double wall = median(walls);
            const double err = tipError(first, refs[element]), cross = refs.count(other) ? tipError(first, refs[other]) : kNaN;
            csv << name << ',' << element << ',' << segments << ',' << fmt::format("{:g}", rtol) << ','
                << fmt::format("{:g}", damping) << ',' << num(wall) << ',' << num(first.cpu_s) << ','
                << first.stats.steps << ',' << first.stats.residual_evaluations << ','
                << first.stats.jacobian_evaluations << ',' << first.stats.error_test_failures << ',' << num(err)
                << ',' << num(cross) << ',' << (first.completed ? 1 : 0) << '\n';
            csv.flush();
            ++done;
            if (!first.completed) ++failed;
            std::fprintf(stderr,
                         "%-9s %-11s η=%-6g n=%-2d rtol=%-6g %s wall %8.3f s (median of %zu), cpu %8.3f s, steps %7ld, "
                         "jac %6ld, tip err %.3g m (vs %s %.3g m)%s%s\n",
                         name.c_str(), element.c_str(), damping, segments, rtol, first.completed ? "ok    " : "FAILED",
                         wall, walls.size(), first.cpu_s, first.stats.steps, first.stats.jacobian_evaluations, err,
                         other.c_str(), cross, first.message.empty() ? "" : " - ", first.message.c_str());
          }
        }
      }
    }
  }
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - study_start).count();
  std::fprintf(stderr, "done: %d cases, %d failed, %.1f s; wrote %s\n", done, failed, elapsed, opt.out.c_str());
  return failed == 0 ? 0 : 1;
}
