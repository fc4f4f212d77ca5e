#include "cranesim/solvers/equilibrium_path.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "cranesim/math/rotation.hpp"
#include "cranesim/model/carriage_tipping.hpp"
#include "cranesim/model/compile.hpp"
#include "cranesim/model/slack_ropes.hpp"
#include "cranesim/solvers/drive_posing.hpp"
#include "cranesim/solvers/equilibrium_system.hpp"
#include "cranesim/solvers/initial_conditions.hpp"

namespace cranesim {
namespace {

/// The value a constraint's drive stands at in the state q (its joints' measured angle,
/// displacement or distance).
double driveValueAt(const Model& model, const Constraint& c, const VecX& q) {
  return drivenCoordinate(c.law(), model.jointFrame(q.data(), c.joint1), model.jointFrame(q.data(), c.joint2));
}

bool differs(double a, double b) { return std::abs(a - b) > 1e-12 * std::max({1.0, std::abs(a), std::abs(b)}); }

/// The scene with every control following its path in τ (the model's time): c(τ) = c_drawn +
/// τ (c(t) − c_drawn), an applied load's scale from 0 (the drawing carries none) to its value
/// at t. Everything else is frozen at t.
Scene pathScene(const Scene& scene, const Model& model, const VecX& q_drawn, double t) {
  Scene path = scene;
  path.solver.t_start = 0.0;
  const auto line = [](double from, double to) { return Profile(RampProfile{from, to - from, 0.0}); };
  for (MemberSpec& m : path.members)
    if (m.length) m.length = line(drawnRopeLength(m), (*m.length)(t));
  for (ConstraintSpec& c : path.constraints) {
    if (!c.drive) continue;
    const auto it = std::find_if(model.constraints.begin(), model.constraints.end(),
                                 [&](const Constraint& k) { return k.name == c.name; });
    c.drive = line(driveValueAt(model, *it, q_drawn), (*c.drive)(t));
  }
  for (LoadSpec& l : path.loads) l.scale = line(0.0, l.scale(t));
  return path;
}

std::string describe(const PathControl& c, double tau) {
  const double scale = c.angle ? 180.0 / std::numbers::pi : 1.0;
  const char* unit = c.angle ? "°" : " m";
  return fmt::format("{} {:.6g}{} → {:.6g}{} (reached {:.6g}{})", c.name, scale * c.drawn, unit, scale * c.target, unit,
                     scale * (c.drawn + tau * (c.target - c.drawn)), unit);
}

/// dx/dτ = −J⁻¹ ∂R/∂τ at a solution x(τ), with J factorised in `lu` (Newton's last, from the
/// iterate before x: the step only predicts); ∂R/∂τ by a forward difference (R is smooth in
/// the controls).
VecX pathTangent(EquilibriumSystem& system, const Eigen::SparseLU<Eigen::SparseMatrix<double>>& lu, const VecX& x,
                 double tau) {
  const VecX r = system.residual(x);
  const double h = 1e-7;
  system.setTime(tau + h);
  const VecX dr = (system.residual(x) - r) / h;
  system.setTime(tau);
  return -lu.solve(dr);
}

/// The predictor x + h dx/dτ with every rotation turned about its body axis,
/// R(φ) exp(h T(φ) dφ/dτ) (2-5), rather than its rotation vector moved along dφ/dτ: the two
/// agree to first order, but a sum of rotation vectors far from the identity turns about a skewed
/// axis, so a crane slewed by 155° was predicted worse than the same crane at 0° (54 against 47
/// iterations). The rotation vector kept is the representative nearest the old one.
VecX predict(const Model& model, const VecX& x, const VecX& tangent, double h) {
  VecX next = x + h * tangent;
  for (const Node& n : model.nodes) {
    if (!n.hasRotation()) continue;
    const Vec3 phi = x.segment<3>(n.q + 3);
    const Vec3 turn = h * (angularVelocityMap<double>(phi) * tangent.segment<3>(n.q + 3));
    Vec3 turned = rotationVector(rotationMatrix<double>(phi) * rotationMatrix<double>(turn));
    const double angle = turned.norm();
    if (angle > 0.0) {
      const Vec3 other = turned * (1.0 - 2.0 * std::numbers::pi / angle);  // the same rotation, angle 2π − θ
      if ((other - phi).squaredNorm() < (turned - phi).squaredNorm()) turned = other;
    }
    next.segment<3>(n.q + 3) = turned;
  }
  return next;
}

/// What the last iterate of a failed statics shows: a carriage tipped, ropes slack at an end
/// (a part that a slack rope alone held has nothing holding it); empty when neither.
std::string lastIterateFindings(const Scene& scene, const Model& model, const VecX& q, double t) {
  std::string findings;
  if (const std::string tipped = carriageTipped(model, q, t); !tipped.empty()) findings += "; its last iterate: " + tipped;
  if (const std::string slack = slackRopeEnds(scene, model, q, t); !slack.empty())
    findings += fmt::format("; ropes slack in its last iterate: {} (a rope only pulls: what it alone holds there falls)", slack);
  return findings;
}

}  // namespace

// At the chord itself every Gauss point sits on the kink of the tension-only law, where the
// rope has no stiffness, and Newton's first step lets the boom fall.
double drawnRopeLength(const MemberSpec& rope) {
  return (1.0 - 1e-3) * (rope.reeving ? rope.reeving->drawn_length : (rope.end - rope.start).norm());
}

std::vector<PathControl> pathControls(const Scene& scene, const Model& model, const VecX& q_drawn, double t) {
  std::vector<PathControl> controls;
  for (const MemberSpec& m : scene.members)
    if (m.length && differs(drawnRopeLength(m), (*m.length)(t)))
      controls.push_back({fmt::format("{} length", m.name), drawnRopeLength(m), (*m.length)(t), false});
  for (const Constraint& c : model.constraints) {
    if (!c.drive) continue;
    const double drawn = driveValueAt(model, c, q_drawn);
    const double target = (*c.drive)(t);
    if (differs(drawn, target)) controls.push_back({fmt::format("{} drive", c.name), drawn, target, c.type == ConstraintType::Revolute});
  }
  for (const LoadSpec& l : scene.loads)
    if (l.scale(t) != 0.0) controls.push_back({fmt::format("{} load scale", l.name), 0.0, l.scale(t), false});
  return controls;
}

StaticResult solveEquilibrium(const Scene& scene, const Model& model, double t, const PathOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const auto finish = [&](StaticResult& result) -> StaticResult& {
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
  };
  // The drives' drawn values are measured on the posed drawing; the path model's own drawing
  // (its ropes' slopes at their drawn lengths) is posed alike.
  VecX q_posed = model.q0;
  poseAtDrives(model, t, q_posed);
  const std::vector<PathControl> controls = pathControls(scene, model, q_posed, t);
  const Scene path_scene = pathScene(scene, model, q_posed, t);
  const Model path = compileModel(path_scene);
  VecX q_drawn = path.q0;
  poseAtDrives(path, 0.0, q_drawn);
  const DynamicState drawn =
      consistentInitialState(Assembler(path), 0.0, q_drawn, VecX::Zero(path.nv), model.solver.assembly_tolerance);

  // The start: Newton at the drawn controls under the full load, load stepping if that fails.
  EquilibriumSystem system(path, 0.0);
  StaticOptions start_newton = options.newton;
  if (!controls.empty()) start_newton.tolerance = std::max(start_newton.tolerance, options.intermediate_tolerance);
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  VecX x(system.size());
  x << drawn.q, drawn.lambda;  // the multipliers of the drawing released from rest: better than none
  std::string why;
  int used = dampedNewton(system, x, start_newton, why, &lu);
  StaticResult result;
  result.t = t;
  if (used >= 0) {
    result.iterations = used;
    result.load_steps = 1;
  } else {
    const VecX stalled = x.head(path.nq);  // Newton's last iterate under the full load
    result = solveStatics(path, drawn.q, 0.0, start_newton);
    result.iterations += -used - 1;
    result.t = t;
    if (!result.converged) {
      result.message = "at the drawn controls: " + result.message + lastIterateFindings(path_scene, path, stalled, 0.0);
      return finish(result);
    }
    x << result.q, result.lambda;
    used = 0;  // no factorisation at hand
  }

  StaticOptions step_newton = options.newton;
  step_newton.max_iterations = options.step_iterations;
  double tau = 0.0, step = 1.0;
  while (tau < 1.0 && !controls.empty()) {
    system.setTime(tau);
    if (used == 0) {  // no Jacobian of this point yet: one more, counted as an iteration
      ++result.iterations;
      if (!factoriseShifted(system.jacobian(x), path.nv, lu)) {
        result.q = x.head(model.nq);
        result.lambda = x.tail(model.m);
        result.path_reached = tau;
        result.message = fmt::format("static equilibrium not found: singular equilibrium Jacobian at {:.1f} % of the path "
                                     "from the drawn controls", 100.0 * tau);
        return finish(result);
      }
    }
    const VecX tangent = pathTangent(system, lu, x, tau);
    // A linear predictor errs like the square of the turn it predicts (a boom head 55 m out
    // turned by 40° lands 13 m off its arc): no node turns by more than max_angle_step. The
    // turn is the angular velocity's, ω = T(φ) dφ/dτ: the rotation vector's own rate grows
    // with its angle (by 2.6× at 155°, a crane slewed far from its drawing).
    double turn_rate = 0.0;
    for (const Node& n : path.nodes)
      if (n.hasRotation()) {
        const Vec3 phi = x.segment<3>(n.q + 3);
        turn_rate = std::max(turn_rate, (angularVelocityMap<double>(phi) * tangent.segment<3>(n.q + 3)).norm());
      }
    const double max_step = std::min(1.0, options.max_angle_step / std::max(turn_rate, 1e-300));
    step = std::min(step, max_step);
    for (;;) {
      const double next = std::min(1.0, tau + step);
      VecX trial = predict(path, x, tangent, next - tau);
      reparameteriseRotations(path, trial);
      system.setTime(next);
      step_newton.tolerance = next < 1.0 ? std::max(options.newton.tolerance, options.intermediate_tolerance)
                                         : options.newton.tolerance;
      const double predicted_residual = system.residual(trial).cwiseAbs().maxCoeff();
      used = dampedNewton(system, trial, step_newton, why, &lu);
      result.iterations += used >= 0 ? used : -used - 1;
      // The iteration budget rejects steps whose corrector does not converge; one that ran out
      // of it while converging (the residual down by six orders of magnitude, a light load's
      // path, whose knees converge slowly at first) gets a second budget instead of a halved step.
      if (used == -(step_newton.max_iterations + 1) &&
          system.residual(trial).cwiseAbs().maxCoeff() < 1e-6 * predicted_residual) {
        const int more = dampedNewton(system, trial, step_newton, why, &lu);
        result.iterations += more >= 0 ? more : -more - 1;
        used = more >= 0 ? step_newton.max_iterations + more : more;
      }
      if (used >= 0) {
        ++result.path_steps;
        x = trial;
        tau = next;
        if (used <= 3) step = std::min(max_step, 2.0 * step);
        break;
      }
      step *= 0.5;
      const bool tipped = !carriageTipped(path, trial.head(path.nq), next).empty();
      if (step < (tipped ? options.min_step_tipped : options.min_step)) {
        std::string moved;
        for (const PathControl& c : controls) moved += (moved.empty() ? "" : ", ") + describe(c, tau);
        result.converged = false;
        result.path_reached = tau;
        result.q = x.head(model.nq);
        result.lambda = x.tail(model.m);
        // A crane that tips on the way, or whose rope goes slack under what it held, has no
        // equilibrium beyond: its corrector's last iterate says so (a load past the tipping load
        // stalls Newton with the carriage on an edge).
        result.message = fmt::format("static equilibrium not found: the path from the drawn controls stopped at "
                                     "{:.1f} % ({}): {}{}", 100.0 * tau, moved, why,
                                     lastIterateFindings(path_scene, path, trial.head(path.nq), next));
        return finish(result);
      }
    }
  }

  // The path's equations at τ = 1 are the model's at t but for what compiling derives from the
  // controls' drawn values: the supports' bed settles under the model's weight, which the ropes'
  // lengths change (a luffing rope paid out from 6 to 34 m adds 1.6e4 N). Newton finishes on the
  // model itself.
  result.path_reached = 1.0;
  EquilibriumSystem own(model, t);
  VecX finished = x;
  const int finishing = dampedNewton(own, finished, options.newton, why);
  result.iterations += finishing >= 0 ? finishing : -finishing - 1;
  if (finishing >= 0) x = finished;
  acceptEquilibrium(own, x, result);
  return finish(result);
}

}  // namespace cranesim

