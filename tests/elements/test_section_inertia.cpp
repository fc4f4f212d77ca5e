// The coordinate columns of the section inertia in closed form
// (section_inertia_coordinate_tangent.hpp) against forward AD through every station
// (SectionInertiaForces on dual numbers), from no relative rotation of the ends to 2.5 rad.

#include <catch2/catch.hpp>

#include <cstdio>

#include "cranesim/elements/parts/section_inertia_coordinate_tangent.hpp"
#include "random_states.hpp"

using namespace cranesim;
using test::Rng;

namespace {

using D = Dual<double, 3>;
using V12 = Eigen::Matrix<double, 12, 1>;
using V12D = Eigen::Matrix<D, 12, 1>;

struct Station {
  double xi, mass;
  Vec3 s;
  Mat3 J;
};

/// Stations across [0, 1] with random first moments and positive definite inertias, and both
/// ends (ξ = 0, 1).
std::vector<Station> randomStations(Rng& rng) {
  std::vector<Station> out;
  for (double xi : {0.0, 0.05, 0.21, 0.5, 0.77, 0.93, 1.0}) {
    const Mat3 A = Mat3::Identity() + 0.3 * Mat3::Random();
    out.push_back({xi, 2.0 + rng(), rng.vec(0.8), Mat3(A * A.transpose())});
  }
  return out;
}

}  // namespace

TEST_CASE("Section inertia: the closed-form coordinate columns equal forward AD through every station", "[timoshenko][condensed_truss]") {
  const Vec3 g(0.4, -1.1, -9.81);
  const double length = 3.2;
  Rng rng(23);
  double worst = 0.0;
  for (double angle : {0.0, 1e-3, 0.05, 0.3, 1.2, 2.5}) {
    for (int trial = 0; trial < 2; ++trial) {
      const std::vector<Station> stations = randomStations(rng);
      const Mat3 R1 = rng.rotation(3.0);
      const Mat3 R2 = R1 * (angle == 0.0 ? Mat3::Identity() : axisAngle(rng.vec().normalized(), angle));
      V12 q;
      q << rng.vec(5.0), rotationLog<double>(R1), rng.vec(5.0), rotationLog<double>(R2);
      const V12 v = 3.0 * V12::Random(), a = 20.0 * V12::Random();
      const bool with_accelerations = trial == 0;
      Vec3T<D> phi2;
      for (int k = 0; k < 3; ++k) phi2(k) = seeded<double, 3>(q(9 + k), k);
      const Mat3T<D> R1d = rotationMatrix<double>(Vec3(q.segment<3>(3))).cast<D>(), R2d = rotationMatrix<D>(phi2);
      const V12D vd = v.cast<D>(), ad = a.cast<D>();
      const V12D* accelerations = with_accelerations ? &ad : nullptr;

      SectionInertiaForces<D> reference(R1d, R2d, vd, accelerations, g, length);
      SectionInertiaCoordinateTangent closed(R1d, R2d, vd, accelerations, g, length);
      for (const Station& st : stations) {
        reference.add(st.xi, st.mass, st.s, st.J);
        closed.add(st.xi, st.mass, st.s, st.J);
      }
      // A beam's station (no first moment, principal inertia) through its own overload.
      reference.add(0.4, 1.5, Vec3(0.2, 0.1, 0.3));
      closed.add(0.4, 1.5, Vec3(0.2, 0.1, 0.3));
      const V12D r_ad = reference.forces(), r = closed.forces();
      Eigen::Matrix<double, 12, 3> columns_ad, columns;
      V12 values_ad, values;
      for (int i = 0; i < 12; ++i) {
        values_ad(i) = r_ad(i).value(), values(i) = r(i).value();
        columns_ad.row(i) = r_ad(i).derivatives().transpose(), columns.row(i) = r(i).derivatives().transpose();
      }
      INFO("relative rotation " << angle << " rad, accelerations " << with_accelerations);
      CHECK((values - values_ad).norm() < 1e-13 * values_ad.norm());
      const double error = (columns - columns_ad).norm() / columns_ad.norm();
      CHECK(error < 1e-12);
      worst = std::max(worst, error);
    }
  }
  std::printf("[section inertia] closed-form coordinate columns vs forward AD: rel. err %.3g\n", worst);
}
