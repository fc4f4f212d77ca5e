// bench_element_bending: accuracy and cost of the Timoshenko and cubic spline beam elements
// in the thesis' static bending test 8.1.1 (see benchmarks/README.md, tests/fixtures/end_moment_arc.hpp).
//
// For every member type, segment count and moment ratio K the equilibrium of
// configs/end_moment_<type>.yaml is solved with solveStatics in two ways:
//   direct        from the straight beam, as `crane-sim static` does;
//   continuation  from the equilibrium of the previous (smaller) K of the list.
// One CSV row per case records the tip position and rotation errors against the exact arc,
// the Newton iterations and load steps, and the median wall and CPU times of `repetitions`
// solves (CPU time: the process's, which is the solve's own on a shared machine; the element
// loop runs serially below 32 elements).
// A failed solve is recorded with converged = 0 and never stops the study.

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "cranesim/solvers/statics.hpp"
#include "end_moment_arc.hpp"
#include "run_statistics.hpp"

namespace {

using namespace cranesim;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Options {
  std::string out = "benchmarks/results/element_bending.csv";
  std::vector<std::string> types{"timoshenko", "spline_beam"};
  std::vector<int> segments{1, 3, 5, 10};
  std::vector<double> ks{0.05, 0.1, 0.25, 0.5, 0.75, 1.0};
  int repetitions = 3;
};

struct Solve {
  StaticResult result;
  double wall_s = kNaN;
  double cpu_s = kNaN;
  std::string error;  // exception text, if any
};

Solve solveOnce(const Model& model, const VecX& q_start) {
  Solve s;
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  try {
    s.result = solveStatics(model, q_start, model.solver.t_start);
  } catch (const std::exception& e) {
    s.error = e.what();
  }
  s.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  s.cpu_s = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  return s;
}

using cranesim_bench::median;

std::string num(double x) { return std::isnan(x) ? std::string("nan") : fmt::format("{:.6g}", x); }

struct Row {
  std::string type, strategy;
  int segments = 0;
  double K = 0.0;
  Solve solve;
  std::vector<double> walls, cpus;
  test::ArcError error{kNaN, kNaN};
};

void writeRow(std::ofstream& csv, const Row& r) {
  const bool ok = r.solve.error.empty() && r.solve.result.converged;
  const double per_segment_deg = 360.0 * r.K / r.segments;
  csv << r.type << ',' << r.segments << ',' << fmt::format("{:g}", r.K) << ',' << num(per_segment_deg) << ','
      << r.strategy << ',' << (ok ? 1 : 0) << ',' << r.solve.result.iterations << ',' << r.solve.result.load_steps << ','
      << num(median(r.walls)) << ',' << num(median(r.cpus)) << ',' << num(ok ? r.error.tip : kNaN) << ',' << num(ok ? r.error.rotation : kNaN)
      << '\n';
  csv.flush();
  std::fprintf(stderr, "%-11s n=%-2d K=%-4g %-12s %s iterations %4d, load steps %3d, wall %8.4f s, CPU %8.4f s, tip error %.3g L, "
                       "rotation error %.3g rad%s%s\n",
               r.type.c_str(), r.segments, r.K, r.strategy.c_str(), ok ? "ok    " : "FAILED", r.solve.result.iterations,
               r.solve.result.load_steps, median(r.walls), median(r.cpus), ok ? r.error.tip : kNaN, ok ? r.error.rotation : kNaN,
               ok ? "" : " - ", ok ? "" : (r.solve.error.empty() ? r.solve.result.message : r.solve.error).c_str());
}

/// Runs one (type, segments) line: every K directly, then the continuation through the Ks.
void study(std::ofstream& csv, const Options& opt, const std::string& type, int segments) {
  const std::string scene_file = std::string(CRANESIM_SOURCE_DIR) + "/configs/end_moment_" + type + ".yaml";
  std::vector<Row> continuation(opt.ks.size());
  for (std::size_t k = 0; k < opt.ks.size(); ++k) {
    continuation[k].type = type;
    continuation[k].strategy = "continuation";
    continuation[k].segments = segments;
    continuation[k].K = opt.ks[k];
  }
  for (int rep = 0; rep < opt.repetitions; ++rep) {
    VecX q_previous;
    for (std::size_t k = 0; k < opt.ks.size(); ++k) {
      const Scene scene = test::endMomentScene(scene_file, segments, opt.ks[k]);
      const Model model = compileModel(scene);
      if (q_previous.size() == 0) q_previous = model.q0;
      Solve s = solveOnce(model, q_previous);
      Row& row = continuation[k];
      row.walls.push_back(s.wall_s);
      row.cpus.push_back(s.cpu_s);
      const bool ok = s.error.empty() && s.result.converged;
      if (ok) q_previous = s.result.q;  // a failure: the next K starts from the last equilibrium
      if (rep == 0) {
        if (ok) row.error = test::arcError(model, s.result.q, test::endMomentArc(scene));
        row.solve = std::move(s);
      }
    }
  }
  for (double K : opt.ks) {
    Row row;
    row.type = type;
    row.strategy = "direct";
    row.segments = segments;
    row.K = K;
    const Scene scene = test::endMomentScene(scene_file, segments, K);
    const Model model = compileModel(scene);
    for (int rep = 0; rep < opt.repetitions; ++rep) {
      Solve s = solveOnce(model, model.q0);
      row.walls.push_back(s.wall_s);
      row.cpus.push_back(s.cpu_s);
      if (rep == 0) row.solve = std::move(s);
      if (!(row.solve.error.empty() && row.solve.result.converged)) break;  // deterministic: do not repeat
    }
    if (row.solve.error.empty() && row.solve.result.converged)
      row.error = test::arcError(model, row.solve.result.q, test::endMomentArc(scene));
    writeRow(csv, row);
  }
  for (const Row& row : continuation) writeRow(csv, row);
}

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
               "usage: bench_element_bending [--quick] [--out PATH] [--reps K] [--types timoshenko,spline_beam]\n"
               "                             [--segments 1,3,5,10] [--ks 0.05,0.1,...]\n"
               "  --quick     smoke test: 3 segments, K in {0.1, 0.5}, 1 repetition\n"
               "  --out PATH  CSV to write (default benchmarks/results/element_bending.csv)\n"
               "  --reps K    solves per case; the median wall and CPU times are reported (default 3)\n"
               "  --ks        moment ratios K = M/M_circle, ascending (the continuation follows them)\n");
}

Options parseOptions(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "bench_element_bending: %s needs a value\n", a.c_str());
        usage(stderr);
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--quick") {
      o.segments = {3};
      o.ks = {0.1, 0.5};
      o.repetitions = 1;
    } else if (a == "--out") o.out = value();
    else if (a == "--reps") o.repetitions = std::max(1, std::stoi(value()));
    else if (a == "--segments") {
      o.segments.clear();
      for (double x : parseList(value())) o.segments.push_back(static_cast<int>(x));
    } else if (a == "--ks") o.ks = parseList(value());
    else if (a == "--types") {
      o.types.clear();
      std::string s = value() + ",";
      for (std::size_t p = 0, c; (c = s.find(',', p)) != std::string::npos; p = c + 1)
        if (c > p) o.types.push_back(s.substr(p, c - p));
    } else if (a == "-h" || a == "--help") {
      usage(stdout);
      std::exit(0);
    } else {
      std::fprintf(stderr, "bench_element_bending: unknown option '%s'\n", a.c_str());
      usage(stderr);
      std::exit(2);
    }
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  try {
    opt = parseOptions(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_element_bending: bad option value (%s)\n", e.what());
    return 2;
  }
  const std::filesystem::path out_path(opt.out);
  std::error_code ec;
  if (out_path.has_parent_path()) std::filesystem::create_directories(out_path.parent_path(), ec);
  std::ofstream csv(out_path);
  if (!csv) {
    std::fprintf(stderr, "bench_element_bending: cannot write %s\n", opt.out.c_str());
    return 1;
  }
  csv << "type,segments,K,bend_per_segment_deg,strategy,converged,newton_iterations,load_steps,"
         "wall_time_s_median,cpu_time_s_median,tip_error_rel,rotation_error_rad\n";
  const auto start = std::chrono::steady_clock::now();
  try {
    for (const std::string& type : opt.types)
      for (int n : opt.segments) study(csv, opt, type, n);
  } catch (const std::exception& e) {  // the scene itself: nothing to measure
    std::fprintf(stderr, "bench_element_bending: %s\n", e.what());
    return 1;
  }
  std::fprintf(stderr, "done in %.1f s; wrote %s\n",
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), opt.out.c_str());
  return 0;
}
