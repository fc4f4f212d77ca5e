#include "solver_reader.hpp"

#include <fmt/format.h>

namespace cranesim {

AbsoluteTolerance readAbsoluteTolerance(const YamlField& f) {
  if (!f.isMap()) return AbsoluteTolerance::uniform(f.positive());
  f.allowKeys({"position", "rotation", "velocity", "angular_velocity"});
  return {f.at("position").positive(), f.at("rotation").positive(), f.at("velocity").positive(),
          f.at("angular_velocity").positive()};
}

double readRelativeTolerance(const YamlField& f) {
  const double rtol = f.positive();
  if (rtol >= 0.1) f.fail(fmt::format("rtol {} is not a tolerance: use a value below 0.1", rtol));
  return rtol;
}

SolverSpec readSolver(const YamlField& f) {
  f.allowKeys({"formulation", "t_start", "t_end", "rtol", "atol", "atol_multipliers", "newton_coefficient", "work_error_control", "max_step", "max_step_growth", "max_order", "initial_step",
               "integrator", "rho_inf", "fixed_step",
               "baumgarte", "assembly_tolerance", "initial_state", "statics", "outside_envelope"});
  SolverSpec s;
  if (const auto form = f.find("formulation"))
    s.formulation = form->choice({"ggl", "baumgarte"}) == "ggl" ? Formulation::GGL : Formulation::Baumgarte;
  s.t_start = f.number("t_start", 0.0);
  s.t_end = f.at("t_end").number();
  if (!(s.t_end > s.t_start)) f.at("t_end").fail(fmt::format("t_end ({}) must be after t_start ({})", s.t_end, s.t_start));
  if (const auto r = f.find("rtol")) s.rtol = readRelativeTolerance(*r);
  if (const auto a = f.find("atol")) s.atol = readAbsoluteTolerance(*a);
  s.atol_multipliers = f.positive("atol_multipliers", s.atol_multipliers);
  s.newton_coefficient = f.positive("newton_coefficient", s.newton_coefficient);
  if (const auto w = f.find("work_error_control")) s.work_error_control = w->boolean();
  if (const auto e = f.find("outside_envelope")) s.stop_outside_envelope = e->choice({"warn", "stop"}) == "stop";
  if (s.newton_coefficient >= 1.0) f.at("newton_coefficient").fail("must lie in (0, 1)");
  if (const auto ms = f.find("max_step")) s.max_step = ms->positive();
  if (const auto h0 = f.find("initial_step")) s.initial_step = h0->positive();
  if (const auto method = f.find("integrator"))
    s.integrator = method->choice({"bdf", "generalized_alpha"}) == "bdf" ? Integrator::Bdf : Integrator::GeneralizedAlpha;
  if (const auto rho = f.find("rho_inf")) {
    if (s.integrator != Integrator::GeneralizedAlpha)
      rho->fail("rho_inf sets the generalized-α method's high-frequency damping: add integrator: generalized_alpha");
    s.rho_inf = rho->number();
    if (!(s.rho_inf >= 0.0 && s.rho_inf <= 1.0)) rho->fail(fmt::format("rho_inf must lie in [0, 1], found {}", s.rho_inf));
  }
  if (const auto fixed = f.find("fixed_step")) {
    if (s.integrator != Integrator::GeneralizedAlpha)
      fixed->fail("fixed_step is the generalized-α method's (BDF steps are always chosen by its error test): add integrator: generalized_alpha");
    s.fixed_step = fixed->positive();
  }
  if (const auto growth = f.find("max_step_growth")) {
    if (s.integrator != Integrator::Bdf)
      growth->fail("max_step_growth bounds IDAS' BDF step control: the generalized-α method has its own");
    s.max_step_growth = growth->number();
    if (!(s.max_step_growth > 1.0 && s.max_step_growth <= 10.0))
      growth->fail(fmt::format("max_step_growth must lie in (1, 10], found {}", s.max_step_growth));
  }
  if (const auto mo = f.find("max_order")) {
    s.max_order = mo->integer();
    if (s.max_order < 1 || s.max_order > 5) mo->fail(fmt::format("max_order must be 1…5, found {}", s.max_order));
  }
  if (const auto b = f.find("baumgarte")) {
    b->allowKeys({"alpha", "beta"});
    s.baumgarte_alpha = b->positive("alpha", s.baumgarte_alpha);
    s.baumgarte_beta = b->positive("beta", s.baumgarte_beta);
  }
  s.assembly_tolerance = f.positive("assembly_tolerance", s.assembly_tolerance);
  if (s.assembly_tolerance >= 0.1)
    f.at("assembly_tolerance").fail(fmt::format("{} is not a drawing's rounding: use a value below 0.1", s.assembly_tolerance));
  if (const auto start = f.find("initial_state")) s.start_from_equilibrium = start->choice({"given", "equilibrium"}) == "equilibrium";
  if (const auto st = f.find("statics")) {
    st->allowKeys({"method", "damping", "duration"});
    if (const auto m = st->find("method"))
      s.static_method = m->choice({"newton", "relaxation"}) == "newton" ? StaticMethod::Newton : StaticMethod::Relaxation;
    s.relaxation_damping = st->positive("damping", s.relaxation_damping);
    s.relaxation_duration = st->positive("duration", s.relaxation_duration);
  }
  return s;
}

}  // namespace cranesim
