#include "cranesim/planning/qr_trajectory.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"  // Ipopt 3.11 headers
#include <IpIpoptApplication.hpp>
#include <IpSolveStatistics.hpp>
#include <IpTNLP.hpp>
#pragma GCC diagnostic pop

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "cranesim/planning/ipopt_application.hpp"

namespace cranesim {

namespace {

using ControlMatrix = Eigen::Matrix<double, 4, 2>;

constexpr int kStateSize = 4;
constexpr int kControlSize = 2;
constexpr std::array<const char*, kStateSize> kStateNames = {"x", "z", "vx", "vz"};

EndState doubleIntegrator(const EndState& state, const EndControl& control) {
  return {state[2], state[3], control[0], control[1]};
}

EndState rk4Step(const EndState& state, const EndControl& control, double ts) {
  const EndState k1 = doubleIntegrator(state, control);
  const EndState k2 = doubleIntegrator(state + 0.5 * ts * k1, control);
  const EndState k3 = doubleIntegrator(state + 0.5 * ts * k2, control);
  const EndState k4 = doubleIntegrator(state + ts * k3, control);
  return state + ts / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
}

std::string format(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

[[noreturn]] void fail(const std::string& message) { throw std::invalid_argument(message); }

template <int Size>
void requireOrderedBounds(const char* name, const Eigen::Matrix<double, Size, 1>& lower,
                          const Eigen::Matrix<double, Size, 1>& upper) {
  for (int i = 0; i < Size; ++i)
    if (!(lower[i] <= upper[i]))
      fail(std::string(name) + "_min[" + std::to_string(i) + "] = " + format(lower[i]) + " > " + name + "_max[" +
           std::to_string(i) + "] = " + format(upper[i]));
}

void requireWithinStateBounds(const char* name, const EndState& state, const QrProblem& problem) {
  for (int i = 0; i < kStateSize; ++i) {
    const std::string entry = std::string(name) + " " + kStateNames[i] + " = " + format(state[i]);
    if (!std::isfinite(state[i])) fail(entry + " is not finite");
    if (state[i] < problem.state_min[i] || state[i] > problem.state_max[i])
      fail(entry + " lies outside the trajectory's state bounds [" + format(problem.state_min[i]) + ", " +
           format(problem.state_max[i]) + "] (state_min, state_max); widen them to plan there");
  }
}

/// Symmetric with all eigenvalues ≥ −ε (semi-definite) or > ε (definite), ε relative to the
/// largest entry: Cholesky of M ± εI succeeds exactly when λ_min(M) ∓ ε > 0.
template <int Size>
bool isSymmetricDefinite(const Eigen::Matrix<double, Size, Size>& matrix, bool strictly) {
  using Matrix = Eigen::Matrix<double, Size, Size>;
  if (!matrix.allFinite()) return false;
  const double tolerance = 1e-12 * std::max(1.0, matrix.cwiseAbs().maxCoeff());
  if ((matrix - matrix.transpose()).cwiseAbs().maxCoeff() > tolerance) return false;
  const Matrix shifted = matrix + (strictly ? -tolerance : tolerance) * Matrix::Identity();
  return Eigen::LLT<Matrix>(shifted).info() == Eigen::Success;
}

/// Rest-to-rest transfer of one axis (position index `axis`, velocity `axis + 2`), with the
/// speed bound in the direction of travel. Accelerating with a₁ and braking with a₂ up to
/// speed v covers v²/a and takes 2v/a with a = 2/(1/a₁ + 1/a₂), so the symmetric profile
/// with that harmonic mean is exact for asymmetric acceleration bounds.
void requireReachableAtRest(const QrProblem& problem, int axis) {
  const int velocity = axis + 2;
  if (problem.start[velocity] != 0.0 || problem.target[velocity] != 0.0) return;
  const double distance = problem.target[axis] - problem.start[axis];
  const bool forward = distance > 0.0;
  const double speed = forward ? problem.state_max[velocity] : -problem.state_min[velocity];
  const double accelerate = forward ? problem.control_max[axis] : -problem.control_min[axis];
  const double brake = forward ? -problem.control_min[axis] : problem.control_max[axis];
  const double acceleration = std::min(accelerate, brake) <= 0.0 ? 0.0 : 2.0 / (1.0 / accelerate + 1.0 / brake);
  const double needed = minimumTransferTime(distance, speed, acceleration);
  const double available = problem.steps * problem.sample_time;
  if (available < needed * (1.0 - 1e-12))  // slack for the rounding of steps·sample_time
    fail(std::string("infeasible horizon: ") + kStateNames[axis] + " needs at least " + format(needed) + " s to move " +
         format(std::abs(distance)) + " m from rest to rest within its velocity and acceleration bounds, but steps·sample_time = " +
         format(available) + " s");
}

double qrCost(const QrProblem& problem, const std::vector<EndState>& states, const std::vector<EndControl>& controls) {
  double cost = 0.0;
  for (std::size_t k = 0; k < controls.size(); ++k) {
    const EndState error = states[k] - problem.target;
    cost += error.dot(problem.Q * error) + controls[k].dot(problem.R * controls[k]);
  }
  const EndState final_error = states.back() - problem.target;
  return cost + final_error.dot(problem.P_end * final_error);  // (6-1)
}

/// A primal-dual point of a window NLP in Ipopt's ordering.
struct PrimalDual {
  std::vector<double> variables, lower_bound_multipliers, upper_bound_multipliers, constraint_multipliers;
};

/// Moves `count` blocks of `width` values one block forward, repeating the last block.
void shiftBlocks(double* values, int count, int width) {
  std::copy(values + width, values + count * width, values);
}

/// (6-1) over `steps` steps from `start` as an NLP in z = (x_0 … x_N, u_0 … u_{N−1}); x_0 is
/// fixed by equal bounds and the RK4 steps x_{k+1} − A x_k − B u_k = 0 are the constraints.
class QrWindowNlp final : public Ipopt::TNLP {
 public:
  /// `initial_guess`: a primal-dual starting point of the same size; nullptr: every state at
  /// `start`, zero controls.
  QrWindowNlp(const QrProblem& problem, const Eigen::Matrix4d& A, const ControlMatrix& B, const EndState& start,
              int steps, const PrimalDual* initial_guess = nullptr)
      : problem_(problem), A_(A), B_(B), start_(start), steps_(steps), initial_guess_(initial_guess) {}

  PrimalDual solution;

  EndState solutionState(int k) const { return state(solution.variables.data(), k); }
  EndControl solutionControl(int k) const { return control(solution.variables.data(), k); }

  /// The solution one step later: every block moves one step forward, the last control is
  /// repeated and the last state follows from it.
  PrimalDual shiftedSolution() const {
    PrimalDual shifted = solution;
    for (auto* values : {&shifted.variables, &shifted.lower_bound_multipliers, &shifted.upper_bound_multipliers}) {
      shiftBlocks(values->data(), steps_ + 1, kStateSize);
      shiftBlocks(values->data() + controlIndex(0), steps_, kControlSize);
    }
    shiftBlocks(shifted.constraint_multipliers.data(), steps_, kStateSize);
    double* z = shifted.variables.data();
    state(z, steps_) = A_ * state(z, steps_) + B_ * control(z, steps_ - 1);
    return shifted;
  }

  bool get_nlp_info(Ipopt::Index& n, Ipopt::Index& m, Ipopt::Index& nnz_jac_g, Ipopt::Index& nnz_h_lag,
                    IndexStyleEnum& index_style) override {
    n = variableCount();
    m = kStateSize * steps_;
    nnz_jac_g = m * kJacobianRowSize;
    nnz_h_lag = (steps_ + 1) * kStateHessianSize + steps_ * kControlHessianSize;
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Ipopt::Index, Ipopt::Number* x_l, Ipopt::Number* x_u, Ipopt::Index m, Ipopt::Number* g_l,
                       Ipopt::Number* g_u) override {
    for (int i = 0; i < kStateSize; ++i) x_l[i] = x_u[i] = start_[i];
    for (int k = 1; k <= steps_; ++k)
      for (int i = 0; i < kStateSize; ++i) {
        x_l[stateIndex(k) + i] = ipoptBound(problem_.state_min[i]);
        x_u[stateIndex(k) + i] = ipoptBound(problem_.state_max[i]);
      }
    for (int k = 0; k < steps_; ++k)
      for (int j = 0; j < kControlSize; ++j) {
        x_l[controlIndex(k) + j] = ipoptBound(problem_.control_min[j]);
        x_u[controlIndex(k) + j] = ipoptBound(problem_.control_max[j]);
      }
    std::fill(g_l, g_l + m, 0.0);
    std::fill(g_u, g_u + m, 0.0);
    return true;
  }

  bool get_starting_point(Ipopt::Index, bool init_z, Ipopt::Number* z, bool init_bound_multipliers, Ipopt::Number* z_L,
                          Ipopt::Number* z_U, Ipopt::Index, bool init_lambda, Ipopt::Number* lambda) override {
    if (!initial_guess_) {
      for (int k = 0; k <= steps_; ++k) state(z, k) = start_;
      for (int k = 0; k < steps_; ++k) control(z, k).setZero();
      return !init_bound_multipliers && !init_lambda;
    }
    if (init_z) std::copy(initial_guess_->variables.begin(), initial_guess_->variables.end(), z);
    if (init_bound_multipliers) {
      std::copy(initial_guess_->lower_bound_multipliers.begin(), initial_guess_->lower_bound_multipliers.end(), z_L);
      std::copy(initial_guess_->upper_bound_multipliers.begin(), initial_guess_->upper_bound_multipliers.end(), z_U);
    }
    if (init_lambda)
      std::copy(initial_guess_->constraint_multipliers.begin(), initial_guess_->constraint_multipliers.end(), lambda);
    return true;
  }

  bool eval_f(Ipopt::Index, const Ipopt::Number* z, bool, Ipopt::Number& obj_value) override {
    obj_value = 0.0;
    for (int k = 0; k <= steps_; ++k) {
      const EndState error = state(z, k) - problem_.target;
      obj_value += error.dot(stateWeight(k) * error);
    }
    for (int k = 0; k < steps_; ++k) obj_value += control(z, k).dot(problem_.R * control(z, k));
    return true;
  }

  bool eval_grad_f(Ipopt::Index, const Ipopt::Number* z, bool, Ipopt::Number* grad_f) override {
    for (int k = 0; k <= steps_; ++k) state(grad_f, k) = 2.0 * stateWeight(k) * (state(z, k) - problem_.target);
    for (int k = 0; k < steps_; ++k) control(grad_f, k) = 2.0 * problem_.R * control(z, k);
    return true;
  }

  bool eval_g(Ipopt::Index, const Ipopt::Number* z, bool, Ipopt::Index, Ipopt::Number* g) override {
    for (int k = 0; k < steps_; ++k)
      Eigen::Map<EndState>(g + kStateSize * k) = state(z, k + 1) - A_ * state(z, k) - B_ * control(z, k);
    return true;
  }

  // Row 4k + i of the (constant) Jacobian: +1 at x_{k+1,i}, −A(i, ·) at x_k, −B(i, ·) at u_k.
  bool eval_jac_g(Ipopt::Index, const Ipopt::Number*, bool, Ipopt::Index, Ipopt::Index, Ipopt::Index* iRow,
                  Ipopt::Index* jCol, Ipopt::Number* values) override {
    int entry = 0;
    for (int k = 0; k < steps_; ++k)
      for (int i = 0; i < kStateSize; ++i) {
        const int row = kStateSize * k + i;
        auto put = [&](int column, double value) {
          if (values) {
            values[entry] = value;
          } else {
            iRow[entry] = row;
            jCol[entry] = column;
          }
          ++entry;
        };
        put(stateIndex(k + 1) + i, 1.0);
        for (int j = 0; j < kStateSize; ++j) put(stateIndex(k) + j, -A_(i, j));
        for (int j = 0; j < kControlSize; ++j) put(controlIndex(k) + j, -B_(i, j));
      }
    return true;
  }

  // The constraints are linear, so the Hessian of the Lagrangian is that of the cost (6-1):
  // block diagonal 2Q, …, 2Q, 2P_end, 2R, …, 2R; lower triangles only.
  bool eval_h(Ipopt::Index, const Ipopt::Number*, bool, Ipopt::Number obj_factor, Ipopt::Index,
              const Ipopt::Number*, bool, Ipopt::Index, Ipopt::Index* iRow, Ipopt::Index* jCol,
              Ipopt::Number* values) override {
    int entry = 0;
    auto putLowerTriangle = [&](int offset, const auto& weight) {
      for (int r = 0; r < weight.rows(); ++r)
        for (int c = 0; c <= r; ++c) {
          if (values) {
            values[entry] = 2.0 * obj_factor * weight(r, c);
          } else {
            iRow[entry] = offset + r;
            jCol[entry] = offset + c;
          }
          ++entry;
        }
    };
    for (int k = 0; k <= steps_; ++k) putLowerTriangle(stateIndex(k), stateWeight(k));
    for (int k = 0; k < steps_; ++k) putLowerTriangle(controlIndex(k), problem_.R);
    return true;
  }

  void finalize_solution(Ipopt::SolverReturn, Ipopt::Index n, const Ipopt::Number* z, const Ipopt::Number* z_L,
                         const Ipopt::Number* z_U, Ipopt::Index m, const Ipopt::Number*, const Ipopt::Number* lambda,
                         Ipopt::Number, const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    solution.variables.assign(z, z + n);
    solution.lower_bound_multipliers.assign(z_L, z_L + n);
    solution.upper_bound_multipliers.assign(z_U, z_U + n);
    solution.constraint_multipliers.assign(lambda, lambda + m);
  }

 private:
  static constexpr int kJacobianRowSize = 1 + kStateSize + kControlSize;
  static constexpr int kStateHessianSize = kStateSize * (kStateSize + 1) / 2;
  static constexpr int kControlHessianSize = kControlSize * (kControlSize + 1) / 2;

  /// Ipopt treats |bound| ≥ 1e19 as absent.
  static double ipoptBound(double bound) { return std::clamp(bound, -1e20, 1e20); }

  int variableCount() const { return kStateSize * (steps_ + 1) + kControlSize * steps_; }
  int stateIndex(int k) const { return kStateSize * k; }
  int controlIndex(int k) const { return kStateSize * (steps_ + 1) + kControlSize * k; }
  const Eigen::Matrix4d& stateWeight(int k) const { return k == steps_ ? problem_.P_end : problem_.Q; }

  Eigen::Map<const EndState> state(const double* z, int k) const { return Eigen::Map<const EndState>(z + stateIndex(k)); }
  Eigen::Map<EndState> state(double* z, int k) const { return Eigen::Map<EndState>(z + stateIndex(k)); }
  Eigen::Map<const EndControl> control(const double* z, int k) const {
    return Eigen::Map<const EndControl>(z + controlIndex(k));
  }
  Eigen::Map<EndControl> control(double* z, int k) const { return Eigen::Map<EndControl>(z + controlIndex(k)); }

  const QrProblem& problem_;
  const Eigen::Matrix4d A_;
  const ControlMatrix B_;
  const EndState start_;
  const int steps_;
  const PrimalDual* initial_guess_;
};

Ipopt::SmartPtr<Ipopt::IpoptApplication> makeIpopt(const QrProblem& problem) {
  Ipopt::SmartPtr<Ipopt::IpoptApplication> ipopt =
      ipoptApplication({problem.print_level, problem.tolerance, problem.max_iterations});
  auto& options = *ipopt->Options();
  options.SetStringValue("hessian_constant", "yes");
  options.SetStringValue("jac_c_constant", "yes");
  options.SetStringValue("jac_d_constant", "yes");
  return ipopt;
}

/// Start from the given primal-dual point, pushed only minimally into the interior (about
/// 4 instead of about 20 iterations per receding-horizon window).
void enableWarmStart(Ipopt::IpoptApplication& ipopt) {
  auto& options = *ipopt.Options();
  options.SetStringValue("warm_start_init_point", "yes");
  options.SetNumericValue("warm_start_bound_push", 1e-9);
  options.SetNumericValue("warm_start_mult_bound_push", 1e-9);
}

/// Solves one NLP and returns its iteration count; `context` is appended to the error message.
int solve(Ipopt::IpoptApplication& ipopt, const Ipopt::SmartPtr<QrWindowNlp>& nlp, const std::string& context = "") {
  const Ipopt::ApplicationReturnStatus status = ipopt.OptimizeTNLP(Ipopt::SmartPtr<Ipopt::TNLP>(GetRawPtr(nlp)));
  if (status != Ipopt::Solve_Succeeded && status != Ipopt::Solved_To_Acceptable_Level)
    throw std::runtime_error("Ipopt: " + ipoptStatusInWords(status) + context);
  return ipopt.Statistics()->IterationCount();
}

}  // namespace

void rk4DoubleIntegrator(double ts, Eigen::Matrix4d& A, Eigen::Matrix<double, 4, 2>& B) {
  // The dynamics are linear, so the RK4 step of a basis vector is a column of its matrix.
  for (int j = 0; j < kStateSize; ++j) A.col(j) = rk4Step(EndState::Unit(j), EndControl::Zero(), ts);
  for (int j = 0; j < kControlSize; ++j) B.col(j) = rk4Step(EndState::Zero(), EndControl::Unit(j), ts);
}

double minimumTransferTime(double distance, double v_max, double a_max) {
  const double length = std::abs(distance);
  if (length == 0.0) return 0.0;
  if (v_max <= 0.0 || a_max <= 0.0) return std::numeric_limits<double>::infinity();
  if (length * a_max <= v_max * v_max) return 2.0 * std::sqrt(length / a_max);  // triangle: peak √(d·a) ≤ v_max
  return length / v_max + v_max / a_max;                                         // trapezoid
}

void validate(const QrProblem& problem) {
  if (problem.steps < 1) fail("steps must be ≥ 1 (got " + std::to_string(problem.steps) + ")");
  if (!(problem.sample_time > 0.0) || !std::isfinite(problem.sample_time))
    fail("sample_time must be > 0 and finite (got " + format(problem.sample_time) + ")");
  if (problem.receding_horizon < 0)
    fail("receding horizon h = " + std::to_string(problem.receding_horizon) + " must be ≥ 0");
  if (problem.receding_horizon > problem.steps)
    fail("receding horizon h = " + std::to_string(problem.receding_horizon) + " exceeds steps = " +
         std::to_string(problem.steps));
  if (!(problem.tolerance > 0.0)) fail("tolerance must be > 0 (got " + format(problem.tolerance) + ")");
  if (problem.max_iterations < 1) fail("max_iterations must be ≥ 1 (got " + std::to_string(problem.max_iterations) + ")");
  requireOrderedBounds("state", problem.state_min, problem.state_max);
  requireOrderedBounds("control", problem.control_min, problem.control_max);
  requireWithinStateBounds("start", problem.start, problem);
  requireWithinStateBounds("target", problem.target, problem);
  if (!isSymmetricDefinite(problem.Q, false)) fail("Q is not symmetric positive semi-definite");
  if (!isSymmetricDefinite(problem.P_end, false)) fail("P_end is not symmetric positive semi-definite");
  if (!isSymmetricDefinite(problem.R, true)) fail("R is not positive definite");
  for (int axis = 0; axis < 2; ++axis) requireReachableAtRest(problem, axis);
}

QrTrajectory solveQrTrajectory(const QrProblem& problem) {
  validate(problem);
  const auto started = std::chrono::steady_clock::now();
  Eigen::Matrix4d A;
  ControlMatrix B;
  rk4DoubleIntegrator(problem.sample_time, A, B);
  const auto ipopt = makeIpopt(problem);

  QrTrajectory trajectory;
  if (problem.receding_horizon == 0) {
    const Ipopt::SmartPtr<QrWindowNlp> nlp = new QrWindowNlp(problem, A, B, problem.start, problem.steps);
    trajectory.iterations = solve(*ipopt, nlp);
    for (int k = 0; k <= problem.steps; ++k) trajectory.states.push_back(nlp->solutionState(k));
    for (int k = 0; k < problem.steps; ++k) trajectory.controls.push_back(nlp->solutionControl(k));
  } else {
    // (6-2): plan h steps ahead from the current state, apply only the first control. Each
    // window starts from the previous window's primal-dual solution one step later.
    trajectory.states = {problem.start};
    PrimalDual guess;
    for (int m = 0; m < problem.steps; ++m) {
      const Ipopt::SmartPtr<QrWindowNlp> nlp = new QrWindowNlp(problem, A, B, trajectory.states.back(),
                                                                problem.receding_horizon, m > 0 ? &guess : nullptr);
      trajectory.iterations += solve(*ipopt, nlp, " (receding-horizon window at step " + std::to_string(m) + ")");
      if (m == 0) enableWarmStart(*ipopt);
      const EndControl applied = nlp->solutionControl(0);
      trajectory.controls.push_back(applied);
      trajectory.states.push_back(A * trajectory.states.back() + B * applied);
      guess = nlp->shiftedSolution();
    }
  }
  for (int k = 0; k <= problem.steps; ++k) trajectory.t.push_back(k * problem.sample_time);
  trajectory.cost = qrCost(problem, trajectory.states, trajectory.controls);
  trajectory.solve_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return trajectory;
}

}  // namespace cranesim
