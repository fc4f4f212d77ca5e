#include "cranesim/solvers/generalized_alpha.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "cranesim/math/sparse_lu.hpp"

namespace cranesim {

GeneralizedAlphaCoefficients GeneralizedAlphaCoefficients::fromSpectralRadius(double rho) {
  GeneralizedAlphaCoefficients k{};
  k.alpha_m = (3.0 * rho - 1.0) / (2.0 * (1.0 + rho));
  k.alpha_f = rho / (1.0 + rho);
  k.gamma = 0.5 + k.alpha_f - k.alpha_m;
  k.error_constant = (rho * rho - rho + 1.0) / (3.0 * (1.0 + rho) * (1.0 + rho));
  return k;
}

namespace {

constexpr int kMaxNewtonIterations = 4;   // as IDAS
constexpr double kMaxNewtonRate = 0.9;    // as IDAS
constexpr double kJacobianRatioLow = 0.6, kJacobianRatioHigh = 1.0 / 0.6;  // c / c_J window, as IDAS
constexpr int kMaxFailuresPerStep = 12;
// Step-size choice: h ← h·0.9·err^(−1/3), grown only by ≥ 1.2 and ≤ 1.6 (c stays within the
// Jacobian's window), shrunk by ≤ 2 after a success and 5 after a failed error test.
constexpr double kSafety = 0.9, kGrowThreshold = 1.2, kGrowMax = 1.6;
constexpr double kMinimumStepFraction = 1e-14;  // of max(1, |t|)

class GeneralizedAlphaStepper final : public TimeStepper {
 public:
  GeneralizedAlphaStepper(const Assembler& assembler, const DynamicState& s, double rho_inf)
      : assembler_(assembler), k_(GeneralizedAlphaCoefficients::fromSpectralRadius(rho_inf)),
        n_(assembler.size()), nd_(assembler.model().nq + assembler.model().nv),
        y_(n_), yp_(n_), w_(n_), w_step_(n_), y_old_(n_), yp_old_(n_), y1_(n_), yp1_(n_), w1_(n_),
        r_(n_), weights_(n_), state_atol_(assembler.model().absoluteTolerances()),
        jacobian_(std::max(assembler.pattern().nonZeros(), 1)) {
    const SolverSpec& solver = assembler.model().solver;
    max_step_ = solver.max_step;
    fixed_step_ = solver.fixed_step;
    h_ = fixed_step_ > 0.0 ? fixed_step_ : solver.initial_step;
    restart(s);
  }

  StepOutcome step(double t_stop) override {
    StepOutcome out;
    const double remaining = t_stop - t_;
    if (h_ <= 0.0) h_ = initialStep(remaining);
    if (max_step_ > 0.0) h_ = std::min(h_, max_step_);
    setWeights();
    for (int failures = 0;; ++failures) {
      if (failures >= kMaxFailuresPerStep) {
        out.failure = fmt::format("the generalized-α step failed {} times at t = {:.6g} s (h = {:.3g} s): {}",
                                  failures, t_, h_, last_failure_);
        return out;
      }
      if (h_ < kMinimumStepFraction * std::max(1.0, std::abs(t_))) {
        out.failure = fmt::format("the generalized-α step size fell to {:.3g} s at t = {:.6g} s: {}", h_, t_,
                                  last_failure_);
        return out;
      }
      // Up to 10 % longer to land on the stop time rather than leave a sliver.
      const bool to_stop = t_ + 1.1 * h_ >= t_stop;
      const double h = to_stop ? t_stop - t_ : h_;
      if (!solveStep(h) || (assembler_.model().m > 0 && !useRatesOfMotion(t_ + h))) {
        ++stats_.nonlinear_failures;
        h_ = 0.25 * h;
        continue;
      }
      const double err = fixed_step_ > 0.0 ? 0.0 : errorNorm(h);
      if (!(err <= 1.0)) {
        ++stats_.error_test_failures;
        last_failure_ = fmt::format("local error {:.3g} × the tolerance", err);
        h_ = h * std::clamp(kSafety * std::pow(err, -1.0 / 3.0), 0.2, 0.9);
        continue;
      }
      accept(h);
      out.reached_stop = to_stop;
      // Grow only by a worthwhile factor and within the Jacobian's c window; a step shortened
      // to land on the stop time does not shorten the next.
      const double grow = err > 0.0 ? kSafety * std::pow(err, -1.0 / 3.0) : 2.0;
      const double next = grow >= kGrowThreshold ? h * std::min(grow, kGrowMax) : grow < 1.0 ? h * std::max(grow, 0.5) : h;
      h_ = fixed_step_ > 0.0 ? fixed_step_ : to_stop ? std::max(next, h_) : next;
      return out;
    }
  }

  double time() const override { return t_; }
  double* state() override { return y_.data(); }

  /// Cubic Hermite interpolation of the differential components and the work integrals on the
  /// last step, linear for the multipliers.
  void interpolate(double t, double* y, double* work) override {
    const double h = t_ - t_old_;
    const double s = h > 0.0 ? std::clamp((t - t_old_) / h, 0.0, 1.0) : 1.0;
    const double h00 = (1.0 + 2.0 * s) * (1.0 - s) * (1.0 - s), h10 = s * (1.0 - s) * (1.0 - s);
    const double h01 = s * s * (3.0 - 2.0 * s), h11 = s * s * (s - 1.0);
    for (int i = 0; i < nd_; ++i)
      y[i] = h00 * y_old_[i] + h * h10 * yp_old_[i] + h01 * y_[i] + h * h11 * yp_[i];
    for (int i = nd_; i < n_; ++i) y[i] = (1.0 - s) * y_old_[i] + s * y_[i];
    for (int i = 0; i < WorkTerms::kCount; ++i)
      work[i] = h00 * work_old_[i] + h * h10 * power_old_[i] + h01 * work_[i] + h * h11 * power_[i];
  }

  void work(double* work) override { std::copy(work_.begin(), work_.end(), work); }

  void restart(const DynamicState& s) override {
    stateVectors(assembler_, s, y_.data(), yp_.data());
    w_ = yp_;
    t_ = t_old_ = s.t;
    y_old_ = y_, yp_old_ = yp_;
    assembler_.workPowers(t_, y_.data(), power_.data());
    work_old_ = work_, power_old_ = power_;
    has_history_ = false;
  }

  void forgetPivots() override {
    lu_.forgetPivots();
    factorised_ = false;
  }

  void setWork(const double* work) override {
    std::copy(work, work + WorkTerms::kCount, work_.begin());
    work_old_ = work_;
  }

  void setMaxStep(double h) override {
    const double scene_limit = assembler_.model().solver.max_step;
    max_step_ = h > 0.0 && scene_limit > 0.0 ? std::min(h, scene_limit) : h > 0.0 ? h : scene_limit;
  }

  SolverStatistics statistics() override {
    SolverStatistics s = stats_;
    s.last_step_size = t_ - t_old_;
    s.last_order = 2;
    return s;
  }

 private:
  /// Solves F(t + h, y₁, ẏ₁(y₁)) = 0 by modified Newton; false when it does not converge.
  bool solveStep(double h) {
    const double t1 = t_ + h;
    const double c = (1.0 - k_.alpha_m) / ((1.0 - k_.alpha_f) * k_.gamma * h);
    rescaleLag(h);
    predict(h);
    bool fresh = false;
    if (!factorised_ || c < kJacobianRatioLow * c_jacobian_ || c > kJacobianRatioHigh * c_jacobian_ || refresh_) {
      if (!newJacobian(t1, c)) return false;
      fresh = true;
    }
    for (;;) {
      if (newton(t1, c)) return true;
      if (fresh) return false;
      // Stale Jacobian: evaluate one here and try again from the predictor.
      predict(h);
      if (!newJacobian(t1, c)) return false;
      fresh = true;
    }
  }

  /// The trial y₁ (and its w₁, ẏ₁): a quadratic through the last two derivatives, else a
  /// tangent; the multipliers as they are.
  void predict(double h) {
    for (int i = 0; i < nd_; ++i) {
      const double curvature = has_history_ ? (yp_[i] - yp_old_[i]) / h_last_ : 0.0;
      y1_[i] = y_[i] + h * yp_[i] + 0.5 * h * h * curvature;
    }
    std::copy(y_.begin() + nd_, y_.end(), y1_.begin() + nd_);
    derivativesOf(h);
  }

  /// The rates the method carries to the next step are those of the motion: q̇ = H dq and the
  /// accelerations and multipliers of the saddle-point system (4-3) at (q₁, dq₁), and w₁ follows
  /// from them by the filter relation. The discrete λ₁, μ₁ have moved y₁ onto Φ = 0, Φ̇ = 0: a
  /// projection, not motion. Carried in ẏ and w, the projection echoes from step to step (an
  /// oscillation of period two in the velocities' derivatives on the pendulum, growing when
  /// the step size changed, until the step size collapsed).
  bool useRatesOfMotion(double t1) {
    const Model& model = assembler_.model();
    const int nq = model.nq, nv = model.nv;
    motion_.t = t1;
    motion_.q = Eigen::Map<const VecX>(y1_.data(), nq);
    motion_.v = Eigen::Map<const VecX>(y1_.data() + nq, nv);
    try {
      accelerations_.solve(assembler_, motion_, assembler_.constraints(t1, motion_.q.data(), motion_.v.data()), Limit::Left);
    } catch (const std::exception& e) {
      last_failure_ = e.what();
      return false;
    }
    std::copy(motion_.qdot.data(), motion_.qdot.data() + nq, yp1_.begin());
    std::copy(motion_.a.data(), motion_.a.data() + nv, yp1_.begin() + nq);
    std::copy(motion_.lambda.data(), motion_.lambda.data() + model.m, y1_.begin() + assembler_.lambdaOffset());
    std::fill(y1_.begin() + assembler_.muOffset(), y1_.end(), 0.0);
    for (int i = 0; i < nd_; ++i)
      w1_[i] = ((1.0 - k_.alpha_f) * yp1_[i] + k_.alpha_f * yp_[i] - k_.alpha_m * w_step_[i]) / (1.0 - k_.alpha_m);
    return true;
  }

  /// w lags ẏ by a multiple of the step: w_n ≈ ẏ(t_n + (α_m − α_f) h) + O(h²). A new step size
  /// rescales the lag, else each change of h costs a first-order error (measured: the local
  /// error estimate jumped tenfold when h grew by 1.6).
  void rescaleLag(double h) {
    const double ratio = has_history_ ? h / h_last_ : 1.0;
    for (int i = 0; i < nd_; ++i) w_step_[i] = yp_[i] + ratio * (w_[i] - yp_[i]);
  }

  /// w₁ and ẏ₁ of the differential components from y₁ (the method's two relations).
  void derivativesOf(double h) {
    for (int i = 0; i < nd_; ++i) {
      w1_[i] = (y1_[i] - y_[i] - h * (1.0 - k_.gamma) * w_step_[i]) / (h * k_.gamma);
      yp1_[i] = ((1.0 - k_.alpha_m) * w1_[i] + k_.alpha_m * w_step_[i] - k_.alpha_f * yp_[i]) / (1.0 - k_.alpha_f);
    }
    std::fill(yp1_.begin() + nd_, yp1_.end(), 0.0);
  }

  bool newJacobian(double t1, double c) {
    const SparsityPattern& p = assembler_.pattern();
    assembler_.jacobian(t1, c, y1_.data(), yp1_.data(), jacobian_.data());
    ++stats_.jacobian_evaluations, ++stats_.linear_setups;
    refresh_ = false;
    factorised_ = lu_.factorise(n_, p.columnPointers().data(), p.rowIndices().data(), jacobian_.data());
    c_jacobian_ = c;
    if (!factorised_) last_failure_ = "the Newton matrix is singular";
    return factorised_;
  }

  /// Newton's iterations with IDAS' convergence test on the estimated remaining error
  /// rate/(1 − rate)·|δ|, but always from a rate measured in this step: the error test sees the
  /// rates of motion, not the Newton error in y₁ (on the pendulum, accepting a first update by
  /// an older step's rate left 0.7 m of error at fixed steps of 1e-4 s).
  bool newton(double t1, double c) {
    const double scale = c == c_jacobian_ ? 1.0 : 2.0 / (1.0 + c / c_jacobian_);
    const double tolerance = assembler_.model().solver.newton_coefficient;
    double first_norm = 0.0;
    for (int m = 0; m < kMaxNewtonIterations; ++m) {
      assembler_.residual(t1, y1_.data(), yp1_.data(), r_.data());
      ++stats_.residual_evaluations, ++stats_.nonlinear_iterations;
      for (double& x : r_) x = -x;
      lu_.solve(r_.data());
      double sum = 0.0;
      for (int i = 0; i < n_; ++i) {
        const double d = scale * r_[i];
        y1_[i] += d;
        if (i < nd_) yp1_[i] += c * d;
        sum += (d * weights_[i]) * (d * weights_[i]);
      }
      const double norm = std::sqrt(sum / n_);
      if (!std::isfinite(norm)) break;
      if (m == 0) {
        first_norm = norm;
        if (norm <= 1e-4 * tolerance) return true;
        continue;
      }
      const double rate = std::pow(norm / first_norm, 1.0 / m);
      if (rate > kMaxNewtonRate) break;
      if (rate / (1.0 - rate) * norm <= tolerance) return true;
    }
    refresh_ = true;
    last_failure_ = "Newton's iterations did not converge";
    return false;
  }

  /// Weighted RMS norm of the local error estimate C h³ y''' over the differential components.
  double errorNorm(double h) const {
    double sum = 0.0;
    for (int i = 0; i < nd_; ++i) {
      double e;
      if (has_history_) {
        const double third = 2.0 * ((yp1_[i] - yp_[i]) / h - (yp_[i] - yp_old_[i]) / h_last_) / (h + h_last_);
        e = k_.error_constant * h * h * h * third;
      } else {
        e = std::max(std::abs(k_.alpha_m - k_.alpha_f), k_.error_constant) * h * (yp1_[i] - yp_[i]);
      }
      sum += (e * weights_[i]) * (e * weights_[i]);
    }
    return std::sqrt(sum / nd_);
  }

  void accept(double h) {
    y_old_.swap(y_), yp_old_.swap(yp_);
    y_ = y1_, yp_ = yp1_, w_ = w1_;
    h_last_ = h;
    t_old_ = t_;
    t_ += h;
    work_old_ = work_, power_old_ = power_;
    assembler_.workPowers(t_, y_.data(), power_.data());
    for (int i = 0; i < WorkTerms::kCount; ++i) work_[i] += 0.5 * h * (power_old_[i] + power_[i]);
    has_history_ = true;
    ++stats_.steps;
  }

  void setWeights() {
    const SolverSpec& solver = assembler_.model().solver;
    for (int i = 0; i < n_; ++i)
      weights_[i] = 1.0 / (solver.rtol * std::abs(y_[i]) + (i < nd_ ? state_atol_[i] : solver.atol_multipliers));
  }

  /// IDAS' choice: a step that changes y by half its tolerance, at most 1/1000 of the interval.
  double initialStep(double remaining) const {
    double sum = 0.0;
    for (int i = 0; i < nd_; ++i) sum += (yp_[i] * weights_[i]) * (yp_[i] * weights_[i]);
    const double rate = std::sqrt(sum / std::max(nd_, 1));
    const double h = 1e-3 * remaining;
    return rate * h > 0.5 ? 0.5 / rate : h;
  }

  const Assembler& assembler_;
  const GeneralizedAlphaCoefficients k_;
  const int n_, nd_;
  // h_: the next step tried; h_last_: the last one accepted, from t_old_ to t_.
  double t_ = 0.0, t_old_ = 0.0, h_ = 0.0, h_last_ = 0.0, max_step_ = 0.0, fixed_step_ = 0.0;
  // At t_: y, ẏ, w and w rescaled to the trial step; at the last step's start t_old_ (the
  // interpolation's, the predictor's and the error estimate's history): y, ẏ; the trial.
  std::vector<double> y_, yp_, w_, w_step_, y_old_, yp_old_, y1_, yp1_, w1_, r_, weights_;
  const VecX state_atol_;  // of q and dq (Model::absoluteTolerances)
  std::array<double, WorkTerms::kCount> work_{}, power_{}, work_old_{}, power_old_{};
  bool has_history_ = false;
  std::vector<double> jacobian_;
  SparseLU lu_;
  bool factorised_ = false, refresh_ = false;
  double c_jacobian_ = 0.0;
  SolverStatistics stats_;
  std::string last_failure_;
  DynamicState motion_;
  AccelerationSolver accelerations_;
};

}  // namespace

std::unique_ptr<TimeStepper> makeGeneralizedAlphaStepper(const Assembler& assembler, const DynamicState& initial,
                                                         double rho_inf) {
  return std::make_unique<GeneralizedAlphaStepper>(assembler, initial, rho_inf);
}

}  // namespace cranesim
