#include "cranesim/solvers/dynamics.hpp"

#include <fmt/format.h>
#include <idas/idas.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <chrono>
#include <cstring>

#include "cranesim/math/rotation.hpp"

namespace cranesim {
namespace {

struct IdaUserData {
  const Assembler* assembler;
  std::string last_error;
};

int residualCallback(sunrealtype t, N_Vector y, N_Vector yp, N_Vector r, void* data) {
  const auto* d = static_cast<IdaUserData*>(data);
  d->assembler->residual(t, N_VGetArrayPointer(y), N_VGetArrayPointer(yp), N_VGetArrayPointer(r));
  return 0;
}

int jacobianCallback(sunrealtype t, sunrealtype cj, N_Vector y, N_Vector yp, N_Vector, SUNMatrix J,
                     void* data, N_Vector, N_Vector, N_Vector) {
  const auto* d = static_cast<IdaUserData*>(data);
  const SparsityPattern& p = d->assembler->pattern();
  std::copy(p.columnPointers().begin(), p.columnPointers().end(), SUNSparseMatrix_IndexPointers(J));
  std::copy(p.rowIndices().begin(), p.rowIndices().end(), SUNSparseMatrix_IndexValues(J));
  d->assembler->jacobian(t, cj, N_VGetArrayPointer(y), N_VGetArrayPointer(yp), SUNSparseMatrix_Data(J));
  return 0;
}

/// Quadratures: the powers of the energy balance's work terms (WorkTerms).
int quadratureCallback(sunrealtype t, N_Vector y, N_Vector, N_Vector rq, void* data) {
  const auto* d = static_cast<IdaUserData*>(data);
  d->assembler->workPowers(t, N_VGetArrayPointer(y), N_VGetArrayPointer(rq));
  return 0;
}

void errorHandler(int code, const char* module, const char* function, char* message, void* data) {
  auto* d = static_cast<IdaUserData*>(data);
  d->last_error = fmt::format("{} ({}, {}, flag {})", message, module, function, code);
}

void check(int flag, const char* what) {
  if (flag < 0) throw std::runtime_error(fmt::format("IDAS set-up failed in {} (flag {})", what, flag));
}

/// Owns the SUNDIALS objects of one run.
class Integrator {
 public:
  Integrator(const Assembler& assembler, const DynamicState& s) : data_{&assembler, {}} {
    const Model& model = assembler.model();
    const int n = assembler.size();
    check(SUNContext_Create(nullptr, &ctx_), "SUNContext_Create");
    y_ = N_VNew_Serial(n, ctx_);
    yp_ = N_VNew_Serial(n, ctx_);
    id_ = N_VNew_Serial(n, ctx_);
    yq_ = N_VNew_Serial(WorkTerms::kCount, ctx_);
    N_VConst(0.0, yq_);
    load(assembler, s);
    mem_ = IDACreate(ctx_);
    check(IDAInit(mem_, residualCallback, s.t, y_, yp_), "IDAInit");
    check(IDASetUserData(mem_, &data_), "IDASetUserData");
    check(IDASetErrHandlerFn(mem_, errorHandler, &data_), "IDASetErrHandlerFn");
    atol_ = N_VNew_Serial(n, ctx_);
    double* atol = N_VGetArrayPointer(atol_);
    std::fill(atol, atol + n, model.solver.atol_multipliers);
    std::fill(atol, atol + model.nq + model.nv, model.solver.atol);
    check(IDASVtolerances(mem_, model.solver.rtol, atol_), "IDASVtolerances");
    const SparsityPattern& p = assembler.pattern();
    A_ = SUNSparseMatrix(n, n, std::max(p.nonZeros(), 1), CSC_MAT, ctx_);
    LS_ = SUNLinSol_KLU(y_, A_, ctx_);
    check(IDASetLinearSolver(mem_, LS_, A_), "IDASetLinearSolver");
    check(IDASetJacFn(mem_, jacobianCallback), "IDASetJacFn");
    // Differential: q and dq. Algebraic, excluded from the error test: λ (and μ).
    double* id = N_VGetArrayPointer(id_);
    std::fill(id, id + n, 0.0);
    std::fill(id, id + model.nq + model.nv, 1.0);
    check(IDASetId(mem_, id_), "IDASetId");
    check(IDASetSuppressAlg(mem_, SUNTRUE), "IDASetSuppressAlg");
    check(IDASetMaxOrd(mem_, model.solver.max_order), "IDASetMaxOrd");
    if (model.solver.max_step > 0.0) check(IDASetMaxStep(mem_, model.solver.max_step), "IDASetMaxStep");
    if (model.solver.initial_step > 0.0) check(IDASetInitStep(mem_, model.solver.initial_step), "IDASetInitStep");
    check(IDASetMaxNumSteps(mem_, 100000), "IDASetMaxNumSteps");
    check(IDASetNonlinConvCoef(mem_, model.solver.newton_coefficient), "IDASetNonlinConvCoef");
    check(IDAQuadInit(mem_, quadratureCallback, yq_), "IDAQuadInit");
    if (model.solver.work_error_control) {
      check(IDAQuadSStolerances(mem_, model.solver.rtol, model.solver.atol), "IDAQuadSStolerances");
      check(IDASetQuadErrCon(mem_, SUNTRUE), "IDASetQuadErrCon");
    }
  }

  ~Integrator() {
    IDAFree(&mem_);
    SUNLinSolFree(LS_);
    SUNMatDestroy(A_);
    N_VDestroy(y_);
    N_VDestroy(yp_);
    N_VDestroy(id_);
    N_VDestroy(atol_);
    N_VDestroy(yq_);
    SUNContext_Free(&ctx_);
  }

  void restart(const Assembler& assembler, const DynamicState& s) {
    load(assembler, s);
    check(IDAReInit(mem_, s.t, y_, yp_), "IDAReInit");
    check(IDAQuadReInit(mem_, yq_), "IDAQuadReInit");
  }

  void* mem() { return mem_; }
  N_Vector y() { return y_; }
  N_Vector yq() { return yq_; }
  const std::string& lastError() const { return data_.last_error; }

 private:
  void load(const Assembler& assembler, const DynamicState& s) {
    const Model& model = assembler.model();
    double* y = N_VGetArrayPointer(y_);
    double* yp = N_VGetArrayPointer(yp_);
    std::fill(y, y + assembler.size(), 0.0);
    std::fill(yp, yp + assembler.size(), 0.0);
    std::copy(s.q.data(), s.q.data() + model.nq, y);
    std::copy(s.v.data(), s.v.data() + model.nv, y + assembler.vOffset());
    std::copy(s.lambda.data(), s.lambda.data() + model.m, y + assembler.lambdaOffset());
    std::copy(s.qdot.data(), s.qdot.data() + model.nq, yp);
    std::copy(s.a.data(), s.a.data() + model.nv, yp + assembler.vOffset());
  }

  IdaUserData data_;
  SUNContext ctx_ = nullptr;
  N_Vector y_ = nullptr, yp_ = nullptr, id_ = nullptr, yq_ = nullptr, atol_ = nullptr;
  SUNMatrix A_ = nullptr;
  SUNLinearSolver LS_ = nullptr;
  void* mem_ = nullptr;
};

constexpr double kStallFraction = 1e-12;  // a step shorter than this (relative to t) makes no progress
constexpr long kMaxStalledSteps = 1000;

DynamicState stateOf(const Assembler& assembler, double t, const double* y) {
  const Model& model = assembler.model();
  DynamicState s;
  s.t = t;
  s.q = Eigen::Map<const VecX>(y, model.nq);
  s.v = Eigen::Map<const VecX>(y + assembler.vOffset(), model.nv);
  return s;
}

/// Re-parameterises every rotation vector beyond the threshold; returns how many changed.
int reparameterise(const Model& model, double* q) {
  int changed = 0;
  for (const Node& n : model.nodes) {
    if (!n.hasRotation()) continue;
    Vec3 phi(q + n.q + 3);
    if (cranesim::reparameterise(phi)) {
      std::copy(phi.data(), phi.data() + 3, q + n.q + 3);
      ++changed;
    }
  }
  return changed;
}

void collectStatistics(void* mem, SolverStatistics& s) {
  long v = 0;
  IDAGetNumSteps(mem, &v), s.steps += v;
  IDAGetNumResEvals(mem, &v), s.residual_evaluations += v;
  IDAGetNumJacEvals(mem, &v), s.jacobian_evaluations += v;
  IDAGetNumLinSolvSetups(mem, &v), s.linear_setups += v;
  IDAGetNumNonlinSolvIters(mem, &v), s.nonlinear_iterations += v;
  IDAGetNumNonlinSolvConvFails(mem, &v), s.nonlinear_failures += v;
  IDAGetNumErrTestFails(mem, &v), s.error_test_failures += v;
  IDAGetLastStep(mem, &s.last_step_size);
  IDAGetLastOrder(mem, &s.last_order);
}

}  // namespace

SimulationOutcome simulate(const Assembler& assembler, const DynamicState& initial, SampleSink& sink,
                           const SimulationControl& control) {
  const auto wall_start = std::chrono::steady_clock::now();
  const Model& model = assembler.model();
  const double t_end = model.solver.t_end, dt_out = model.output.interval;
  const std::vector<double> breakpoints = model.breakpoints();

  SimulationOutcome outcome;
  Integrator ida(assembler, initial);
  N_Vector dense = N_VClone(ida.y());
  // Counters restart with IDAReInit; they are summed over segments.
  SolverStatistics total;

  double t = initial.t;
  N_Vector quadrature = N_VClone(ida.yq());
  long stalled_steps = 0;
  long next_sample = 1;
  bool sampled_end = false;
  sink.sample(t, N_VGetArrayPointer(ida.y()), WorkTerms{});
  std::size_t next_break = 0;
  while (next_break < breakpoints.size() && breakpoints[next_break] <= t) ++next_break;

  const auto finish = [&](bool complete, std::string message) {
    collectStatistics(ida.mem(), total);
    outcome.complete = complete;
    outcome.message = std::move(message);
    outcome.t_reached = t;
    outcome.statistics = total;
    outcome.statistics.wall_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    N_VDestroy(dense);
    N_VDestroy(quadrature);
    return outcome;
  };

  while (t < t_end) {
    const double t_stop = next_break < breakpoints.size() ? breakpoints[next_break] : t_end;
    IDASetStopTime(ida.mem(), t_stop);
    double t_ret = t;
    const int flag = IDASolve(ida.mem(), t_stop, &t_ret, ida.y(), dense, IDA_ONE_STEP);
    if (flag < 0) {
      const std::string why = ida.lastError().empty() ? fmt::format("IDAS flag {}", flag) : ida.lastError();
      return finish(false, fmt::format("solver failure at t = {:.6g} s: {}", t, why));
    }
    // Samples up to t_ret, interpolated by IDAS' dense output; the last one exactly at t_end.
    const bool segment_end = flag == IDA_TSTOP_RETURN;
    const double eps = 1e-12 * std::max(1.0, std::abs(t_ret));
    while (!sampled_end) {
      double ts = initial.t + static_cast<double>(next_sample) * dt_out;
      if (ts > t_end - eps) ts = t_end;
      if (ts > t_ret + eps) break;
      IDAGetDky(ida.mem(), std::min(ts, t_ret), 0, dense);
      IDAGetQuadDky(ida.mem(), std::min(ts, t_ret), 0, quadrature);
      sink.sample(ts, N_VGetArrayPointer(dense), WorkTerms::fromArray(N_VGetArrayPointer(quadrature)));
      ++next_sample;
      sampled_end = ts == t_end;
    }
    // IDAS' step limit does not apply in one-step mode: stop a run whose step size collapsed.
    stalled_steps = t_ret - t > kStallFraction * std::max(1.0, std::abs(t_ret)) ? 0 : stalled_steps + 1;
    if (stalled_steps > kMaxStalledSteps) {
      t = t_ret;
      return finish(false, fmt::format("solver failure at t = {:.6g} s: the step size collapsed to {:.3g} s for {} "
                                       "steps (a locked mechanism or a discontinuity the model cannot follow)",
                                       t, t_ret - t, kMaxStalledSteps));
    }
    t = t_ret;
    if (model.m > 0) {
      const double* yy = N_VGetArrayPointer(ida.y());
      total.max_step_constraint_residual =
          std::max(total.max_step_constraint_residual, assembler.constraintResidual(t, yy));
    }
    if (control.on_step) control.on_step(t);
    if (control.stop_requested && control.stop_requested->load())
      return finish(false, fmt::format("interrupted at t = {:.6g} s", t));

    double* y = N_VGetArrayPointer(ida.y());
    const int changed = reparameterise(model, y);
    if ((segment_end || changed > 0) && t < t_end) {
      if (segment_end) ++next_break;
      collectStatistics(ida.mem(), total);
      total.reparameterisations += changed;
      ++total.restarts;
      double t_quadrature = 0.0;
      IDAGetQuad(ida.mem(), &t_quadrature, ida.yq());
      DynamicState s = stateOf(assembler, t, y);
      try {
        // A velocity drive may jump at a breakpoint: project dq onto the coming segment's
        // velocity constraints, then solve its accelerations and multipliers.
        if (segment_end && model.m > 0) {
          const ConstraintState C = assembler.constraints(t, s.q.data(), s.v.data(), Limit::Right);
          const MatX G = MatX(C.G);
          s.v -= G.transpose() * (G * G.transpose()).ldlt().solve(C.phi_dot);
        }
        solveAccelerations(assembler, s, Limit::Right);
      } catch (const std::exception& e) {
        return finish(false, e.what());
      }
      ida.restart(assembler, s);
    }
  }
  return finish(true, "");
}

}  // namespace cranesim
