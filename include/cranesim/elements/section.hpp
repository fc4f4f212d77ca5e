#pragma once
// Cross-section and material of a flexible member. Section axes: x along the member, y and z
// the principal axes of the section.

#include <numbers>

namespace cranesim {

struct Material {
  double density = 7850.0;         // ρ, kg/m³
  double youngs_modulus = 2.1e11;  // E, Pa
  double shear_modulus = 8.1e10;   // G, Pa
};

struct Section {
  double area = 0.0;           // A, m²
  double Iy = 0.0, Iz = 0.0;   // second moments about y and z, m⁴
  double J = 0.0;              // torsion constant, m⁴ (polar moment for round sections)
  double shear_factor = 0.0;   // Timoshenko shear coefficient κ (A_s = κ A); 0: no shear deformation
  double outer_radius = 0.0, inner_radius = 0.0;  // round sections only; 0 otherwise

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
