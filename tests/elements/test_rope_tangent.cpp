// The spline rope's closed-form tangents (elements/spline_rope.hpp: velocityTangent,
// coordinateTangent) against forward AD of its force over q and polarization over dq (exact for
// a force linear in dq away from the slack kink), and against central differences of the element
// residual: taut, damped, reeled (left, right and held rates at a breakpoint of the length), with
// one Gauss point slack, and with transverse damping.

#include <catch2/catch.hpp>

#include <memory>
#include <vector>

#include "cranesim/elements/spline_rope.hpp"
#include "cranesim/model/kernel_elements.hpp"
#include "element_differences.hpp"

using namespace cranesim;

namespace {

using Q = SplineRopeKernel::Q<double>;
using Mat12 = SplineRopeKernel::Mat12;

/// A 4 m steel rope element whose length is reeled in at 0.6 m/s from t = 0.5 s.
SplineRopeKernel reeledRope(double damping, double transverse_damping) {
  SplineRopeKernel k;
  k.total_length = Profile(RampProfile{4.0, -0.6, 0.5});
  k.section = Section::circular(0.01, 0.0, 0.3);
  k.material = {7800.0, 1.0e11, 4.0e10};
  k.damping = damping;
  k.transverse_damping = transverse_damping;
  return k;
}

/// Stretched by `stretch` along x, sagging: slopes tilted down at the start, up at the end.
Q sagging(double stretch, double tilt) {
  Q q;
  q << Vec3::Zero(), stretch * Vec3(std::cos(tilt), 0.1 * std::sin(tilt), -std::sin(tilt)), Vec3(4.0 * stretch, 0.02, 0.0),
      stretch * Vec3(std::cos(tilt), 0.0, std::sin(tilt));
  return q;
}

/// Ends 3.99 m apart on a 4 m element, end slopes stretched by 1 %: taut at the ends, slack in
/// the middle (the slope's norm there is about 1.5 · 3.99/4 − 0.5 · 1.01 < 1).
Q partlySlack() {
  Q q;
  q << Vec3::Zero(), Vec3(1.01, 0.0, -0.01), Vec3(3.99, 0.01, 0.0), Vec3(1.01, 0.01, 0.01);
  return q;
}

Q velocities() {
  Q v;
  v << 0.1, -0.2, 0.3, 0.05, 0.1, -0.02, -0.2, 0.1, 0.4, 0.03, -0.05, 0.1;
  return v;
}

/// ∂F/∂q by forward AD of the kernel's force and ∂F/∂dq by polarization: the way every kernel
/// without closed forms is differentiated (element.hpp).
std::pair<Mat12, Mat12> referenceTangents(const SplineRopeKernel& k, const Q& q, const Q& v, double t, const Vec3& g,
                                          ParameterRates rates) {
  const Mat12 Jq = coordinateDerivative(q, [&]<class S>(const Eigen::Matrix<S, 12, 1>& qs) {
    return k.force<S>(qs, v.cast<S>(), t, g, rates);
  });
  Mat12 Jv;
  for (int j = 0; j < 12; ++j) {
    const double s = 1e-6;
    Q vp = v, vm = v;
    vp(j) += s, vm(j) -= s;
    Jv.col(j) = (k.force<double>(q, vp, t, g, rates) - k.force<double>(q, vm, t, g, rates)) / (2.0 * s);
  }
  return {Jq, Jv};
}

void checkTangents(const SplineRopeKernel& k, const Q& q, double t, ParameterRates rates) {
  const Q v = velocities(), a = Q::Constant(0.3);
  const Vec3 g(0.0, 0.0, -9.81);
  const auto [Jq_ref, Jv_ref] = referenceTangents(k, q, v, t, g, rates);
  Mat12 M;
  const Mat12 Jv = k.velocityTangent(q, v, t, M, rates);
  const Mat12 Jq = k.coordinateTangent(q, v, a, t, g, rates);
  CHECK((M - k.massMatrix<double>(q, t)).cwiseAbs().maxCoeff() == 0.0);
  CHECK((Jq - Jq_ref).cwiseAbs().maxCoeff() < 1e-12 * Jq_ref.cwiseAbs().maxCoeff());
  CHECK((Jv - Jv_ref).cwiseAbs().maxCoeff() < 1e-7 * std::max(Jv_ref.cwiseAbs().maxCoeff(), 1.0));

  // The element's Jacobian [∂r/∂q | ∂r/∂dq + cj M] against central differences of its residual.
  std::vector<int> idx(12);
  for (int i = 0; i < 12; ++i) idx[i] = i;
  const std::unique_ptr<Element> element = makeElement(k, {}, idx, idx);
  ElementInput in{q.data(), v.data(), a.data(), t, g};
  in.rates = rates;
  const double cj = 50.0;
  Eigen::Matrix<double, 12, 24> J;
  element->jacobian(in, cj, J.data());
  const Eigen::Matrix<double, 12, 24> fd = test::centralDifferenceJacobian(*element, in, cj);
  CHECK((J - fd).cwiseAbs().maxCoeff() < 1e-6 * J.cwiseAbs().maxCoeff());
}

}  // namespace

TEST_CASE("Spline rope tangents: taut, undamped and damped, at rest length and reeled", "[rope][jacobian]") {
  for (double damping : {0.0, 1e-3}) {
    INFO("η = " << damping);
    const SplineRopeKernel k = reeledRope(damping, 0.0);
    checkTangents(k, sagging(1.002, 0.1), 0.2, ParameterRates::Left);   // before the reeling starts
    checkTangents(k, sagging(1.002, 0.1), 0.9, ParameterRates::Left);   // reeled in at 0.6 m/s
    checkTangents(k, sagging(1.002, 0.1), 0.9, ParameterRates::Held);   // statics and modes
  }
}

TEST_CASE("Spline rope tangents: the rates' side at the length's breakpoint", "[rope][jacobian]") {
  const SplineRopeKernel k = reeledRope(1e-3, 0.0);
  // At t = 0.5 s the left rate is 0 and the right one −0.6 m/s: the tangents follow the side asked.
  checkTangents(k, sagging(1.002, 0.1), 0.5, ParameterRates::Left);
  checkTangents(k, sagging(1.002, 0.1), 0.5, ParameterRates::Right);
  const Q q = sagging(1.002, 0.1), v = velocities(), a = Q::Zero();
  const Vec3 g(0.0, 0.0, -9.81);
  CHECK((k.coordinateTangent(q, v, a, 0.5, g, ParameterRates::Left) -
         k.coordinateTangent(q, v, a, 0.5, g, ParameterRates::Right)).norm() > 0.0);
}

TEST_CASE("Spline rope tangents: partly slack, and with transverse damping", "[rope][jacobian]") {
  const SplineRopeKernel axial = reeledRope(1e-3, 0.0);
  const Q q = partlySlack();
  const double L = axial.segmentLength(0.2);
  int slack = 0;
  for (int g = 0; g < axial.rule.points; ++g) slack += axial.tension(q, 0.2, axial.rule.xi[g]) == 0.0;
  CHECK(L == 4.0);
  CHECK(slack > 0);
  CHECK(slack < axial.rule.points);
  checkTangents(axial, q, 0.2, ParameterRates::Left);
  checkTangents(reeledRope(1e-3, 800.0), sagging(1.002, 0.1), 0.9, ParameterRates::Left);
  checkTangents(reeledRope(0.0, 800.0), q, 0.2, ParameterRates::Left);
}
