// The Timoshenko beam's members that are not templates (timoshenko_beam.hpp): compiled here
// once, so that a file including the kernel does not instantiate its tangents.
#include "cranesim/elements/timoshenko_beam.hpp"

namespace cranesim {

auto TimoshenkoBeamKernel::shapeFunctions(double xi) const -> ShapeFunctions {
  const SectionProperties p = section.properties(material);
  const double L = length, x = xi, x2 = x * x, x3 = x2 * x;
  ShapeFunctions f;
  // Axial and torsion: linear (C-21, C-22).
  f.N(0, 0) = 1.0 - x, f.N(0, 6) = x, f.dN(0, 0) = -1.0 / L, f.dN(0, 6) = 1.0 / L;
  f.N(3, 3) = 1.0 - x, f.N(3, 9) = x, f.dN(3, 3) = -1.0 / L, f.dN(3, 9) = 1.0 / L;
  // Bending in one plane, dofs (v¹, θ¹, v², θ²) with v' = θ when shear-rigid (C-23; the thesis
  // prints the functions of end 2 only, with α = 4Φ). Each row: value, d/dξ.
  const auto plane = [&](double Phi, double Nv[4], double dNv[4], double Nt[4], double dNt[4]) {
    const double m = 1.0 / (1.0 + Phi);
    Nv[0] = m * (1.0 - 3.0 * x2 + 2.0 * x3 + Phi * (1.0 - x));
    Nv[1] = m * L * (x - 2.0 * x2 + x3 + 0.5 * Phi * (x - x2));
    Nv[2] = m * (3.0 * x2 - 2.0 * x3 + Phi * x);
    Nv[3] = m * L * (-x2 + x3 + 0.5 * Phi * (x2 - x));
    dNv[0] = m * (-6.0 * x + 6.0 * x2 - Phi);
    dNv[1] = m * L * (1.0 - 4.0 * x + 3.0 * x2 + 0.5 * Phi * (1.0 - 2.0 * x));
    dNv[2] = m * (6.0 * x - 6.0 * x2 + Phi);
    dNv[3] = m * L * (-2.0 * x + 3.0 * x2 + 0.5 * Phi * (2.0 * x - 1.0));
    Nt[0] = m * 6.0 * (x2 - x) / L;
    Nt[1] = m * (1.0 - 4.0 * x + 3.0 * x2 + Phi * (1.0 - x));
    Nt[2] = -m * 6.0 * (x2 - x) / L;
    Nt[3] = m * (3.0 * x2 - 2.0 * x + Phi * x);
    dNt[0] = m * 6.0 * (2.0 * x - 1.0) / L;
    dNt[1] = m * (-4.0 + 6.0 * x - Phi);
    dNt[2] = -m * 6.0 * (2.0 * x - 1.0) / L;
    dNt[3] = m * (6.0 * x - 2.0 + Phi);
  };
  double Nv[4], dNv[4], Nt[4], dNt[4];
  // x–y plane: v and ψ_z (bending about z, EI_z): v' = ψ_z.
  plane(shearParameter(p.EIz, p.GAy, length), Nv, dNv, Nt, dNt);
  const int vz[4] = {1, 5, 7, 11};
  for (int k = 0; k < 4; ++k) {
    f.N(1, vz[k]) = Nv[k], f.dN(1, vz[k]) = dNv[k] / L;
    f.N(5, vz[k]) = Nt[k], f.dN(5, vz[k]) = dNt[k] / L;
  }
  // x–z plane: w and ψ_y (bending about y, EI_y): w' = −ψ_y, i.e. (w, −ψ_y) plays (v, ψ_z) (C-24).
  plane(shearParameter(p.EIy, p.GAz, length), Nv, dNv, Nt, dNt);
  const int wy[4] = {2, 4, 8, 10};
  const double sign[4] = {1.0, -1.0, 1.0, -1.0};
  for (int k = 0; k < 4; ++k) {
    f.N(2, wy[k]) = sign[k] * Nv[k], f.dN(2, wy[k]) = sign[k] * dNv[k] / L;
    f.N(4, wy[k]) = -sign[k] * Nt[k], f.dN(4, wy[k]) = -sign[k] * dNt[k] / L;
  }
  return f;
}

auto TimoshenkoBeamKernel::strainMatrix(double xi) const -> Mat6x12 {
  const ShapeFunctions f = shapeFunctions(xi);
  Mat6x12 B;
  B.row(0) = f.dN.row(0);
  B.row(1) = f.dN.row(3);
  B.row(2) = f.dN.row(4);
  B.row(3) = f.dN.row(5);
  B.row(4) = f.dN.row(1) - f.N.row(5);
  B.row(5) = f.dN.row(2) + f.N.row(4);
  return B;
}

auto TimoshenkoBeamKernel::localStiffness() const -> Mat12 {
  const SectionProperties p = section.properties(material);
  Eigen::Matrix<double, 6, 1> D;
  D << p.EA, p.GJ, p.EIy, p.EIz, p.GAy, p.GAz;
  const GaussRule& rule = gaussLegendre(stiffness_points);
  Mat12 K = Mat12::Zero();
  for (int g = 0; g < rule.points; ++g) {
    const Mat6x12 B = strainMatrix(rule.xi[g]);
    K.noalias() += (rule.weight[g] * length) * (B.transpose() * D.asDiagonal() * B);
  }
  return K;
}

double TimoshenkoBeamKernel::strainEnergy(const Q<double>& q) const {
  const auto d = localDeformation<double>(q);
  return 0.5 * d.dot(stiffness() * d);
}

Eigen::Matrix<double, 12, 1> TimoshenkoBeamKernel::sectionForces(const Vec3& r1, const Mat3& R1, const Vec3& r2, const Mat3& R2, const V<double>& v,
                                                                 const V<double>& a, const Vec3& gravity, const Mat12& K) const {
  const CoRotatedTangent<double> c = coRotateWithTangent<double>(r1, R1, r2, R2);
  const V<double> r = inertialAndGravityForce<double>(r1, R1, r2, R2, v, gravity, &a) + elasticForce<double>(c, v, K);
  const Mat3& RB = c.R;
  Eigen::Matrix<double, 12, 1> out;
  for (int e = 0; e < 2; ++e) {
    const double face = e == 0 ? -1.0 : 1.0;
    out.segment<3>(6 * e) = face * (RB.transpose() * r.segment<3>(6 * e));
    out.segment<3>(6 * e + 3) = face * (RB.transpose() * ((e == 0 ? R1 : R2) * r.segment<3>(6 * e + 3)));
  }
  return out;
}

Eigen::Matrix<double, 12, 1> TimoshenkoBeamKernel::sectionForces(const Q<double>& q, const V<double>& v, const V<double>& a, const Vec3& gravity) const {
  return sectionForces(q.segment<3>(0), rotationMatrix<double>(Vec3(q.segment<3>(3))), q.segment<3>(6),
                       rotationMatrix<double>(Vec3(q.segment<3>(9))), v, a, gravity, stiffness());
}

auto TimoshenkoBeamKernel::coordinateTangent(const Q<double>& q, const V<double>& v, const V<double>& a, double, const Vec3& gravity,
                                             const Mat12& M, const Mat12& C) const -> Mat12 {
  using D = SectionInertiaCoordinateTangent::D;
  const V<D> vd = v.cast<D>(), ad = a.cast<D>();
  const Mat3 R1 = rotationMatrix<double>(Vec3(q.segment<3>(3)));
  SectionInertiaCoordinateTangent inertia(R1.cast<D>(), rotationMatrix<D>(seededSecondRotation(q)), vd, &ad, gravity, length);
  addMassPoints(inertia);
  CoRotatedElasticTangent elastic = coRotatedElasticTangent(length, damping, q.segment<3>(0), R1, q.segment<3>(6),
                                                            rotationMatrix<double>(Vec3(q.segment<3>(9))), v, stiffness());
  elastic.alongRotationVector(q.segment<3>(9));
  return objectiveCoordinateTangent({q, v, a, gravity, M, C}, elastic.force, elastic.second_end, inertia.forces());
}

auto TimoshenkoBeamKernel::velocityTangent(const Q<double>& q, const V<double>& v, double, Mat12& M) const -> Mat12 {
  return velocityTangent(q.segment<3>(0), rotationMatrix<double>(Vec3(q.segment<3>(3))), q.segment<3>(6),
                         rotationMatrix<double>(Vec3(q.segment<3>(9))), v, stiffness(), M);
}

auto TimoshenkoBeamKernel::velocityTangent(const Vec3& r1, const Mat3& R1, const Vec3& r2, const Mat3& R2, const V<double>& v, const Mat12& K,
                                           Mat12& M) const -> Mat12 {
  const SectionProperties p = section.properties(material);
  const Vec3 J(p.rhoIp, p.rhoIy, p.rhoIz);
  const GaussRule& rule = gaussLegendre(mass_points);
  const auto gaussPoints = [&](const auto& add) {
    for (int gp = 0; gp < rule.points; ++gp) {
      const double wl = rule.weight[gp] * length;
      add(rule.xi[gp], wl * p.rhoA, Vec3::Zero(), Mat3((wl * J).asDiagonal()));
    }
  };
  return stationVelocityTangent(r1, R1, r2, R2, v, K, gaussPoints, M);
}

auto TimoshenkoBeamKernel::endFrameRates(const Vec3& r1, const Mat3& R1, const Vec3& r2, const Mat3& R2, const V<double>& v) const -> EndFrameRates {
  using P = Dual<double, 1>;
  const Mat3 dR1 = R1 * skew<double>(Vec3(v.segment<3>(3))), dR2 = R2 * skew<double>(Vec3(v.segment<3>(9)));
  Mat3T<P> R1p, R2p;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      R1p(i, j) = P(R1(i, j), Eigen::Matrix<double, 1, 1>(dR1(i, j)));
      R2p(i, j) = P(R2(i, j), Eigen::Matrix<double, 1, 1>(dR2(i, j)));
    }
  const EndFrames<P> moving = endFrames<P>(r1.cast<P>(), R1p, r2.cast<P>(), R2p);
  EndFrameRates out{endFrames<double>(r1, R1, r2, R2), Mat3(), Mat3(), Vec3()};
  for (int i = 0; i < 3; ++i) {
    out.phi_dot(i) = moving.phi(i).derivatives()(0);
    for (int j = 0; j < 3; ++j) {
      out.Tinv_dot(i, j) = moving.Tinv(i, j).derivatives()(0);
      out.TinvRrelT_dot(i, j) = moving.TinvRrelT(i, j).derivatives()(0);
    }
  }
  return out;
}

std::array<double, 4> TimoshenkoBeamKernel::centreLineWeights() const {
  const GaussRule& rule = gaussLegendre(mass_points);
  std::array<double, 4> n{};
  for (int gp = 0; gp < rule.points; ++gp) {
    const HermiteBasis h = hermiteBasis(rule.xi[gp], length);
    for (int k = 0; k < 4; ++k) n[k] += rule.weight[gp] * length * h.N[k];
  }
  return n;
}

double TimoshenkoBeamKernel::kineticEnergy(const Q<double>& q, const V<double>& v, double) const {
  return 0.5 * v.dot(massMatrix<double>(q) * v);
}

double TimoshenkoBeamKernel::gravityPotential(const Q<double>& q, const Vec3& gravity) const {
  return gravityPotential(endFrames<double>(q), gravity);
}

double TimoshenkoBeamKernel::gravityPotential(const EndFrames<double>& e, const Vec3& gravity) const {
  const std::array<double, 4> n = centreLineWeights();
  const double rhoA = section.properties(material).rhoA;
  return -rhoA * gravity.dot(n[0] * e.r1 + n[1] * e.R1.col(0) + n[2] * e.r2 + n[3] * e.R2.col(0));
}

double TimoshenkoBeamKernel::potentialEnergy(const Q<double>& q, double, const Vec3& gravity) const {
  return gravityPotential(q, gravity) + strainEnergy(q);
}

}  // namespace cranesim
