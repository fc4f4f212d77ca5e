#include "cranesim/solvers/dynamics.hpp"

#include <fmt/format.h>
#include <idas/idas.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <cstring>

#include "cranesim/solvers/generalized_alpha.hpp"
#include "cranesim/solvers/serial_vector_ops.hpp"
#include "cranesim/solvers/simulation.hpp"
#include "cranesim/solvers/sparse_lu_linear_solver.hpp"

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
  static_cast<IdaUserData*>(data)->assembler->workPowers(t, N_VGetArrayPointer(y), N_VGetArrayPointer(rq));
  return 0;
}

void errorHandler(int code, const char* module, const char* function, char* message, void* data) {
  auto* d = static_cast<IdaUserData*>(data);
  d->last_error = fmt::format("{} ({}, {}, flag {})", message, module, function, code);
}

void check(int flag, const char* what) {
  if (flag < 0) throw std::runtime_error(fmt::format("IDAS set-up failed in {} (flag {})", what, flag));
}

/// IDAS' variable-order BDF with KLU (SparseLU) on the assembler's Jacobian; owns the SUNDIALS objects.
class IdasStepper final : public TimeStepper {
 public:
  IdasStepper(const Assembler& assembler, const DynamicState& s) : data_{&assembler, {}}, t_(s.t) {
    const Model& model = assembler.model();
    const int n = assembler.size();
    check(SUNContext_Create(nullptr, &ctx_), "SUNContext_Create");
    y_ = N_VNew_Serial(n, ctx_);
    yp_ = N_VNew_Serial(n, ctx_);
    id_ = N_VNew_Serial(n, ctx_);
    dense_ = N_VNew_Serial(n, ctx_);
    yq_ = N_VNew_Serial(WorkTerms::kCount, ctx_);
    dense_q_ = N_VNew_Serial(WorkTerms::kCount, ctx_);
    for (N_Vector v : {y_, yp_, id_, dense_, yq_, dense_q_}) useCompiledSerialOps(v);
    N_VConst(0.0, yq_);
    load(assembler, s);
    mem_ = IDACreate(ctx_);
    check(IDAInit(mem_, residualCallback, s.t, y_, yp_), "IDAInit");
    check(IDASetUserData(mem_, &data_), "IDASetUserData");
    check(IDASetErrHandlerFn(mem_, errorHandler, &data_), "IDASetErrHandlerFn");
    atol_ = N_VNew_Serial(n, ctx_);
    double* atol = N_VGetArrayPointer(atol_);
    std::fill(atol, atol + n, model.solver.atol_multipliers);
    const VecX state_atol = model.absoluteTolerances();
    std::copy(state_atol.data(), state_atol.data() + state_atol.size(), atol);
    check(IDASVtolerances(mem_, model.solver.rtol, atol_), "IDASVtolerances");
    const SparsityPattern& p = assembler.pattern();
    A_ = SUNSparseMatrix(n, n, std::max(p.nonZeros(), 1), CSC_MAT, ctx_);
    LS_ = sparseLuLinearSolver(ctx_);
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
    check(IDASetEtaMax(mem_, model.solver.max_step_growth), "IDASetEtaMax");
    if (model.solver.initial_step > 0.0) check(IDASetInitStep(mem_, model.solver.initial_step), "IDASetInitStep");
    check(IDASetMaxNumSteps(mem_, 100000), "IDASetMaxNumSteps");
    check(IDASetNonlinConvCoef(mem_, model.solver.newton_coefficient), "IDASetNonlinConvCoef");
    check(IDAQuadInit(mem_, quadratureCallback, yq_), "IDAQuadInit");
    if (model.solver.work_error_control) {
      check(IDAQuadSStolerances(mem_, model.solver.rtol, model.solver.atol.position), "IDAQuadSStolerances");
      check(IDASetQuadErrCon(mem_, SUNTRUE), "IDASetQuadErrCon");
    }
  }

  ~IdasStepper() override {
    IDAFree(&mem_);
    SUNLinSolFree(LS_);
    SUNMatDestroy(A_);
    for (N_Vector v : {y_, yp_, id_, atol_, yq_, dense_, dense_q_}) N_VDestroy(v);
    SUNContext_Free(&ctx_);
  }

  StepOutcome step(double t_stop) override {
    IDASetStopTime(mem_, t_stop);
    double t_ret = t_;
    const int flag = IDASolve(mem_, t_stop, &t_ret, y_, dense_, IDA_ONE_STEP);
    StepOutcome out;
    if (flag < 0) {
      out.failure = data_.last_error.empty() ? fmt::format("IDAS flag {}", flag) : data_.last_error;
      return out;
    }
    t_ = t_ret;
    out.reached_stop = flag == IDA_TSTOP_RETURN;
    return out;
  }

  double time() const override { return t_; }
  double* state() override { return N_VGetArrayPointer(y_); }

  void interpolate(double t, double* y, double* work) override {
    IDAGetDky(mem_, t, 0, dense_);
    IDAGetQuadDky(mem_, t, 0, dense_q_);
    std::copy_n(N_VGetArrayPointer(dense_), N_VGetLength(dense_), y);
    std::copy_n(N_VGetArrayPointer(dense_q_), WorkTerms::kCount, work);
  }

  void work(double* work) override {
    double t_quadrature = 0.0;
    IDAGetQuad(mem_, &t_quadrature, dense_q_);
    std::copy_n(N_VGetArrayPointer(dense_q_), WorkTerms::kCount, work);
  }

  void restart(const DynamicState& s) override {
    addCounters(before_restarts_);
    work(N_VGetArrayPointer(yq_));
    load(*data_.assembler, s);
    t_ = s.t;
    check(IDAReInit(mem_, s.t, y_, yp_), "IDAReInit");
    check(IDAQuadReInit(mem_, yq_), "IDAQuadReInit");
  }

  void forgetPivots() override { cranesim::forgetPivots(LS_); }

  void setWork(const double* work) override {
    std::copy_n(work, WorkTerms::kCount, N_VGetArrayPointer(yq_));
    check(IDAQuadReInit(mem_, yq_), "IDAQuadReInit");
  }

  void setMaxStep(double h) override {
    const double scene_limit = data_.assembler->model().solver.max_step;
    const double limit = h > 0.0 && scene_limit > 0.0 ? std::min(h, scene_limit) : h > 0.0 ? h : scene_limit;
    check(IDASetMaxStep(mem_, limit), "IDASetMaxStep");
    // IDAS holds the limit only where it raises the step; raising it whenever the error allows
    // (not only when it allows doubling) brings a longer step down to the limit at once, and
    // raising it by as much as the error allows brings a step cut short back up to it at once.
    // A step the error would shorten by less than half is kept: shortened by IDAS' 10 %, it
    // leaves a sliver before the stop time and every advance after it takes one step more.
    check(IDASetEtaFixedStepBounds(mem_, 0.5, 1.0), "IDASetEtaFixedStepBounds");
    check(IDASetEtaMax(mem_, 10.0), "IDASetEtaMax");
  }

  /// IDAS' counters restart with IDAReInit; they are summed over the segments.
  SolverStatistics statistics() override {
    SolverStatistics s = before_restarts_;
    addCounters(s);
    IDAGetLastStep(mem_, &s.last_step_size);
    IDAGetLastOrder(mem_, &s.last_order);
    return s;
  }

 private:
  void load(const Assembler& assembler, const DynamicState& s) {
    stateVectors(assembler, s, N_VGetArrayPointer(y_), N_VGetArrayPointer(yp_));
  }

  void addCounters(SolverStatistics& s) const {
    long v = 0;
    IDAGetNumSteps(mem_, &v), s.steps += v;
    IDAGetNumResEvals(mem_, &v), s.residual_evaluations += v;
    IDAGetNumJacEvals(mem_, &v), s.jacobian_evaluations += v;
    IDAGetNumLinSolvSetups(mem_, &v), s.linear_setups += v;
    IDAGetNumNonlinSolvIters(mem_, &v), s.nonlinear_iterations += v;
    IDAGetNumNonlinSolvConvFails(mem_, &v), s.nonlinear_failures += v;
    IDAGetNumErrTestFails(mem_, &v), s.error_test_failures += v;
  }

  IdaUserData data_;
  double t_ = 0.0;
  SolverStatistics before_restarts_;
  SUNContext ctx_ = nullptr;
  N_Vector y_ = nullptr, yp_ = nullptr, id_ = nullptr, atol_ = nullptr, yq_ = nullptr, dense_ = nullptr,
           dense_q_ = nullptr;
  SUNMatrix A_ = nullptr;
  SUNLinearSolver LS_ = nullptr;
  void* mem_ = nullptr;
};

}  // namespace

void stateVectors(const Assembler& assembler, const DynamicState& s, double* y, double* yp) {
  const Model& model = assembler.model();
  std::fill(y, y + assembler.size(), 0.0);
  std::fill(yp, yp + assembler.size(), 0.0);
  std::copy(s.q.data(), s.q.data() + model.nq, y);
  std::copy(s.v.data(), s.v.data() + model.nv, y + assembler.vOffset());
  std::copy(s.lambda.data(), s.lambda.data() + model.m, y + assembler.lambdaOffset());
  std::copy(s.qdot.data(), s.qdot.data() + model.nq, yp);
  std::copy(s.a.data(), s.a.data() + model.nv, yp + assembler.vOffset());
}

std::unique_ptr<TimeStepper> makeTimeStepper(const Assembler& assembler, const DynamicState& initial) {
  const SolverSpec& solver = assembler.model().solver;
  if (solver.integrator == Integrator::GeneralizedAlpha)
    return makeGeneralizedAlphaStepper(assembler, initial, solver.rho_inf);
  return std::make_unique<IdasStepper>(assembler, initial);
}

SimulationOutcome simulate(const Assembler& assembler, const DynamicState& initial, SampleSink& sink,
                           const SimulationControl& control) {
  Simulation simulation(assembler, initial, sink);
  simulation.advanceTo(assembler.model().solver.t_end, control);
  return simulation.outcome();
}

}  // namespace cranesim
