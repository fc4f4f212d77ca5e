#include "cranesim/model/anchored_support_element.hpp"

#include <cmath>
#include <numbers>

#include "cranesim/math/rotation.hpp"
#include "cranesim/model/forward_tangents.hpp"

namespace cranesim {
namespace {

constexpr double kAnchorCreepSpeed = 1e-4;  // v_ε of s₊, m/s

/// The held point's force: the trial T up to the stick's onset ς = kStickFraction B, beyond it
/// ς + w y/√(1 + y²) along T with y = (|T| − ς)/w, w = B − ς (C², bounded by B).
template <class S> Vec3T<S> heldSupportForce(const Vec3T<S>& trial, const S& bound) {
  using std::sqrt;
  if (valueOf(bound) <= 0.0) return Vec3T<S>::Zero();
  const S size = sqrt(trial.squaredNorm() + S(1e-300)), onset = AnchoredSupportElement::kStickFraction * bound, width = bound - onset;
  if (valueOf(size) <= valueOf(onset)) return trial;
  const S y = (size - onset) / width;
  return trial * ((onset + width * y / sqrt(1.0 + y * y)) / size);
}

}  // namespace

AnchoredSupportElement::AnchoredSupportElement(std::vector<SupportPoint> points, const std::vector<double>& footprints, int body,
                                               int anchor, std::vector<int> q_indices, std::vector<int> v_indices)
    : points_(std::move(points)), nodes_{body, anchor}, q_(std::move(q_indices)), v_(std::move(v_indices)) {
  up_ = points_.front().bed.up.normalized();
  across1_ = (std::abs(up_.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY());
  across1_ = (across1_ - up_ * up_.dot(across1_)).normalized();
  across2_ = up_.cross(across1_);
  centre_ = Vec3::Zero();
  for (const SupportPoint& p : points_) centre_ += p.bed.anchor / static_cast<double>(points_.size());
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const Vec3 arm = points_[i].bed.anchor - centre_;
    drawn_arms_.push_back(arm - up_ * up_.dot(arm));
    levers_.push_back(2.0 / 3.0 * std::sqrt(footprints[i] / std::numbers::pi));
    stiffness_ += points_[i].bed.shear_stiffness;
  }
}

AnchoredSupportElement::Local AnchoredSupportElement::gather(const double* x, const std::vector<int>& at) const {
  Local out;
  for (int k = 0; k < 9; ++k) out(k) = x[at[static_cast<std::size_t>(k)]];
  return out;
}

template <class S>
Eigen::Matrix<S, 9, 1> AnchoredSupportElement::heldRows(const Eigen::Matrix<S, 9, 1>& q, const Eigen::Matrix<S, 9, 1>& v) const {
  // Statics and modes hold the anchor where it was drawn (its rows pin it there).
  const Mat3T<S> R = rotationMatrix<S>(Vec3T<S>(q.template segment<3>(3)));
  const Vec3T<S> up = up_.cast<S>();
  const auto across = [&](const Vec3T<S>& x) -> Vec3T<S> { return x - up * up.dot(x); };
  Eigen::Matrix<S, 9, 1> out = Eigen::Matrix<S, 9, 1>::Zero();
  for (const SupportPoint& s : points_) {
    const SupportBed& bed = s.bed;
    const Vec3T<S> p = s.point.cast<S>();
    const Vec3T<S> at = q.template head<3>() + R * p;
    const Vec3T<S> moving = v.template head<3>() + R * (Vec3T<S>(v.template segment<3>(3)).cross(p));
    const S normal = penaltyForce<S>(S(bed.level) - up.dot(at), -up.dot(moving), bed.law);
    const Vec3T<S> trial = -across(at - bed.anchor.cast<S>()) * bed.shear_stiffness - across(moving) * bed.shear_damping;
    const Vec3T<S> F = heldSupportForce<S>(trial, normal * bed.friction);
    out.template head<3>() -= F;
    out.template segment<3>(3) -= p.cross(R.transpose() * F);
  }
  // The pinned anchor's rows are those of a spring that, on the anchor's lag mass ε, rings at
  // kHeldAnchorFrequency: its modes stay clear of the crane's, and of the zero threshold modes
  // scale with the stiffest one (solvers/modes.hpp).
  const double pin = kAnchorLag * std::pow(2.0 * std::numbers::pi * kHeldAnchorFrequency, 2);
  out.template tail<3>() = q.template tail<3>() * pin;
  return out;
}

template <class S>
Eigen::Matrix<S, 9, 1> AnchoredSupportElement::rows(const Eigen::Matrix<S, 9, 1>& q, const Eigen::Matrix<S, 9, 1>& v, bool held) const {
  if (held) return heldRows(q, v);
  using std::cos;
  using std::sin;
  using std::sqrt;
  const Mat3T<S> R = rotationMatrix<S>(Vec3T<S>(q.template segment<3>(3)));
  const Vec3T<S> up = up_.cast<S>(), t1 = across1_.cast<S>(), t2 = across2_.cast<S>();
  const auto across = [&](const Vec3T<S>& x) -> Vec3T<S> { return x - up * up.dot(x); };
  const Vec3T<S> omega = R * Vec3T<S>(v.template segment<3>(3));
  const Vec3T<S> slid = t1 * q(6) + t2 * q(7), slid_rate = t1 * v(6) + t2 * v(7);
  const S turn_rate = v(8), cosine = cos(q(8)), sine = sin(q(8));
  const double floor_share = kSlipBandFloor / static_cast<double>(points_.size());

  Eigen::Matrix<S, 9, 1> out = Eigen::Matrix<S, 9, 1>::Zero();
  Vec3T<S> pull = Vec3T<S>::Zero(), weighted_arm = Vec3T<S>::Zero();
  S moment = S(0.0), bound = S(0.0), weight = S(0.0);
  std::vector<S> weights;
  weights.reserve(points_.size());
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const SupportBed& bed = points_[i].bed;
    const Vec3T<S> p = points_[i].point.cast<S>(), u = drawn_arms_[i].cast<S>();
    const Vec3T<S> arm = u * cosine + up.cross(u) * sine;  // A_i − C − d
    const Vec3T<S> Rp = R * p, at = q.template head<3>() + Rp, moving = v.template head<3>() + omega.cross(Rp);
    const Vec3T<S> anchor_moving = slid_rate + up.cross(arm) * turn_rate;
    const Vec3T<S> e = across(at - centre_.cast<S>() - slid - arm), e_rate = across(moving - anchor_moving);
    const Vec3T<S> F = -e * bed.shear_stiffness - e_rate * bed.shear_damping;
    out.template head<3>() -= F;
    out.template segment<3>(3) -= p.cross(R.transpose() * F);
    const S normal = penaltyForce<S>(S(bed.level) - up.dot(at), -up.dot(moving), bed.law);
    const Vec3T<S> f = e * bed.shear_stiffness;
    pull += f;
    moment += up.dot(arm.cross(f));
    bound += normal * bed.friction;
    weights.push_back(normal * bed.friction + floor_share);
    weight += weights.back();
    weighted_arm += arm * weights.back();
  }
  // The centre of friction c = C + d + c_arm, the moment about it, and the friction's lever ρ.
  const Vec3T<S> c_arm = weighted_arm / weight;
  moment -= up.dot(c_arm.cross(pull));
  S lever = S(0.0);
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const Vec3T<S> u = drawn_arms_[i].cast<S>(), arm = u * cosine + up.cross(u) * sine;
    lever += weights[i] * sqrt((arm - c_arm).squaredNorm() + levers_[i] * levers_[i]);
  }
  lever /= weight;

  Eigen::Matrix<S, 3, 1> g(t1.dot(pull), t2.dot(pull), moment / lever);
  const S size = sqrt(g.squaredNorm() + S(1e-300));
  // The band in which slip engages: (1 − kStickFraction) μN + kSlipBandFloor, so that it does
  // not close as a support unloads.
  const S band = bound * (1.0 - kStickFraction) + kSlipBandFloor, onset = bound + kSlipBandFloor - band;
  Eigen::Matrix<S, 3, 1> slip = Eigen::Matrix<S, 3, 1>::Zero();
  if (valueOf(size) > valueOf(onset)) {
    const Eigen::Matrix<S, 3, 1> direction = g / size;
    S engaged = S(1.0);
    if (valueOf(size) < valueOf(onset + band)) {
      const S t = (size - onset) / band;
      engaged = t * t * (3.0 - 2.0 * t);
    }
    const Vec3T<S> body_at_centre = across(v.template head<3>() + omega.cross(centre_.cast<S>() + slid + c_arm - q.template head<3>()));
    const Eigen::Matrix<S, 3, 1> body_rate(t1.dot(body_at_centre), t2.dot(body_at_centre), lever * up.dot(omega));
    const S along = direction.dot(body_rate);
    const S following = 0.5 * (along + sqrt(along * along + S(kAnchorCreepSpeed * kAnchorCreepSpeed)));
    const S over = size - bound - kSlipBandFloor, width = bound * kCatchUpFraction + kSlipBandFloor;
    S catching = S(0.0);
    if (valueOf(over) > 0.0) catching = valueOf(over) < valueOf(width) ? over * over / (2.0 * width) : over - 0.5 * width;
    slip = direction * (engaged * following + catching / (stiffness_ * kCatchUpTime));
  }
  // ν is the anchor's velocity at c and ρ θ̇: θ̇ = ν₃/ρ, ḋ = ν_lin − θ̇ up × c_arm.
  const S turning = slip(2) / lever;
  const Vec3T<S> sliding = t1 * slip(0) + t2 * slip(1) - up.cross(c_arm) * turning;
  out(6) = v(6) - t1.dot(sliding);
  out(7) = v(7) - t2.dot(sliding);
  out(8) = v(8) - turning;
  return out;
}

void AnchoredSupportElement::residual(const ElementInput& in, double* r) const {
  const bool held = in.rates == ParameterRates::Held;
  Eigen::Map<Local> out(r);
  out = rows<double>(gather(in.q, q_), gather(in.v, v_), held);
  if (!held) out.tail<3>() += kAnchorLag * gather(in.a, v_).tail<3>();
}

void AnchoredSupportElement::jacobian(const ElementInput& in, double cj, double* J) const {
  const bool held = in.rates == ParameterRates::Held;
  forwardTangents<9>(gather(in.q, q_), gather(in.v, v_), [&](const auto& q, const auto& v) { return rows(q, v, held); }, J, J + 81);
  if (!held)
    for (int k = 6; k < 9; ++k) J[81 + k * 9 + k] += cj * kAnchorLag;
}

void AnchoredSupportElement::coordinateJacobian(const ElementInput& in, double* J) const {
  const bool held = in.rates == ParameterRates::Held;
  double Jv[81];
  forwardTangents<9>(gather(in.q, q_), gather(in.v, v_), [&](const auto& q, const auto& v) { return rows(q, v, held); }, J, Jv);
}

void AnchoredSupportElement::mass(const ElementInput&, double* M) const {
  std::fill(M, M + 81, 0.0);
  for (int k = 6; k < 9; ++k) M[k * 9 + k] = kAnchorLag;
}

std::vector<AnchoredSupportElement::PointSlip> AnchoredSupportElement::slips(const Local& q, const Local& v) const {
  const Mat3 R = rotationMatrix<double>(Vec3(q.segment<3>(3)));
  const Vec3 omega = R * Vec3(v.segment<3>(3)), slid = across1_ * q(6) + across2_ * q(7), slid_rate = across1_ * v(6) + across2_ * v(7);
  const auto across = [&](const Vec3& x) -> Vec3 { return x - up_ * up_.dot(x); };
  std::vector<PointSlip> out;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const Vec3 u = drawn_arms_[i], arm = u * std::cos(q(8)) + up_.cross(u) * std::sin(q(8));
    const Vec3 Rp = R * points_[i].point;
    out.push_back({across(Vec3(q.head<3>()) + Rp - centre_ - slid - arm), across(Vec3(v.head<3>()) + omega.cross(Rp)),
                   across(slid_rate + up_.cross(arm) * v(8))});
  }
  return out;
}

double AnchoredSupportElement::potentialEnergy(const ElementInput& in) const {
  const Local q = gather(in.q, q_);
  const std::vector<PointSlip> at = slips(q, Local::Zero());
  double sum = 0.0;
  for (std::size_t i = 0; i < points_.size(); ++i) sum += 0.5 * points_[i].bed.shear_stiffness * at[i].offset.squaredNorm();
  return sum;
}

double AnchoredSupportElement::dissipatedPower(const ElementInput& in) const {
  // P = −(the body rows' force)·v_body − dΦ/dt with Φ = ½ Σ k |e|²: Σ k e·Ȧ + c ė·Ṗ (the normal
  // law's damper not included: the support's SupportElement books it).
  const std::vector<PointSlip> at = slips(gather(in.q, q_), gather(in.v, v_));
  double sum = 0.0;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const SupportBed& bed = points_[i].bed;
    const PointSlip& s = at[i];
    sum += bed.shear_stiffness * s.offset.dot(s.anchor_moving) + bed.shear_damping * (s.moving - s.anchor_moving).dot(s.moving);
  }
  return sum;
}

}  // namespace cranesim
