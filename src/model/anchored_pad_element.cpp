#include "cranesim/model/anchored_pad_element.hpp"

#include <cmath>

#include "cranesim/math/rotation.hpp"
#include "cranesim/model/forward_tangents.hpp"

namespace cranesim {
namespace {

constexpr double kCreepSpeed = 1e-4;    // v_ε of s₊, m/s

/// The held pad's rows: T up to the stick's onset ς = kStickFraction B, beyond it
/// ς + w y/√(1 + y²) along T with y = (|T| − ς)/w, w = B − ς (C², bounded by B).
template <class S> Eigen::Matrix<S, 6, 1> heldPadRows(const Vec3T<S>& trial, const S& bound, const Vec3T<S>& p, const Mat3T<S>& R) {
  using std::sqrt;
  Vec3T<S> F = Vec3T<S>::Zero();
  if (valueOf(bound) > 0.0) {
    const S size = sqrt(trial.squaredNorm() + S(1e-300)), onset = AnchoredPadElement::kStickFraction * bound, width = bound - onset;
    if (valueOf(size) <= valueOf(onset)) {
      F = trial;
    } else {
      const S y = (size - onset) / width;
      F = trial * ((onset + width * y / sqrt(1.0 + y * y)) / size);
    }
  }
  Eigen::Matrix<S, 6, 1> out;
  out.template head<3>() = -F;
  out.template segment<3>(3) = -p.cross(R.transpose() * F);
  return out;
}

}  // namespace

AnchoredPadElement::AnchoredPadElement(const SupportPoint& pad, int body, int anchor, std::vector<int> q_indices,
                                       std::vector<int> v_indices)
    : pad_(pad), nodes_{body, anchor}, q_(std::move(q_indices)), v_(std::move(v_indices)) {}

AnchoredPadElement::Local AnchoredPadElement::gather(const double* x, const std::vector<int>& at) const {
  Local out;
  for (int k = 0; k < 9; ++k) out(k) = x[at[static_cast<std::size_t>(k)]];
  return out;
}

template <class S>
Eigen::Matrix<S, 9, 1> AnchoredPadElement::rows(const Eigen::Matrix<S, 9, 1>& q, const Eigen::Matrix<S, 9, 1>& v, bool held) const {
  using std::sqrt;
  const SupportBed& bed = pad_.bed;
  const Mat3T<S> R = rotationMatrix<S>(Vec3T<S>(q.template segment<3>(3)));
  const Vec3T<S> p = pad_.point.cast<S>(), up = bed.up.cast<S>();
  const Vec3T<S> at = q.template head<3>() + R * p;
  const Vec3T<S> moving = v.template head<3>() + R * (Vec3T<S>(v.template segment<3>(3)).cross(p));
  const Vec3T<S> slid = q.template tail<3>(), anchor_moving = v.template tail<3>();
  const Vec3T<S> anchor = bed.anchor.cast<S>() + slid;
  const S rising = up.dot(moving);
  const S normal = penaltyForce<S>(S(bed.level) - up.dot(at), -rising, bed.law);
  const auto across = [&](const Vec3T<S>& x) -> Vec3T<S> { return x - up * up.dot(x); };
  const S bound = normal * bed.friction;
  Eigen::Matrix<S, 9, 1> out;
  if (held) {
    // Statics and modes hold the anchor where it was drawn (its row pins it there, apart from the
    // pad's rows): the pad's spring-and-damper force T is the stick law's −k e − c ė up to
    // kStickFraction μN and saturates smoothly at μN beyond, so that a pad pushed past μN has no
    // equilibrium and a lifted pad (N = 0) carries nothing.
    const Vec3T<S> e = across(at - bed.anchor.cast<S>()), trial = -e * bed.shear_stiffness - across(moving) * bed.shear_damping;
    out.template head<6>() = heldPadRows<S>(trial, bound, p, R);
    out.template tail<3>() = slid * bed.shear_stiffness;
    return out;
  }
  const Vec3T<S> e = across(at - anchor), e_rate = across(moving - anchor_moving);
  const Vec3T<S> F = -e * bed.shear_stiffness - e_rate * bed.shear_damping;
  out.template head<3>() = -F;
  out.template segment<3>(3) = -p.cross(R.transpose() * F);
  Vec3T<S> slip = Vec3T<S>::Zero();
  const S stretch = sqrt(e.squaredNorm() + S(1e-300));
  const S pull = stretch * bed.shear_stiffness;
  // The band in which slip engages: (1 − kStickFraction) μN + kSlipBandFloor, so that it does
  // not close as a pad unloads.
  const S band = bound * (1.0 - kStickFraction) + kSlipBandFloor, onset = bound + kSlipBandFloor - band;
  if (valueOf(pull) > valueOf(onset)) {
    const Vec3T<S> direction = e / stretch;
    S engaged = S(1.0);
    if (valueOf(pull) < valueOf(onset + band)) {
      const S t = (pull - onset) / band;
      engaged = t * t * (3.0 - 2.0 * t);
    }
    const S along = direction.dot(across(moving));
    const S following = 0.5 * (along + sqrt(along * along + S(kCreepSpeed * kCreepSpeed)));
    const S over = pull - bound - kSlipBandFloor, width = bound * kCatchUpFraction + kSlipBandFloor;
    S catching = S(0.0);
    if (valueOf(over) > 0.0) catching = valueOf(over) < valueOf(width) ? over * over / (2.0 * width) : over - 0.5 * width;
    slip = direction * (engaged * following + catching / (bed.shear_stiffness * kCatchUpTime));
  }
  out.template tail<3>() = anchor_moving - slip;
  return out;
}

void AnchoredPadElement::residual(const ElementInput& in, double* r) const {
  const bool held = in.rates == ParameterRates::Held;
  Eigen::Map<Local> out(r);
  out = rows<double>(gather(in.q, q_), gather(in.v, v_), held);
  if (!held) out.tail<3>() += kAnchorLag * gather(in.a, v_).tail<3>();
}

void AnchoredPadElement::jacobian(const ElementInput& in, double cj, double* J) const {
  const bool held = in.rates == ParameterRates::Held;
  forwardTangents<9>(gather(in.q, q_), gather(in.v, v_), [&](const auto& q, const auto& v) { return rows(q, v, held); }, J, J + 81);
  if (!held)
    for (int k = 6; k < 9; ++k) J[81 + k * 9 + k] += cj * kAnchorLag;
}

void AnchoredPadElement::coordinateJacobian(const ElementInput& in, double* J) const {
  const bool held = in.rates == ParameterRates::Held;
  double Jv[81];
  forwardTangents<9>(gather(in.q, q_), gather(in.v, v_), [&](const auto& q, const auto& v) { return rows(q, v, held); }, J, Jv);
}

void AnchoredPadElement::mass(const ElementInput&, double* M) const {
  std::fill(M, M + 81, 0.0);
  for (int k = 6; k < 9; ++k) M[k * 9 + k] = kAnchorLag;
}

double AnchoredPadElement::potentialEnergy(const ElementInput& in) const {
  const Local q = gather(in.q, q_);
  const SupportBed& bed = pad_.bed;
  const Vec3 at = q.head<3>() + rotationMatrix<double>(Vec3(q.segment<3>(3))) * pad_.point;
  Vec3 e = at - bed.anchor - Vec3(q.tail<3>());
  e -= bed.up * bed.up.dot(e);
  return 0.5 * bed.shear_stiffness * e.squaredNorm();
}

double AnchoredPadElement::dissipatedPower(const ElementInput& in) const {
  // P = −(body rows' force)·v_body − dΦ/dt with Φ = ½ k |e|²: k e·ȧ + c ė·Ṗ (the normal law's
  // damper not included: the pad's SupportElement books it).
  const Local q = gather(in.q, q_), v = gather(in.v, v_);
  const SupportBed& bed = pad_.bed;
  const Mat3 R = rotationMatrix<double>(Vec3(q.segment<3>(3)));
  const Vec3 at = q.head<3>() + R * pad_.point, moving = v.head<3>() + R * Vec3(v.segment<3>(3)).cross(pad_.point);
  const auto across = [&](const Vec3& x) -> Vec3 { return x - bed.up * bed.up.dot(x); };
  const Vec3 e = across(at - bed.anchor - Vec3(q.tail<3>())), e_rate = across(moving - Vec3(v.tail<3>()));
  return bed.shear_stiffness * e.dot(across(Vec3(v.tail<3>()))) + bed.shear_damping * e_rate.dot(across(moving));
}

}  // namespace cranesim
