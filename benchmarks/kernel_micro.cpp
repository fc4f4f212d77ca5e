// bench_kernels: Google Benchmark timings of the DAE kernels, Assembler::residual and
// Assembler::jacobian, for pendulum chains of 8 and 64 links (chain_scene.hpp) in both
// formulations, at the consistent initial state; and for the thesis crane in both 12-DOF
// lattice fidelities (configs/crane.yaml, crane_condensed.yaml) at its drawn state: the DAE
// residual and Jacobian, and the statics' Jacobian (EquilibriumSystem: ∂/∂q and ∂/∂λ only);
// and the crane's elements by kind (BM_CraneElements/<kind>: one residual and one DAE Jacobian
// of every element of that kind, single-threaded), the breakdown of the crane's kernel time.
// BM_Scaling/<model>/<work>: how the cost per residual, DAE Jacobian, KLU refactorisation and
// solve grows with the coordinates, from one lattice section tube by tube
// (configs/jib_fidelities.yaml) through the main boom tube by tube to the full-member crane
// (configs/crane_members.yaml), beside the 162-coordinate cranes; counters: coordinates, DAE
// unknowns, Jacobian non-zeros, LU non-zeros (the fill).

#include <benchmark/benchmark.h>

#include <cxxabi.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <typeinfo>
#include <vector>

#include <fmt/format.h>

#include "chain_scene.hpp"
#include "cranesim/assembly/assembler.hpp"
#include "cranesim/assembly/constraint_second_derivatives.hpp"
#include "cranesim/math/sparse_lu.hpp"
#include "cranesim/io/results_writer.hpp"
#include "cranesim/io/scene_reader.hpp"
#include "cranesim/model/compile.hpp"
#include "cranesim/solvers/equilibrium_system.hpp"
#include "cranesim/solvers/initial_conditions.hpp"

namespace {

/// A compiled chain with a consistent state y = [q, dq, λ, (μ = 0)], ẏ = [q̇, d(dq)/dt, 0, (0)].
struct Fixture {
  cranesim::Model model;
  std::unique_ptr<cranesim::Assembler> assembler;
  std::vector<double> y, yp, res, values;

  Fixture(int n, const std::string& formulation) {
    cranesim_bench::ChainSolver s;
    s.formulation = formulation;
    model = cranesim::compileModel(cranesim::parseScene(cranesim_bench::chainSceneYaml(n, s), "<chain>"));
    assembler = std::make_unique<cranesim::Assembler>(model);
    const cranesim::DynamicState st = cranesim::consistentInitialState(
        *assembler, model.solver.t_start, model.q0, model.v0, model.solver.assembly_tolerance);
    const auto& a = *assembler;
    y.assign(a.size(), 0.0);
    yp.assign(a.size(), 0.0);
    for (int i = 0; i < model.nq; ++i) y[i] = st.q[i], yp[i] = st.qdot[i];
    for (int i = 0; i < model.nv; ++i) y[a.vOffset() + i] = st.v[i], yp[a.vOffset() + i] = st.a[i];
    for (int i = 0; i < model.m; ++i) y[a.lambdaOffset() + i] = st.lambda[i];
    res.assign(a.size(), 0.0);
    values.assign(a.pattern().nonZeros(), 0.0);
  }
};

Fixture& fixture(int n, bool ggl) {
  // One fixture per case, built on first use (Model must outlive its Assembler).
  static std::unique_ptr<Fixture> cache[2][2];
  auto& f = cache[n == 64][ggl];
  if (!f) f = std::make_unique<Fixture>(n, ggl ? "ggl" : "baumgarte");
  return *f;
}

void BM_Residual(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Fixture& f = fixture(n, state.range(1) != 0);
  for (auto _ : state) {
    f.assembler->residual(0.0, f.y.data(), f.yp.data(), f.res.data());
    benchmark::DoNotOptimize(f.res.data());
    benchmark::ClobberMemory();
  }
  state.counters["unknowns"] = f.assembler->size();
  state.SetLabel(state.range(1) ? "ggl" : "baumgarte");
}

void BM_Jacobian(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Fixture& f = fixture(n, state.range(1) != 0);
  const double cj = 1e3;  // 1/h for a typical step
  for (auto _ : state) {
    f.assembler->jacobian(0.0, cj, f.y.data(), f.yp.data(), f.values.data());
    benchmark::DoNotOptimize(f.values.data());
    benchmark::ClobberMemory();
  }
  state.counters["unknowns"] = f.assembler->size();
  state.counters["nonzeros"] = static_cast<double>(f.values.size());
  state.SetLabel(state.range(1) ? "ggl" : "baumgarte");
}

/// The thesis crane at its drawn state (dq = 0) with a multiplier guess of 1 MN.
struct CraneFixture {
  cranesim::Model model;
  std::unique_ptr<cranesim::Assembler> assembler;
  std::unique_ptr<cranesim::EquilibriumSystem> statics;
  std::vector<double> y, yp, res, values;
  cranesim::VecX x;

  explicit CraneFixture(const cranesim::Scene& scene) {
    model = cranesim::compileModel(scene);
    assembler = std::make_unique<cranesim::Assembler>(model);
    statics = std::make_unique<cranesim::EquilibriumSystem>(model, 0.0);
    const auto& a = *assembler;
    y.assign(a.size(), 0.0);
    yp.assign(a.size(), 0.0);
    for (int i = 0; i < model.nq; ++i) y[i] = model.q0[i];
    // In motion: every velocity and acceleration non-zero, so that the elements take the paths
    // they take during a run (at rest the super truss' coordinate columns take its cheaper
    // static-force path, and inertial terms vanish).
    for (int i = 0; i < model.nv; ++i) {
      y[a.vOffset() + i] = 0.01 * std::sin(1.0 + i);
      yp[a.vOffset() + i] = 0.01 * std::cos(1.0 + i);
    }
    for (int i = 0; i < model.m; ++i) y[a.lambdaOffset() + i] = 1e6;
    res.assign(a.size(), 0.0);
    values.assign(a.pattern().nonZeros(), 0.0);
    x.resize(statics->size());
    x << model.q0, cranesim::VecX::Constant(model.m, 1e6);
  }
};

cranesim::Scene configScene(const std::string& name) {
  return cranesim::readScene(std::string(CRANESIM_SOURCE_DIR) + "/configs/" + name);
}

/// The models of BM_Scaling, by name: a scene from configs/, or the full-member crane with its
/// derrick condensed (main_boom_members).
cranesim::Scene scalingScene(const std::string& name) {
  if (name != "main_boom_members") return configScene(name + ".yaml");
  cranesim::Scene scene = configScene("crane_members.yaml");
  for (cranesim::MemberSpec& m : scene.members)
    if (m.name.rfind("derrick", 0) == 0) m.fidelity = cranesim::TrussFidelity::Condensed;
  return scene;
}

CraneFixture& fixture(const std::string& name) {
  static std::map<std::string, std::unique_ptr<CraneFixture>> cache;
  auto& f = cache[name];
  if (!f) f = std::make_unique<CraneFixture>(scalingScene(name));
  return *f;
}

CraneFixture& crane(bool condensed) { return fixture(condensed ? "crane_condensed" : "crane"); }

const char* fidelity(const benchmark::State& state) { return state.range(0) ? "condensed" : "super_truss"; }

void BM_CraneResidual(benchmark::State& state) {
  CraneFixture& f = crane(state.range(0) != 0);
  for (auto _ : state) {
    f.assembler->residual(0.0, f.y.data(), f.yp.data(), f.res.data());
    benchmark::DoNotOptimize(f.res.data());
    benchmark::ClobberMemory();
  }
  state.SetLabel(fidelity(state));
}

void BM_CraneJacobian(benchmark::State& state) {
  CraneFixture& f = crane(state.range(0) != 0);
  for (auto _ : state) {
    f.assembler->jacobian(0.0, 1e3, f.y.data(), f.yp.data(), f.values.data());
    benchmark::DoNotOptimize(f.values.data());
    benchmark::ClobberMemory();
  }
  state.SetLabel(fidelity(state));
}

void BM_CraneStaticJacobian(benchmark::State& state) {
  CraneFixture& f = crane(state.range(0) != 0);
  for (auto _ : state) benchmark::DoNotOptimize(f.statics->jacobian(f.x));
  state.SetLabel(fidelity(state));
}

/// One output sample of a run (ResultsRecorder::sample): the consistent accelerations and
/// multipliers by a saddle-point LU on the mass matrix, energies, frames, constraint residuals.
void BM_CraneSample(benchmark::State& state) {
  CraneFixture& f = crane(state.range(0) != 0);
  cranesim::ResultsRecorder recorder(*f.assembler);
  for (auto _ : state) recorder.sample(0.0, f.y.data(), cranesim::WorkTerms{});
  state.SetLabel(fidelity(state));
}

/// The crane's joint constraints alone, serially: their equations and velocity Jacobian G
/// (residual) or their second derivatives too (jacobian), as the DAE Jacobian needs them.
void BM_CraneConstraints(benchmark::State& state) {
  CraneFixture& f = crane(state.range(0) != 0);
  const bool second = state.range(1) != 0;
  for (auto _ : state) {
    for (const cranesim::Constraint& c : f.model.constraints) {
      if (second) {
        const cranesim::ConstraintSecondDerivatives C(f.model, c, f.y.data(), 0.0);
        benchmark::DoNotOptimize(C);
      } else {
        auto C = cranesim::evaluateConstraint<double>(f.model, c, f.y.data(), 0.0);
        benchmark::DoNotOptimize(C);
      }
    }
    benchmark::ClobberMemory();
  }
  state.counters["constraints"] = static_cast<double>(f.model.constraints.size());
  state.SetLabel(fidelity(state));
}

/// The element's kernel type, e.g. "CondensedTrussKernel" (or the element class's name).
std::string elementKind(const cranesim::Element& e) {
  int status = 0;
  char* raw = abi::__cxa_demangle(typeid(e).name(), nullptr, nullptr, &status);
  std::string name = status == 0 ? raw : typeid(e).name();
  std::free(raw);
  const auto open = name.find('<'), close = name.rfind('>');
  if (open != std::string::npos && close != std::string::npos) name = name.substr(open + 1, close - open - 1);
  const auto scope = name.rfind("::");
  return scope == std::string::npos ? name : name.substr(scope + 2);
}

/// One residual or DAE Jacobian of every crane element of one kind, serially, at the fixture's state.
void craneElements(benchmark::State& state, bool condensed, const std::string& kind, bool jacobian) {
  CraneFixture& f = crane(condensed);
  const auto& a = *f.assembler;
  const cranesim::ElementInput in{f.y.data(), f.y.data() + a.vOffset(), f.yp.data() + a.vOffset(), 0.0,
                                  f.model.gravity};
  std::vector<const cranesim::Element*> group;
  std::size_t largest = 0;  // the largest Jacobian of the group, size() × (nq_local + size())
  for (const auto& e : f.model.elements)
    if (elementKind(*e) == kind) {
      group.push_back(e.get());
      largest = std::max(largest, e->size() * (e->coordinateIndices().size() + e->size()));
    }
  std::vector<double> out(largest);
  for (auto _ : state) {
    for (const cranesim::Element* e : group) {
      if (jacobian)
        e->jacobian(in, 1e3, out.data());
      else
        e->residual(in, out.data());
      benchmark::DoNotOptimize(out.data());
    }
    benchmark::ClobberMemory();
  }
  state.counters["elements"] = static_cast<double>(group.size());
}

/// BM_CraneElements/<fidelity>/<kind>/<residual|jacobian> for every kind of element in each crane.
void registerCraneElementBenchmarks() {
  for (const bool condensed : {false, true}) {
    std::set<std::string> kinds;
    for (const auto& e : crane(condensed).model.elements) kinds.insert(elementKind(*e));
    for (const std::string& kind : kinds)
      for (const bool jacobian : {false, true})
        benchmark::RegisterBenchmark(
            fmt::format("BM_CraneElements/{}/{}/{}", condensed ? "condensed" : "super_truss", kind,
                        jacobian ? "jacobian" : "residual")
                .c_str(),
            craneElements, condensed, kind, jacobian)
            ->Unit(benchmark::kMillisecond);
  }
}

/// One residual, DAE Jacobian, KLU refactorisation of that Jacobian, or solve with it, of a model
/// of BM_Scaling.
void scaling(benchmark::State& state, const std::string& name, const std::string& work) {
  CraneFixture& f = fixture(name);
  const auto& a = *f.assembler;
  const cranesim::SparsityPattern& p = a.pattern();
  f.assembler->jacobian(0.0, 1e3, f.y.data(), f.yp.data(), f.values.data());
  cranesim::SparseLU lu;
  if (!lu.factorise(static_cast<int>(a.size()), p.columnPointers().data(), p.rowIndices().data(), f.values.data()))
    state.SkipWithError("singular DAE Jacobian");
  std::vector<double> x(a.size(), 1.0);
  for (auto _ : state) {
    if (work == "residual") {
      f.assembler->residual(0.0, f.y.data(), f.yp.data(), f.res.data());
      benchmark::DoNotOptimize(f.res.data());
    } else if (work == "jacobian") {
      f.assembler->jacobian(0.0, 1e3, f.y.data(), f.yp.data(), f.values.data());
      benchmark::DoNotOptimize(f.values.data());
    } else if (work == "factor") {
      benchmark::DoNotOptimize(lu.factorise(static_cast<int>(a.size()), p.columnPointers().data(), p.rowIndices().data(),
                                            f.values.data()));
    } else {
      lu.solve(x.data());
      benchmark::DoNotOptimize(x.data());
    }
    benchmark::ClobberMemory();
  }
  state.counters["coordinates"] = f.model.nq;
  state.counters["unknowns"] = static_cast<double>(a.size());
  state.counters["jacobian_nonzeros"] = static_cast<double>(p.nonZeros());
  state.counters["lu_nonzeros"] = static_cast<double>(lu.factorNonZeros());
}

void registerScalingBenchmarks() {
  for (const char* name : {"crane", "crane_condensed", "jib_fidelities", "main_boom_members", "crane_members"})
    for (const char* work : {"residual", "jacobian", "factor", "solve"})
      benchmark::RegisterBenchmark(fmt::format("BM_Scaling/{}/{}", name, work).c_str(), scaling, std::string(name), std::string(work))
          ->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_CraneResidual)->Arg(0)->Arg(1)->ArgName("condensed")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CraneJacobian)->Arg(0)->Arg(1)->ArgName("condensed")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CraneSample)->Arg(0)->Arg(1)->ArgName("condensed")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CraneStaticJacobian)->Arg(0)->Arg(1)->ArgName("condensed")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CraneConstraints)->ArgsProduct({{1}, {0, 1}})->ArgNames({"condensed", "second"})->Unit(benchmark::kMillisecond);

// Args: {links, ggl (1) or baumgarte (0)}.
BENCHMARK(BM_Residual)->ArgsProduct({{8, 64}, {1, 0}})->ArgNames({"N", "ggl"})->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Jacobian)->ArgsProduct({{8, 64}, {1, 0}})->ArgNames({"N", "ggl"})->Unit(benchmark::kMicrosecond);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  registerCraneElementBenchmarks();
  registerScalingBenchmarks();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
