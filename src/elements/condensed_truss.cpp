// The condensed truss's members that are not templates (condensed_truss.hpp): compiled here once,
// so that a file including the kernel does not instantiate its tangents.
#include "cranesim/elements/condensed_truss.hpp"

namespace cranesim {

auto CondensedTrussKernel::coordinateTangent(const Q<double>& q, const V<double>& v, const V<double>& a, double, const Vec3& gravity,
                                             const Mat12& M, const Mat12& C) const -> Mat12 {
  using D = SectionInertiaCoordinateTangent::D;
  const V<D> vd = v.cast<D>(), ad = a.cast<D>();
  const Mat3 R1 = rotationMatrix<double>(Vec3(q.segment<3>(3)));
  SectionInertiaCoordinateTangent inertia(R1.cast<D>(), rotationMatrix<D>(seededSecondRotation(q)), vd, &ad, gravity, length);
  for (const MassStation& st : stations) inertia.add(st.xi, st.mass, st.first_moment, st.inertia);
  CoRotatedElasticTangent elastic = coRotatedElasticTangent(frame.length, frame.damping, q.segment<3>(0), R1, q.segment<3>(6),
                                                            rotationMatrix<double>(Vec3(q.segment<3>(9))), v, stiffness);
  elastic.alongRotationVector(q.segment<3>(9));
  return objectiveCoordinateTangent({q, v, a, gravity, M, C}, elastic.force, elastic.second_end, inertia.forces());
}

auto CondensedTrussKernel::velocityTangent(const Q<double>& q, const V<double>& v, double, Mat12& M) const -> Mat12 {
  const auto massStations = [&](const auto& add) {
    for (const MassStation& st : stations) add(st.xi, st.mass, st.first_moment, st.inertia);
  };
  return frame.stationVelocityTangent(q.segment<3>(0), rotationMatrix<double>(Vec3(q.segment<3>(3))), q.segment<3>(6),
                                      rotationMatrix<double>(Vec3(q.segment<3>(9))), v, stiffness, massStations, M);
}

double CondensedTrussKernel::strainEnergy(const Q<double>& q) const {
  const Eigen::Matrix<double, 12, 1> d = frame.localDeformation<double>(q);
  return 0.5 * d.dot(stiffness * d);
}

double CondensedTrussKernel::kineticEnergy(const Q<double>& q, const V<double>& v, double) const {
  return 0.5 * v.dot(massMatrix<double>(q) * v);
}

double CondensedTrussKernel::potentialEnergy(const Q<double>& q, double, const Vec3& gravity) const {
  const Mat3 R1 = rotationMatrix<double>(Vec3(q.segment<3>(3))), R2 = rotationMatrix<double>(Vec3(q.segment<3>(9)));
  const Vec3 phi = rotationLog<double>(Mat3(R1.transpose() * R2));
  double n[4] = {0.0, 0.0, 0.0, 0.0};
  Vec3 turned = Vec3::Zero();  // Σ exp(ξφ̃) s
  for (const MassStation& st : stations) {
    const HermiteBasis h = hermiteBasis(st.xi, length);
    for (int k = 0; k < 4; ++k) n[k] += st.mass * h.N[k];
    if (st.first_moment == Vec3::Zero()) continue;
    const Vec3 psi = st.xi * phi, ps = psi.cross(st.first_moment);
    const ExpCoefficients<double> c = expCoefficients<double>(psi.squaredNorm());
    turned += st.first_moment + c.a * ps + c.b * psi.cross(ps);
  }
  const Vec3 centre = n[0] * q.segment<3>(0) + n[1] * R1.col(0) + n[2] * q.segment<3>(6) + n[3] * R2.col(0);
  return strainEnergy(q) - gravity.dot(centre + R1 * turned);
}

auto CondensedTrussKernel::condensedStiffness(const TrussGeometry& g) -> Mat12 {
  std::vector<int> column(g.nodes.size(), -1);  // first DOF of each internal node
  int n = 12;
  for (std::size_t k = 0; k < g.nodes.size(); ++k)
    if (g.nodes[k].end_section < 0) column[k] = n, n += 6;
  // A node's displacement and rotation [u; θ] (truss axes) from all DOF.
  const auto nodeMap = [&](int k) {
    Eigen::MatrixXd E = Eigen::MatrixXd::Zero(6, n);
    const TrussNode& node = g.nodes[k];
    if (node.end_section < 0) {
      E.block<6, 6>(0, column[k]).setIdentity();
    } else {
      const int s = node.end_section;
      const Vec3 p = node.position - (s * g.length) * Vec3::UnitX();
      E.block<6, 6>(0, 6 * s).setIdentity();
      E.block<3, 3>(0, 6 * s + 3) = -skew<double>(p);
    }
    return E;
  };
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
  for (const TrussMember& tube : g.members) {
    const TrussNode &a = g.nodes[tube.node1], &b = g.nodes[tube.node2];
    if (a.end_section >= 0 && a.end_section == b.end_section) continue;  // rigid with its section
    const Vec3 axis = b.position - a.position;
    TimoshenkoBeamKernel beam;
    beam.length = axis.norm();
    beam.section = tube.section;
    beam.material = g.material;
    const Mat3 Rt = tubeAxes(axis, tube.z_axis).transpose();  // truss axes → tube axes
    Eigen::MatrixXd A(12, n);
    A.topRows<6>() = nodeMap(tube.node1);
    A.bottomRows<6>() = nodeMap(tube.node2);
    for (int blk = 0; blk < 4; ++blk) A.middleRows<3>(3 * blk) = Rt * A.middleRows<3>(3 * blk);
    K.noalias() += A.transpose() * beam.localStiffness() * A;
  }
  const int ni = n - 12;
  Mat12 reduced = K.topLeftCorner<12, 12>();
  if (ni > 0) {
    const Eigen::LDLT<Eigen::MatrixXd> Kii(K.bottomRightCorner(ni, ni));
    if (Kii.info() != Eigen::Success || !(Kii.vectorD().array() > 0.0).all())
      throw std::invalid_argument("condensed truss: the internal nodes are not held by the tubes (singular stiffness)");
    reduced -= K.bottomLeftCorner(ni, 12).transpose() * Kii.solve(K.bottomLeftCorner(ni, 12));
  }
  return 0.5 * (reduced + reduced.transpose());
}

auto CondensedTrussKernel::massStations(const TrussGeometry& g, int points_per_bay) -> std::vector<MassStation> {
  std::vector<double> breaks;  // bay boundaries: the distinct stations of the nodes
  for (const TrussNode& node : g.nodes) breaks.push_back(node.position.x() / g.length);
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end(), [](double x, double y) { return std::abs(x - y) < 1e-12; }),
               breaks.end());
  const GaussRule& rule = gaussLegendre(points_per_bay);
  std::vector<MassStation> bay_points;
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k)
    for (int p = 0; p < rule.points; ++p) {
      MassStation st;
      st.xi = breaks[k] + rule.xi[p] * (breaks[k + 1] - breaks[k]);
      bay_points.push_back(st);
    }
  std::vector<MassStation> points;  // tubes across the axis
  const auto pointAt = [&](double xi) -> MassStation& {
    for (MassStation& st : points)
      if (std::abs(st.xi - xi) < 1e-12) return st;
    points.push_back(MassStation{xi});
    return points.back();
  };
  const double rho = g.material.density;
  for (const TrussMember& tube : g.members) {
    const Vec3 a = g.nodes[tube.node1].position, b = g.nodes[tube.node2].position;
    const double l = (b - a).norm(), m = rho * tube.section.area * l;
    const Mat3 Rt = tubeAxes(b - a, tube.z_axis);
    // Rotary inertia of the tube's cross-sections per unit length, truss axes.
    const Mat3 rotary = Rt * Vec3(rho * (tube.section.Iy + tube.section.Iz), rho * tube.section.Iy, rho * tube.section.Iz).asDiagonal() *
                        Rt.transpose();
    const double xa = a.x() / g.length, xb = b.x() / g.length;
    if (std::abs(xb - xa) < 1e-12) {
      const Vec3 c = 0.5 * (a + b) - a.x() * Vec3::UnitX(), e = (b - a) / l;
      MassStation& st = pointAt(xa);
      st.mass += m;
      st.first_moment += m * c;
      st.inertia += m * (c.squaredNorm() * Mat3::Identity() - c * c.transpose()) +
                    m * l * l / 12.0 * (Mat3::Identity() - e * e.transpose()) + l * rotary;
      continue;
    }
    const double lo = std::min(xa, xb), hi = std::max(xa, xb);
    for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
      if (breaks[k] < lo - 1e-12 || breaks[k + 1] > hi + 1e-12) continue;
      const double bay = breaks[k + 1] - breaks[k];
      for (int p = 0; p < rule.points; ++p) {
        MassStation& st = bay_points[k * rule.points + p];
        const double share = rule.weight[p] * bay / (hi - lo), dm = m * share;
        const Vec3 o = a + ((st.xi - xa) / (xb - xa)) * (b - a) - (st.xi * g.length) * Vec3::UnitX();
        st.mass += dm;
        st.first_moment += dm * o;
        st.inertia += dm * (o.squaredNorm() * Mat3::Identity() - o * o.transpose()) + (l * share) * rotary;
      }
    }
  }
  std::vector<MassStation> all;
  for (const auto* group : {&points, &bay_points})
    for (const MassStation& st : *group)
      if (st.mass > 0.0) all.push_back(st);
  return all;
}

}  // namespace cranesim
