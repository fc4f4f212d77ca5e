// The spline rope's members that are not templates (spline_rope.hpp), compiled here once.
#include "cranesim/elements/spline_rope.hpp"

namespace cranesim {

auto SplineRopeKernel::velocityTangent(const Q<double>& q, const Q<double>& v, double t, Mat12& M,
                                       ParameterRates rates) const -> Mat12 {
  M = massMatrix<double>(q, t);
  Mat12 J = Mat12::Zero();
  if (damping == 0.0 && transverse_damping == 0.0) return J;
  const double L = segmentLength(t), rate = segmentRate(t, rates), EA = material.youngs_modulus * section.area;
  for (int g = 0; g < rule.points; ++g) {
    const auto dN = shape(hermiteBasis(rule.xi[g], L).dN);
    if (damping > 0.0) {
      const AxialStress s = axialStress(q, v, rate, dN, rule.xi[g], L);
      if (s.stress > 0.0) J.noalias() += (rule.weight[g] * L * EA * damping) * s.du.transpose() * s.du;
    }
    if (transverse_damping > 0.0) {
      const Eigen::Matrix<double, 3, 12> A = transverseTurning<double>(q, v, rate, dN, rule.xi[g], L).dw_dv;
      J.noalias() += (rule.weight[g] * L * transverse_damping) * A.transpose() * A;
    }
  }
  return J;
}

auto SplineRopeKernel::coordinateTangent(const Q<double>& q, const Q<double>& v, const Q<double>&, double t, const Vec3&,
                                         ParameterRates rates) const -> Mat12 {
  const double L = segmentLength(t);
  const double rate = damping > 0.0 || transverse_damping > 0.0 ? segmentRate(t, rates) : 0.0;
  const double EA = material.youngs_modulus * section.area;
  Mat12 J = Mat12::Zero();
  for (int g = 0; g < rule.points; ++g) {
    const auto dN = shape(hermiteBasis(rule.xi[g], L).dN);
    const AxialStress s = axialStress(q, v, rate, dN, rule.xi[g], L);
    if (!(s.stress > 0.0)) continue;
    Eigen::Matrix<double, 1, 12> dstress = s.du;
    if (damping > 0.0) {
      Eigen::Matrix<double, 1, 12> dstrain_rate = (s.slope_rate.transpose() * dN - s.strain_rate * s.du) / s.stretch;
      if (rate != 0.0)
        dstrain_rate += (rate / s.stretch) * s.slope.transpose() * shape(hermiteBasisLengthDerivative(rule.xi[g], L).dN);
      dstress += damping * dstrain_rate;
    }
    const Eigen::Matrix<double, 3, 12> inner =
        (s.stress / s.stretch) * (dN - s.u * s.du) + s.u * dstress;  // (σ/λ)(I − u uᵀ) dN + u ∂σ/∂q
    J.noalias() += (rule.weight[g] * L * EA) * dN.transpose() * inner;
  }
  if (transverse_damping > 0.0)
    J += coordinateDerivative(q, [&]<class S>(const Q<S>& qs) { return transverseDampingForce<S>(qs, v.cast<S>(), rate, L); });
  return J;
}

double SplineRopeKernel::kineticEnergy(const Q<double>& q, const Q<double>& v, double t) const {
  return 0.5 * v.dot(massMatrix<double>(q, t) * v);
}

double SplineRopeKernel::potentialEnergy(const Q<double>& q, double t, const Vec3& gravity) const {
  const double L = segmentLength(t), rhoA = material.density * section.area;
  const double EA = material.youngs_modulus * section.area;
  double U = 0.0;
  for (int g = 0; g < rule.points; ++g) {
    const HermiteBasis b = hermiteBasis(rule.xi[g], L);
    const double strain = std::max((shape(b.dN) * q).norm() - 1.0, 0.0);
    U += rule.weight[g] * L * (0.5 * EA * strain * strain - rhoA * gravity.dot(shape(b.N) * q));
  }
  return U;
}

double SplineRopeKernel::explicitTimePower(const Q<double>& q, const Q<double>& v, double t, const Vec3& gravity) const {
  const double rate = segmentRate(t);
  if (rate == 0.0) return 0.0;
  const double L = segmentLength(t), rhoA = material.density * section.area;
  const double EA = material.youngs_modulus * section.area;
  double power = 0.0;
  for (int g = 0; g < rule.points; ++g) {
    const HermiteBasis b = hermiteBasis(rule.xi[g], L), bL = hermiteBasisLengthDerivative(rule.xi[g], L);
    const Vec3 rs = shape(b.dN) * q, rs_L = shape(bL.dN) * q, u = shape(b.N) * v;
    const double stretch = rs.norm(), strain = std::max(stretch - 1.0, 0.0);
    const double e = 0.5 * rhoA * u.squaredNorm() + 0.5 * EA * strain * strain - rhoA * gravity.dot(shape(b.N) * q);
    const double e_L = rhoA * u.dot(shape(bL.N) * v) + EA * strain * rs.dot(rs_L) / stretch -
                       rhoA * gravity.dot(shape(bL.N) * q);
    power += rule.weight[g] * rate * (e + L * e_L);
    if (damping > 0.0)
      power += rule.weight[g] * L * EA * dampingStress(q, v, rate, rule.xi[g], L) * rate * rs.dot(rs_L) / stretch;
    // The transverse damper's force does dqᵀ c A w = c ‖w‖² − c wᵀ w_L, w_L the part of w that
    // reeling causes: the first is dissipated, the second the winch's.
    if (transverse_damping > 0.0) {
      const TransverseTurning<double> turning = transverseTurning<double>(q, v, rate, shape(b.dN), rule.xi[g], L);
      power += rule.weight[g] * L * transverse_damping * turning.w.dot(turning.w_reeling);
    }
  }
  return power;
}

double SplineRopeKernel::dissipatedPower(const Q<double>& q, const Q<double>& v, double t, const Vec3& gravity) const {
  return axialDissipatedPower(q, v, t) + transverseDissipatedPower(q, v, t, gravity);
}

double SplineRopeKernel::transverseDissipatedPower(const Q<double>& q, const Q<double>& v, double t, const Vec3&) const {
  if (transverse_damping == 0.0) return 0.0;
  const double L = segmentLength(t), rate = segmentRate(t);
  double power = 0.0;
  for (int g = 0; g < rule.points; ++g) {
    const auto dN = shape(hermiteBasis(rule.xi[g], L).dN);
    power += rule.weight[g] * L * transverse_damping * transverseTurning<double>(q, v, rate, dN, rule.xi[g], L).w.squaredNorm();
  }
  return power;
}

double SplineRopeKernel::axialDissipatedPower(const Q<double>& q, const Q<double>& v, double t) const {
  if (damping == 0.0) return 0.0;
  const double L = segmentLength(t), rate = segmentRate(t), EA = material.youngs_modulus * section.area;
  double power = 0.0;
  for (int g = 0; g < rule.points; ++g) {
    const auto dN = shape(hermiteBasis(rule.xi[g], L).dN);
    const Vec3 rs = dN * q;
    const double strain_rate = rs.dot(slopeRate<double>(q, v, rate, dN, rule.xi[g], L)) / rs.norm();
    power += rule.weight[g] * L * EA * dampingStress(q, v, rate, rule.xi[g], L) * strain_rate;
  }
  return power;
}

double SplineRopeKernel::tension(const Q<double>& q, double t, double xi) const {
  const double strain = (shape(hermiteBasis(xi, segmentLength(t)).dN) * q).norm() - 1.0;
  return material.youngs_modulus * section.area * std::max(strain, 0.0);
}

auto SplineRopeKernel::axialStress(const Q<double>& q, const Q<double>& v, double rate, const Eigen::Matrix<double, 3, 12>& dN,
                                   double xi, double L) const -> AxialStress {
  AxialStress s;
  s.slope = dN * q;
  s.stretch = s.slope.norm();
  s.u = s.slope / s.stretch;
  s.du = s.u.transpose() * dN;
  s.slope_rate = damping > 0.0 ? slopeRate<double>(q, v, rate, dN, xi, L) : Vec3::Zero();
  s.strain_rate = s.slope.dot(s.slope_rate) / s.stretch;
  s.stress = s.stretch - 1.0 + damping * s.strain_rate;
  return s;
}

double SplineRopeKernel::dampingStress(const Q<double>& q, const Q<double>& v, double rate, double xi, double L) const {
  const auto dN = shape(hermiteBasis(xi, L).dN);
  const Vec3 rs = dN * q;
  const double stretch = rs.norm(), strain = stretch - 1.0;
  const double strain_rate = rs.dot(slopeRate<double>(q, v, rate, dN, xi, L)) / stretch;
  return std::max(strain + damping * strain_rate, 0.0) - std::max(strain, 0.0);
}

Eigen::Matrix<double, 3, 12> SplineRopeKernel::shape(const std::array<double, 4>& n) {
  Eigen::Matrix<double, 3, 12> N;
  for (int k = 0; k < 4; ++k) N.block<3, 3>(0, 3 * k) = n[k] * Mat3::Identity();
  return N;
}

}  // namespace cranesim
