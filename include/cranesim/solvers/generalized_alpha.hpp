#pragma once
// The generalized-α method for the multibody DAE F(t, y, ẏ) = 0 (assembler.hpp), with
// step-size control: the standard of structural multibody codes, with ρ∞ as the knob for
// high-frequency dissipation.
//
// The first-order form of Jansen, Whiting & Hulbert (2000), written as Arnold & Brüls (2007)
// write the second-order one: every equation, constraints included, holds at t_{n+1}, and an
// auxiliary variable w carries the method's filter on the derivative of the differential
// components (q, dq):
//     y_{n+1} = y_n + h [(1 − γ) w_n + γ w_{n+1}]
//     (1 − α_m) w_{n+1} + α_m w_n = (1 − α_f) ẏ_{n+1} + α_f ẏ_n
//     F(t_{n+1}, y_{n+1}, ẏ_{n+1}) = 0
// with α_m = (3ρ∞ − 1) / (2(1 + ρ∞)), α_f = ρ∞ / (1 + ρ∞), γ = ½ + α_f − α_m. For y' = λy it is
// second-order accurate and A-stable, and its amplification at hλ → −∞ is ρ∞: ρ∞ = 1 is the
// trapezoidal rule (no numerical damping), ρ∞ = 0 is BDF2 at constant steps.
//
// Each step solves F = 0 for y_{n+1} with ẏ_{n+1} = c y_{n+1} + const, c = (1 − α_m) /
// ((1 − α_f) γ h): the Newton matrix ∂F/∂y + c ∂F/∂ẏ is the one IDAS uses, so the step reuses
// the assembler's Jacobian and KLU, and keeps a factorisation over steps as IDAS does (new
// Jacobian when c drifts beyond [0.6, 1.67] of its value or Newton fails). The local error is
// C h³ y''' with C = (ρ∞² − ρ∞ + 1) / (3 (1 + ρ∞)²) (the principal root's error for y' = λy);
// y''' is estimated by the second divided difference of ẏ over the last two steps. Steps are
// accepted when that error's weighted RMS norm (rtol |y| + atol, differential components) is
// ≤ 1, like IDAS' error test. After a (re)start w = ẏ, a first-order start (exact for ρ∞ = 1),
// and the first step's error is estimated from the change of ẏ.

#include <memory>

#include "cranesim/solvers/time_stepper.hpp"

namespace cranesim {

struct GeneralizedAlphaCoefficients {
  double alpha_m, alpha_f, gamma;
  double error_constant;  // C of the local error C h³ y'''
  static GeneralizedAlphaCoefficients fromSpectralRadius(double rho_inf);
};

std::unique_ptr<TimeStepper> makeGeneralizedAlphaStepper(const Assembler& assembler, const DynamicState& initial,
                                                         double rho_inf);

}  // namespace cranesim
