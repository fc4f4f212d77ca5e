#include "cranesim/model/equivalent_beam.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "cranesim/elements/condensed_truss.hpp"

namespace cranesim {

EquivalentBeam equivalentBeam(const TrussGeometry& g) {
  using Mat6 = Eigen::Matrix<double, 6, 6>;
  const CondensedTrussKernel condensed(g);
  const double L = g.length, E = g.material.youngs_modulus, G = g.material.shear_modulus;
  const Eigen::LDLT<Mat6> clamped(Mat6(condensed.stiffness.bottomRightCorner<6, 6>()));
  if (clamped.info() != Eigen::Success || !(clamped.vectorD().array() > 0.0).all())
    throw std::invalid_argument("equivalent beam: the truss' condensed stiffness is not positive definite");
  const Mat6 C = clamped.solve(Mat6::Identity());
  enum { ux, uy, uz, tx, ty, tz };

  EquivalentBeam beam;
  // One bending plane (deflection w, rotation θ) with bending stiffness EI: its shear compliance,
  // or −1 where a taper makes the guided deflection stiffer than the shear-rigid beam's.
  const auto shearCompliance = [&](int w, int theta, double EI) {
    const double guided = C(w, w) - C(w, theta) * C(w, theta) / C(theta, theta), bending = L * L * L / (12.0 * EI);
    beam.guided_mismatch = std::max(beam.guided_mismatch, bending / guided - 1.0);
    return guided > bending ? (guided - bending) / L : -1.0;
  };
  const double EIy = L / C(ty, ty), EIz = L / C(tz, tz);
  // κGA: the mean compliance of the planes that have one.
  std::vector<double> planes;
  for (const double s : {shearCompliance(uz, ty, EIy), shearCompliance(uy, tz, EIz)})
    if (s >= 0.0) planes.push_back(s);
  const double shear = planes.empty() ? 0.0 : planes.size() == 1 ? planes[0] : 0.5 * (planes[0] + planes[1]);
  beam.shear_plane_mismatch = planes.size() == 2 && shear > 0.0 ? 0.5 * std::abs(planes[0] - planes[1]) / shear : 0.0;

  beam.mass = condensed.mass();
  beam.section.area = L / (C(ux, ux) * E);
  beam.section.Iy = EIy / E;
  beam.section.Iz = EIz / E;
  beam.section.J = L / (C(tx, tx) * G);
  beam.section.shear_factor = shear > 0.0 ? 1.0 / (shear * G * beam.section.area) : 0.0;
  beam.material = g.material;
  beam.material.density = beam.mass / (beam.section.area * L);
  return beam;
}

}  // namespace cranesim
