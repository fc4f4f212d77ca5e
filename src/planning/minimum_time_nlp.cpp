#include "cranesim/planning/minimum_time_nlp.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"  // Ipopt 3.11 headers
#include <IpIpoptApplication.hpp>
#include <IpSolveStatistics.hpp>
#pragma GCC diagnostic pop

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "cranesim/planning/ipopt_application.hpp"
#include "final_time_tnlp.hpp"
#include "cranesim/planning/qr_trajectory.hpp"

namespace cranesim {
namespace {

// A node's variables in z: position, speed, angle, angular velocity, acceleration.
enum NodeVariable { kX, kV, kTheta, kOmega, kU, kNodeSize };
constexpr int kStateSize = 4;               // the defects per interval: x, v, θ, θ'
constexpr int kDefectJacobianRowSize = 2 * kNodeSize + 1;
constexpr int kHessianEntriesPerNode = 6;   // (θ,θ), (a,θ) and t_f with v, θ, θ', a

/// Ipopt treats |bound| ≥ 1e19 as absent.
double ipoptBound(double bound) { return std::clamp(bound, -1e20, 1e20); }

/// Trapezoidal collocation of the suspended pendulum, z = (node 0 … node N, t_f); the defect
/// of interval k is s_{k+1} − s_k − h/2 (f_k + f_{k+1}) with h = t_f / N.
class MinimumTimeNlp final : public FinalTimeTnlp {
 public:
  MinimumTimeNlp(const MinimumTimeProblem& problem, std::vector<double> initial_guess)
      : FinalTimeTnlp(std::move(initial_guess)), p_(problem), N_(problem.intervals) {}

  bool get_nlp_info(Ipopt::Index& n, Ipopt::Index& m, Ipopt::Index& nnz_jac_g, Ipopt::Index& nnz_h_lag,
                    IndexStyleEnum& index_style) override {
    n = finalTimeIndex() + 1;
    m = kStateSize * N_ + (hasJerkLimit() ? 2 * N_ : 0);
    nnz_jac_g = kStateSize * N_ * kDefectJacobianRowSize + (hasJerkLimit() ? 2 * N_ * 3 : 0);
    nnz_h_lag = (N_ + 1) * kHessianEntriesPerNode;
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Ipopt::Index n, Ipopt::Number* x_l, Ipopt::Number* x_u, Ipopt::Index m, Ipopt::Number* g_l,
                       Ipopt::Number* g_u) override {
    const double inf = std::numeric_limits<double>::infinity();
    for (int k = 0; k <= N_; ++k) {
      double* lower = x_l + kNodeSize * k;
      double* upper = x_u + kNodeSize * k;
      lower[kX] = -1e20, upper[kX] = 1e20;
      lower[kV] = ipoptBound(-p_.speed_limit), upper[kV] = ipoptBound(p_.speed_limit);
      lower[kTheta] = -std::numbers::pi / 2, upper[kTheta] = std::numbers::pi / 2;
      lower[kOmega] = -1e20, upper[kOmega] = 1e20;
      lower[kU] = ipoptBound(-p_.acceleration_limit), upper[kU] = ipoptBound(p_.acceleration_limit);
      if (k == 0 || k == N_) {
        lower[kX] = upper[kX] = k == 0 ? 0.0 : p_.distance;
        for (int i : {kV, kTheta, kOmega}) lower[i] = upper[i] = 0.0;
        if (hasJerkLimit()) lower[kU] = upper[kU] = 0.0;
      }
    }
    x_l[n - 1] = 1e-6, x_u[n - 1] = 1e20;
    std::fill(g_l, g_l + kStateSize * N_, 0.0);
    std::fill(g_u, g_u + kStateSize * N_, 0.0);
    for (int r = kStateSize * N_; r < m; r += 2) {
      g_l[r] = ipoptBound(-inf), g_u[r] = 0.0;      // a_{k+1} − a_k − j_max h ≤ 0
      g_l[r + 1] = 0.0, g_u[r + 1] = ipoptBound(inf);  // a_{k+1} − a_k + j_max h ≥ 0
    }
    return true;
  }

  bool eval_g(Ipopt::Index, const Ipopt::Number* z, bool, Ipopt::Index, Ipopt::Number* g) override {
    const double h = z[finalTimeIndex()] / N_;
    for (int k = 0; k < N_; ++k) {
      const double* a = z + kNodeSize * k;
      const double* b = a + kNodeSize;
      for (int c = 0; c < kStateSize; ++c) g[kStateSize * k + c] = b[c] - a[c] - 0.5 * h * (rate(a, c) + rate(b, c));
    }
    if (hasJerkLimit()) {
      for (int k = 0; k < N_; ++k) {
        const double change = z[kNodeSize * (k + 1) + kU] - z[kNodeSize * k + kU];
        g[kStateSize * N_ + 2 * k] = change - p_.jerk_limit * h;
        g[kStateSize * N_ + 2 * k + 1] = change + p_.jerk_limit * h;
      }
    }
    return true;
  }

  bool eval_jac_g(Ipopt::Index, const Ipopt::Number* z, bool, Ipopt::Index, Ipopt::Index, Ipopt::Index* rows,
                  Ipopt::Index* cols, Ipopt::Number* values) override {
    int e = 0;
    if (values == nullptr) {
      for (int k = 0; k < N_; ++k)
        for (int c = 0; c < kStateSize; ++c) {
          for (int i = 0; i < 2 * kNodeSize; ++i) rows[e] = kStateSize * k + c, cols[e++] = kNodeSize * k + i;
          rows[e] = kStateSize * k + c, cols[e++] = finalTimeIndex();
        }
      if (hasJerkLimit())
        for (int r = 0; r < 2 * N_; ++r) {
          const int k = r / 2;
          for (int col : {kNodeSize * k + kU, kNodeSize * (k + 1) + kU, finalTimeIndex()})
            rows[e] = kStateSize * N_ + r, cols[e++] = col;
        }
      return true;
    }
    const double tf = z[finalTimeIndex()];
    const double h = tf / N_;
    for (int k = 0; k < N_; ++k) {
      const double* a = z + kNodeSize * k;
      const double* b = a + kNodeSize;
      for (int c = 0; c < kStateSize; ++c) {
        double rate_a[kNodeSize], rate_b[kNodeSize];
        rateGradient(a, c, rate_a);
        rateGradient(b, c, rate_b);
        for (int i = 0; i < kNodeSize; ++i) values[e++] = (i == c ? -1.0 : 0.0) - 0.5 * h * rate_a[i];
        for (int i = 0; i < kNodeSize; ++i) values[e++] = (i == c ? 1.0 : 0.0) - 0.5 * h * rate_b[i];
        values[e++] = -0.5 / N_ * (rate(a, c) + rate(b, c));
      }
    }
    if (hasJerkLimit())
      for (int r = 0; r < 2 * N_; ++r) {
        values[e++] = -1.0;
        values[e++] = 1.0;
        values[e++] = (r % 2 == 0 ? -1.0 : 1.0) * p_.jerk_limit / N_;
      }
    return true;
  }

  /// The objective and the jerk constraints are linear; the defects' second derivatives come
  /// from h/2 f at each node, where node j collects the multipliers of intervals j − 1 and j.
  bool eval_h(Ipopt::Index, const Ipopt::Number* z, bool, Ipopt::Number, Ipopt::Index, const Ipopt::Number* lambda,
              bool, Ipopt::Index, Ipopt::Index* rows, Ipopt::Index* cols, Ipopt::Number* values) override {
    const int tf_index = finalTimeIndex();
    int e = 0;
    if (values == nullptr) {
      for (int j = 0; j <= N_; ++j) {
        const int base = kNodeSize * j;
        rows[e] = base + kTheta, cols[e++] = base + kTheta;
        rows[e] = base + kU, cols[e++] = base + kTheta;
        for (int i : {kV, kTheta, kOmega, kU}) rows[e] = tf_index, cols[e++] = base + i;
      }
      return true;
    }
    const double tf = z[tf_index];
    const double L = p_.rope_length, g = p_.gravity;
    for (int j = 0; j <= N_; ++j) {
      double mu[kStateSize] = {0.0, 0.0, 0.0, 0.0};
      for (int k : {j - 1, j})
        if (k >= 0 && k < N_)
          for (int c = 0; c < kStateSize; ++c) mu[c] += lambda[kStateSize * k + c];
      const double* node = z + kNodeSize * j;
      const double s = std::sin(node[kTheta]), co = std::cos(node[kTheta]), u = node[kU];
      const double scale = -0.5 * tf / N_;
      values[e++] = scale * mu[3] * (g * s + u * co) / L;
      values[e++] = scale * mu[3] * s / L;
      values[e++] = -0.5 / N_ * mu[0];
      values[e++] = -0.5 / N_ * mu[3] * (-(g * co - u * s) / L);
      values[e++] = -0.5 / N_ * mu[2];
      values[e++] = -0.5 / N_ * (mu[1] - mu[3] * co / L);
    }
    return true;
  }

 private:
  bool hasJerkLimit() const { return std::isfinite(p_.jerk_limit); }
  int finalTimeIndex() const { return kNodeSize * (N_ + 1); }

  /// Component c of the state's rate f = (v, a, θ', −(g sin θ + a cos θ)/L) at a node.
  double rate(const double* node, int c) const {
    switch (c) {
      case kX: return node[kV];
      case kV: return node[kU];
      case kTheta: return node[kOmega];
      default: return -(p_.gravity * std::sin(node[kTheta]) + node[kU] * std::cos(node[kTheta])) / p_.rope_length;
    }
  }

  /// ∂f_c/∂(node variables).
  void rateGradient(const double* node, int c, double* gradient) const {
    std::fill(gradient, gradient + kNodeSize, 0.0);
    const double s = std::sin(node[kTheta]), co = std::cos(node[kTheta]);
    switch (c) {
      case kX: gradient[kV] = 1.0; break;
      case kV: gradient[kU] = 1.0; break;
      case kTheta: gradient[kOmega] = 1.0; break;
      default:
        gradient[kTheta] = -(p_.gravity * co - node[kU] * s) / p_.rope_length;
        gradient[kU] = -co / p_.rope_length;
    }
  }

  const MinimumTimeProblem& p_;
  const int N_;
};

void requirePositive(const char* name, double value) {
  if (!(value > 0.0)) throw std::invalid_argument(std::string(name) + " must be > 0 (got " + std::to_string(value) + ")");
}

/// A smooth rest-to-rest move x = D (3τ² − 2τ³) with the pendulum hanging straight, over a time
/// long enough that it roughly respects the limits.
std::vector<double> initialGuess(const MinimumTimeProblem& p) {
  const double rigid = minimumTransferTime(p.distance, p.speed_limit, p.acceleration_limit);
  const double tf = 1.5 * rigid + 2.0 * std::numbers::pi * std::sqrt(p.rope_length / p.gravity);
  const int N = p.intervals;
  std::vector<double> z(kNodeSize * (N + 1) + 1, 0.0);
  for (int k = 0; k <= N; ++k) {
    const double tau = static_cast<double>(k) / N;
    double* node = z.data() + kNodeSize * k;
    node[kX] = p.distance * tau * tau * (3.0 - 2.0 * tau);
    node[kV] = p.distance * 6.0 * tau * (1.0 - tau) / tf;
    node[kU] = p.distance * (6.0 - 12.0 * tau) / (tf * tf);
  }
  z.back() = tf;
  return z;
}

}  // namespace

MinimumTimeTrajectory solveMinimumTime(const MinimumTimeProblem& problem) {
  if (problem.intervals < 2) throw std::invalid_argument("intervals must be ≥ 2");
  requirePositive("rope_length", problem.rope_length);
  requirePositive("gravity", problem.gravity);
  requirePositive("speed_limit", problem.speed_limit);
  requirePositive("acceleration_limit", problem.acceleration_limit);
  requirePositive("jerk_limit", problem.jerk_limit);
  if (!std::isfinite(problem.acceleration_limit)) throw std::invalid_argument("acceleration_limit must be finite");

  const auto started = std::chrono::steady_clock::now();
  Ipopt::SmartPtr<Ipopt::IpoptApplication> ipopt =
      ipoptApplication({problem.print_level, problem.tolerance, problem.max_iterations});
  if (!problem.exact_hessian) ipopt->Options()->SetStringValue("hessian_approximation", "limited-memory");

  const Ipopt::SmartPtr<MinimumTimeNlp> nlp = new MinimumTimeNlp(problem, initialGuess(problem));
  const Ipopt::ApplicationReturnStatus status = ipopt->OptimizeTNLP(Ipopt::SmartPtr<Ipopt::TNLP>(GetRawPtr(nlp)));
  if (status != Ipopt::Solve_Succeeded && status != Ipopt::Solved_To_Acceptable_Level)
    throw std::runtime_error("Ipopt: minimum-time solve ended with " + ipoptStatusInWords(status));

  MinimumTimeTrajectory trajectory;
  const std::vector<double>& z = nlp->solution;
  trajectory.final_time = z.back();
  for (int k = 0; k <= problem.intervals; ++k) {
    const double* node = z.data() + kNodeSize * k;
    trajectory.t.push_back(trajectory.final_time * k / problem.intervals);
    trajectory.position.push_back(node[kX]);
    trajectory.velocity.push_back(node[kV]);
    trajectory.angle.push_back(node[kTheta]);
    trajectory.angular_velocity.push_back(node[kOmega]);
    trajectory.acceleration.push_back(node[kU]);
  }
  trajectory.iterations = ipopt->Statistics()->IterationCount();
  trajectory.solve_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return trajectory;
}

}  // namespace cranesim
