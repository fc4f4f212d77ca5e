#include "cranesim/solvers/statics.hpp"

#include <fmt/format.h>

#include <Eigen/SparseLU>

#include <algorithm>
#include <numbers>

#include "cranesim/solvers/equilibrium_system.hpp"

namespace cranesim {
namespace {

/// A Newton correction more than this many times longer than the previous one is wild
/// (dampedNewton): converging Newton corrections shrink.
constexpr double kMaxCorrectionGrowth = 2.0;

/// A solution Newton declares converged is accepted only when its largest force residual
/// max |F + Gᵀλ| is at most this fraction of the largest force present, max |F| (acceptEquilibrium).
constexpr double kResidualAcceptance = 1e-6;

/// The largest step fraction (≤ 1) that turns no node by more than π/2 and moves none by more
/// than a tenth of the scene's size (1 + max |q|): a rotation vector is meaningful within a
/// turn, and a mechanism far from its rest position (a body hanging on an unloaded joint, two
/// strut ties meeting in line at zero tension) would otherwise spin or fling its nodes by
/// thousands of turns or kilometres.
double stepLimit(const Model& model, const VecX& x, const VecX& dx) {
  const double reach = 0.1 * (1.0 + x.head(model.nq).cwiseAbs().maxCoeff());
  double limit = 1.0;
  for (const Node& n : model.nodes) {
    limit = std::min(limit, reach / std::max(dx.segment(n.q, n.hasPosition() ? 3 : 1).norm(), 1e-300));
    if (n.hasRotation()) limit = std::min(limit, 0.5 * std::numbers::pi / std::max(dx.segment<3>(n.q + 3).norm(), 1e-300));
  }
  return limit;
}

/// Whether the residual is as small as rounding lets it be: the forces to force_tolerance of
/// the largest constraint force (≥ 1 N), the constraints to 1e-14 of the coordinates. The
/// Newton step need not be small then: along a direction without stiffness (a light load free
/// to spin about its rope) it is rounding noise amplified, and no line search improves on it.
bool atRoundingFloor(const Model& model, const VecX& x, const VecX& r, const StaticOptions& options) {
  const double force_scale = std::max(1.0, model.m > 0 ? x.tail(model.m).cwiseAbs().maxCoeff() : 0.0);
  const double length_scale = 1.0 + x.head(model.nq).cwiseAbs().maxCoeff();
  return r.head(model.nv).cwiseAbs().maxCoeff() <= options.force_tolerance * force_scale &&
         (model.m == 0 || r.tail(model.m).cwiseAbs().maxCoeff() <= 1e-14 * length_scale);
}

}  // namespace

int dampedNewton(EquilibriumSystem& system, VecX& x, const StaticOptions& options, std::string& why,
                 Eigen::SparseLU<Eigen::SparseMatrix<double>>* factorisation) {
  const Model& model = system.model();
  Eigen::SparseLU<Eigen::SparseMatrix<double>> own;
  Eigen::SparseLU<Eigen::SparseMatrix<double>>& lu = factorisation ? *factorisation : own;
  VecX r = system.residual(x);
  int short_steps = 0;
  double previous_correction = 0.0;  // ‖Δq‖ of the last iteration's step (before the line search)
  for (int it = 1; it <= options.max_iterations; ++it) {
    if (atRoundingFloor(model, x, r, options)) return it - 1;
    // Directions without stiffness (a slack rope, a body free to turn about its joint) make
    // the Jacobian singular: the coordinate block's diagonal is shifted as in
    // Levenberg–Marquardt. The shift changes the step, not the equations being solved.
    const Eigen::SparseMatrix<double> J = system.jacobian(x);
    lu.compute(J);
    VecX dx;
    if (lu.info() == Eigen::Success) dx = -lu.solve(r);
    // A Jacobian that factorises but would turn a node by thousands of turns is singular to
    // rounding (a body hanging on its joint before the joint carries load). A shift barely
    // above rounding leaves the stiffness-free directions to rounding too: the shift grows
    // while the step exceeds the caps of stepLimit and the growth still tames it. A step that
    // stays beyond the caps whatever the shift is a real correction of the stiff directions
    // (a predicted crane whose boom head is metres off its arc); shifting further would only
    // damp it into many short Levenberg–Marquardt steps (shifts of 1e-4…1e-2 of the largest
    // stiffness cost the corrector of a luffing path 12 iterations and a linear rate of
    // convergence). The line search then scales it to the caps.
    // A Newton correction more than twice as long as the last one is wild too, whatever the caps:
    // near a family of equilibria (a body free to spin about its joint: its Jacobian is
    // singular along the spin at every equilibrium) the step along the family is the residual's
    // rounding, or its quadratic remainder, divided by the smallest singular value, and an
    // iterate within 1e-14 of equilibrium would be spun by a sizeable fraction of a turn, away
    // from it (a tilted offset bar took 11…655 iterations, or failed, as rounding decided;
    // 7…12 with this rule, test_statics_spin.cpp). The shift that tames it leaves the stiff
    // directions' correction as it was.
    const double magnitude = J.coeffs().cwiseAbs().maxCoeff();
    bool shifted_step = false;
    const auto limitOf = [&] { return lu.info() == Eigen::Success ? stepLimit(model, x, dx) : 0.0; };
    const auto growthOf = [&] {
      return lu.info() == Eigen::Success && previous_correction > 0.0 ? dx.head(model.nq).norm() / previous_correction : 0.0;
    };
    double limit = limitOf(), previous_limit = 0.0, growth = growthOf(), previous_growth = 0.0;
    const auto wild = [&] {
      if (lu.info() != Eigen::Success) return true;
      if (!shifted_step) return limit < 1e-3 || growth > kMaxCorrectionGrowth;
      return (limit < 1.0 && limit > 1.1 * previous_limit) ||
             (growth > kMaxCorrectionGrowth && growth < previous_growth / 1.1);
    };
    for (double shift = 1e-10 * magnitude; wild() && shift < magnitude; shift *= 100.0) {
      Eigen::SparseMatrix<double> shifted = J;
      for (int k = 0; k < model.nv; ++k) shifted.coeffRef(k, k) += shift;
      lu.compute(shifted);
      shifted_step = true;
      previous_limit = limit;
      previous_growth = growth;
      if (lu.info() == Eigen::Success) dx = -lu.solve(r);
      limit = limitOf();
      growth = growthOf();
    }
    if (lu.info() != Eigen::Success) {
      why = "singular equilibrium Jacobian (a mechanism without stiffness in some direction?)";
      return -it;
    }
    // Damped Newton: a step s is accepted when the residual decreases (Armijo) or, for an
    // unshifted Jacobian, when it passes the natural monotonicity test (Deuflhard): the
    // simplified Newton correction from the trial point, with the same factorisation, is
    // shorter than the step's own, ‖Δx̄(s)‖ ≤ (1 − s/4)‖Δx‖ (coordinates only: λ follows q).
    // The second test is blind to the scaling of the equations: the linearised step of a stiff
    // beam stretches it to second order, which multiplies the force residual by 10³ although
    // the step is excellent (the cantilever of 8.1.2: 8 iterations with it, 333 without). The
    // first one keeps the progress on a slack rope, whose Levenberg–Marquardt-shifted steps
    // are not Newton steps.
    // A Newton step below the tolerance ends the iteration whatever the line search would say:
    // near a root of a stiff, nearly linear system the residual sits at its rounding floor
    // (stiffness × the spacing of q's doubles) and a step below that spacing cannot lower it.
    const double scale = 1.0 + x.head(model.nq).cwiseAbs().maxCoeff();
    if (!shifted_step && dx.head(model.nq).cwiseAbs().maxCoeff() < options.tolerance * scale) {
      x += dx;
      reparameteriseRotations(model, x);
      return it;
    }
    const double merit = r.squaredNorm(), correction = dx.head(model.nq).norm();
    double step = stepLimit(model, x, dx);
    VecX trial;
    VecX r_trial;
    for (int k = 0; k < 30; ++k, step *= 0.5) {
      trial = x + step * dx;
      r_trial = system.residual(trial);
      if (!r_trial.allFinite()) continue;
      if (r_trial.squaredNorm() <= (1.0 - 1e-4 * step) * merit) break;
      if (shifted_step) continue;
      const VecX simplified = -lu.solve(r_trial);
      if (simplified.head(model.nq).norm() <= (1.0 - 0.25 * step) * correction) break;
    }
    x = trial;
    reparameteriseRotations(model, x);
    r = r_trial;
    previous_correction = correction;
    short_steps = step < options.stall_step ? short_steps + 1 : 0;
    if (short_steps >= options.stall_iterations) {
      why = fmt::format("Newton stalled after {} iterations (line search step {:.2g}, residual {:.3g})", it, step,
                        r.cwiseAbs().maxCoeff());
      return -(it + 1);
    }
    // Converged only on a full step: a short damped step proves nothing.
    if (step == 1.0 && dx.head(model.nq).cwiseAbs().maxCoeff() < options.tolerance * (1.0 + x.head(model.nq).cwiseAbs().maxCoeff()))
      return it;
  }
  why = fmt::format("no convergence in {} Newton iterations (residual {:.3g})", options.max_iterations,
                    r.cwiseAbs().maxCoeff());
  return -(options.max_iterations + 1);
}

void acceptEquilibrium(EquilibriumSystem& system, const VecX& x, StaticResult& result) {
  const Model& model = system.model();
  const VecX r = system.residual(x);
  VecX unloaded = x;  // λ = 0: the residual is the generalized forces F alone
  unloaded.tail(model.m).setZero();
  const double forces = std::max(1.0, system.residual(unloaded).head(model.nv).cwiseAbs().maxCoeff());
  result.q = x.head(model.nq);
  result.lambda = x.tail(model.m);
  result.force_residual = r.head(model.nv).cwiseAbs().maxCoeff();
  result.constraint_residual = model.m > 0 ? r.tail(model.m).cwiseAbs().maxCoeff() : 0.0;
  result.converged = result.force_residual <= kResidualAcceptance * forces;
  if (!result.converged)
    result.message = fmt::format("static equilibrium not found: after {} Newton iterations the force residual is {:.3g} N, {:.2g} "
                                 "of the largest force present ({:.3g} N; accepted up to {:g})",
                                 result.iterations, result.force_residual, result.force_residual / forces, forces,
                                 kResidualAcceptance);
}

StaticResult solveStatics(const Model& model, const VecX& q_start, double t, const StaticOptions& options) {
  StaticResult result;
  result.t = t;
  EquilibriumSystem system(model, t);
  VecX x = VecX::Zero(system.size());
  x.head(model.nq) = q_start;
  double reached = 0.0;
  double increment = 1.0 / options.initial_load_steps;
  int halvings = 0;
  while (reached < 1.0) {
    const double target = std::min(1.0, reached + increment);
    system.setLoadFactor(target);
    VecX trial = x;
    std::string why;
    const int used = dampedNewton(system, trial, options, why);
    if (used < 0) {
      result.iterations += -used - 1;
      if (++halvings > options.max_load_halvings) {
        result.message = fmt::format("static equilibrium not found at load factor {:.4g}: {}", target, why);
        result.q = x.head(model.nq);
        result.lambda = x.tail(model.m);
        return result;
      }
      increment *= 0.5;
      continue;
    }
    result.iterations += used;
    ++result.load_steps;
    x = trial;
    reached = target;
    if (used <= options.fast_iterations) increment *= 2.0;
  }
  system.setLoadFactor(1.0);
  acceptEquilibrium(system, x, result);
  return result;
}

}  // namespace cranesim
