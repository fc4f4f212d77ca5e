#pragma once
// Cross-section and material of a flexible member. Section axes: x along the member, y and z
// the principal axes of the section.

#include <numbers>
#include <optional>

namespace cranesim {

struct Material {
  double density = 7850.0;         // ρ, kg/m³
  double youngs_modulus = 2.1e11;  // E, Pa
  double shear_modulus = 8.1e10;   // G, Pa
};

/// What a beam's equations need of its section, per unit length: the stiffnesses EA, GJ, EI_y,
/// EI_z and the shear stiffnesses κGA across y and z (0: no shear deformation, Euler–Bernoulli),
/// the mass ρA and the rotary inertias ρI_y, ρI_z about the section's axes and ρI_p about the
/// member axis (ρ(I_y + I_z) for a homogeneous section).
struct SectionProperties {
  double EA = 0.0, GJ = 0.0, EIy = 0.0, EIz = 0.0;  // N, N·m²
  double GAy = 0.0, GAz = 0.0;                       // N
  double rhoA = 0.0;                                 // kg/m
  double rhoIy = 0.0, rhoIz = 0.0, rhoIp = 0.0;      // kg·m
};

struct Section {
  double area = 0.0;           // A, m²
  double Iy = 0.0, Iz = 0.0;   // second moments about y and z, m⁴
  double J = 0.0;              // torsion constant, m⁴ (polar moment for round sections)
  double shear_factor = 0.0;   // Timoshenko shear coefficient κ (A_s = κ A); 0: no shear deformation
  double outer_radius = 0.0, inner_radius = 0.0;  // round sections only; 0 otherwise
  /// The properties themselves, for a section given by them (a composite boom, a beam with
  /// attachments, a benchmark stated in EA, EI, ρA …) instead of by a shape and a material.
  std::optional<SectionProperties> given;

  /// The given properties, or those of the shape in `material`.
  SectionProperties properties(const Material& material) const {
    if (given) return *given;
    const double E = material.youngs_modulus, G = material.shear_modulus, rho = material.density;
    SectionProperties p;
    p.EA = E * area;
    p.GJ = G * J;
    p.EIy = E * Iy;
    p.EIz = E * Iz;
    p.GAy = p.GAz = shear_factor * G * area;
    p.rhoA = rho * area;
    p.rhoIy = rho * Iy;
    p.rhoIz = rho * Iz;
    p.rhoIp = rho * (Iy + Iz);
    return p;
  }

  /// A solid or hollow circular section (tube when inner > 0). κ after Cowper (1966):
  /// solid 6(1+ν)/(7+6ν); thin tube 2(1+ν)/(4+3ν); Cowper's general formula in between.
  static Section circular(double outer, double inner, double poisson) {
    Section s;
    const double ro2 = outer * outer, ri2 = inner * inner;
    s.area = std::numbers::pi * (ro2 - ri2);
    s.Iy = s.Iz = std::numbers::pi / 4.0 * (ro2 * ro2 - ri2 * ri2);
    s.J = 2.0 * s.Iy;
    const double m = inner / outer, m2 = m * m, nu = poisson;
    s.shear_factor = 6.0 * (1.0 + nu) * (1.0 + m2) * (1.0 + m2) /
                     ((7.0 + 6.0 * nu) * (1.0 + m2) * (1.0 + m2) + (20.0 + 12.0 * nu) * m2);
    s.outer_radius = outer;
    s.inner_radius = inner;
    return s;
  }
};

}  // namespace cranesim
