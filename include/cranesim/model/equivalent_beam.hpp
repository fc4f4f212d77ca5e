#pragma once
// The Timoshenko beam equivalent to a lattice section (`fidelity: beam`): a uniform section whose
// stiffnesses reproduce the full-member model's between the two end sections, and whose mass is
// the truss' mass.
//
// The stiffnesses come from K_red, the full-member stiffness condensed onto the end sections
// (condensed_truss.hpp), so every lacing form is covered without a closed-form shear-web formula.
// With end section 1 clamped, C = K_red,22⁻¹ is the flexibility of end section 2 (truss axes,
// [u, θ]); a uniform Timoshenko beam of length L has
//     C_uxux = L/EA,   C_θxθx = L/GJ,   C_θθ = L/EI                 (a constant moment),
//     C_ww − C_wθ²/C_θθ = L³/(12 EI) + L/(κGA)                     (clamped–guided)
// in each bending plane (deflection w = u_z with rotation θ_y, w = u_y with θ_z). All four are
// the same seen from either end, so a transition piece (two chords at one end, four at the other)
// gets the same beam whichever end is clamped. A uniform beam cannot follow a taper: where the
// clamped–guided deflection is stiffer than the shear-rigid beam of that EI (the two-chord end
// of a transition piece carries a constant moment only by its tubes' own bending, so its EI is
// small), the beam is too soft in that loading by `guided_mismatch`. The element has one shear
// factor for both planes: κGA is the mean of the shear compliances of the planes that have one
// (`shear_plane_mismatch`: how far those two differ).
//
// Mass: the truss' total mass spread uniformly (density ρ_eq = m/(A_eq L)); the section's rotary
// inertia is then ρ_eq I_eq per length, the stiffness' radius of gyration, which for a lattice
// whose chords carry most of both is close to the material's.

#include "cranesim/elements/section.hpp"
#include "cranesim/model/truss_geometry.hpp"

namespace cranesim {

struct EquivalentBeam {
  Section section;    // A_eq = EA/E, I_eq = EI/E, J_eq = GJ/G, κ = κGA/(G A_eq)
  Material material;  // E, G of the truss' material; density ρ_eq
  double mass = 0.0;  // kg, the truss' mass (every tube, cross-section beams included)
  /// Clamped–guided deflection of the beam over the section's, − 1, largest of the two planes:
  /// 0 where the beam's shear compliance can match it.
  double guided_mismatch = 0.0;
  /// |1/κGA_y − 1/κGA_z| / (1/κGA_y + 1/κGA_z) when both planes have a shear compliance, else 0.
  double shear_plane_mismatch = 0.0;
};

/// The equivalent beam of the truss `g` (see the file comment). Throws std::invalid_argument
/// if the condensed stiffness does not describe a beam (a non-positive stiffness).
EquivalentBeam equivalentBeam(const TrussGeometry& g);

}  // namespace cranesim
