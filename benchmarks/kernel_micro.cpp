// bench_kernels: Google Benchmark timings of the DAE kernels, Assembler::residual and
// Assembler::jacobian, for pendulum chains of 8 and 64 links (chain_scene.hpp) in both
// formulations, at the consistent initial state; and for the thesis crane in both 12-DOF
// lattice fidelities (configs/crane.yaml, crane_condensed.yaml) at its drawn state: the DAE
// residual and Jacobian, and the statics' Jacobian (EquilibriumSystem: ∂/∂q and ∂/∂λ only);
// and the crane's elements by kind (BM_CraneElements/<kind>: one residual and one DAE Jacobian
// of every element of that kind, single-threaded), the breakdown of the crane's kernel time.

#include <benchmark/benchmark.h>

#include <cxxabi.h>

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <set>
#include <string>
#include <typeinfo>
#include <vector>

#include <fmt/format.h>

#include "chain_scene.hpp"
#include "cranesim/assembly/assembler.hpp"
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

  explicit CraneFixture(const std::string& scene) {
    model = cranesim::compileModel(cranesim::readScene(std::string(CRANESIM_SOURCE_DIR) + "/configs/" + scene));
    assembler = std::make_unique<cranesim::Assembler>(model);
    statics = std::make_unique<cranesim::EquilibriumSystem>(model, 0.0);
    const auto& a = *assembler;
    y.assign(a.size(), 0.0);
    yp.assign(a.size(), 0.0);
    for (int i = 0; i < model.nq; ++i) y[i] = model.q0[i];
    for (int i = 0; i < model.m; ++i) y[a.lambdaOffset() + i] = 1e6;
    res.assign(a.size(), 0.0);
    values.assign(a.pattern().nonZeros(), 0.0);
    x.resize(statics->size());
    x << model.q0, cranesim::VecX::Constant(model.m, 1e6);
  }
};

CraneFixture& crane(bool condensed) {
  static std::unique_ptr<CraneFixture> cache[2];
  auto& f = cache[condensed];
  if (!f) f = std::make_unique<CraneFixture>(condensed ? "crane_condensed.yaml" : "crane.yaml");
  return *f;
}

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

BENCHMARK(BM_CraneResidual)->Arg(0)->Arg(1)->ArgName("condensed")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CraneJacobian)->Arg(0)->Arg(1)->ArgName("condensed")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CraneStaticJacobian)->Arg(0)->Arg(1)->ArgName("condensed")->Unit(benchmark::kMillisecond);

// Args: {links, ggl (1) or baumgarte (0)}.
BENCHMARK(BM_Residual)->ArgsProduct({{8, 64}, {1, 0}})->ArgNames({"N", "ggl"})->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Jacobian)->ArgsProduct({{8, 64}, {1, 0}})->ArgNames({"N", "ggl"})->Unit(benchmark::kMicrosecond);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  registerCraneElementBenchmarks();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
