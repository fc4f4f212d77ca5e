#include "cranesim/assembly/constraint_second_derivatives.hpp"

#include "cranesim/math/rotation.hpp"

namespace cranesim {
namespace {

using Mat12 = Eigen::Matrix<double, 12, 12>;
using Vec12 = Eigen::Matrix<double, 12, 1>;
using Mat3x12 = Eigen::Matrix<double, 3, 12>;

/// One joint of the constraint: its node's frame and rate map, and the joint frame on it.
struct JointSide {
  bool moves = false;    // on a node (not the ground)
  bool rotates = false;  // on a frame node
  Mat3 R = Mat3::Identity(), T = Mat3::Identity();
  Vec3 offset = Vec3::Zero();
  Mat3 relative = Mat3::Identity();
  Vec3 rJ = Vec3::Zero();
  Mat3 RJ = Mat3::Identity();
};

JointSide jointSide(const Model& model, int joint, const double* q) {
  const Joint& J = model.joints[joint];
  JointSide s;
  s.offset = J.offset;
  s.relative = J.rotation;
  s.rJ = J.offset;
  s.RJ = J.rotation;
  if (J.node < 0) return s;
  const Node& N = model.nodes[J.node];
  s.moves = true;
  s.rotates = N.hasRotation();
  if (s.rotates) {
    const Vec3 phi(q + N.q + 3);
    s.R = rotationMatrix<double>(phi);
    s.T = angularVelocityMap<double>(phi);
  }
  s.rJ = Vec3(q + N.q) + s.R * s.offset;
  s.RJ = s.R * s.relative;
  return s;
}

/// A vector of the equations, affine in the twists: x = value + J δ. Its rotation R(I + δθ̃) u on
/// side s contributes W_x(y) to the second derivatives, with u = lever[s] and sign[s].
struct VectorJet {
  Vec3 value = Vec3::Zero();
  Mat3x12 J = Mat3x12::Zero();
  bool moves = false;  // J ≠ 0
  Vec3 lever[2] = {Vec3::Zero(), Vec3::Zero()};
  double sign[2] = {0.0, 0.0};
};

VectorJet vectorJet(ConstraintVectorRef ref, const std::array<JointSide, 2>& side) {
  VectorJet x;
  const auto addRotation = [&](int s, const Vec3& u, double sign) {
    if (!side[s].rotates) return;
    x.moves = true;
    x.J.block<3, 3>(0, 6 * s + 3) -= sign * side[s].R * skew<double>(u);
    x.lever[s] = u;
    x.sign[s] = sign;
  };
  switch (ref.kind) {
    case ConstraintVector::Separation:
      x.value = side[0].rJ - side[1].rJ;
      for (int s = 0; s < 2; ++s) {
        const double sign = s == 0 ? 1.0 : -1.0;
        if (!side[s].moves) continue;
        x.moves = true;
        x.J.block<3, 3>(0, 6 * s).diagonal().setConstant(sign);
        addRotation(s, side[s].offset, sign);
      }
      break;
    case ConstraintVector::Axis1:
    case ConstraintVector::Axis2: {
      const int s = ref.kind == ConstraintVector::Axis1 ? 0 : 1;
      x.value = side[s].RJ.col(ref.index);
      addRotation(s, side[s].relative.col(ref.index), 1.0);
      break;
    }
    case ConstraintVector::Inertial: x.value = Vec3::Unit(ref.index); break;
  }
  return x;
}

/// W_x(y) (file comment of the header) added to H.
void addRotationCurvature(const VectorJet& x, const Vec3& y, const std::array<JointSide, 2>& side, Mat12& H) {
  for (int s = 0; s < 2; ++s) {
    if (x.sign[s] == 0.0) continue;
    const Vec3 w = side[s].R.transpose() * y;
    const Vec3& u = x.lever[s];
    Mat3 W = w * u.transpose();
    W.diagonal().array() -= w.dot(u);
    H.block<3, 3>(6 * s + 3, 6 * s + 3) += x.sign[s] * W;
  }
}

/// h(p, t) of every equation with its first and second derivatives in (p, t).
constexpr int kWrapperDirections = kMaxConstraintPrimitives + 1;
constexpr int kWrapperTime = kMaxConstraintPrimitives;
using WrapperDual = Dual<Dual<double, kWrapperDirections>, kWrapperDirections>;

WrapperDual seededTwice(double value, int direction) {
  return seeded<Dual<double, kWrapperDirections>, kWrapperDirections>(seeded<double, kWrapperDirections>(value, direction),
                                                                      direction);
}

}  // namespace

ConstraintSecondDerivatives constraintSecondDerivatives(const Model& model, const Constraint& c, const double* q,
                                                        double t) {
  const std::array<JointSide, 2> side = {jointSide(model, c.joint1, q), jointSide(model, c.joint2, q)};
  const ConstraintLaw law = c.law();
  const ConstraintPrimitives primitives = constraintPrimitives(law);

  // The primitives p_a = x_a · y_a, their twist gradients and second derivatives.
  std::array<Vec12, kMaxConstraintPrimitives> gradient;
  std::array<Mat12, kMaxConstraintPrimitives> curvature;
  WrapperDual prim[kMaxConstraintPrimitives];
  for (int a = 0; a < primitives.count; ++a) {
    const VectorJet x = vectorJet(primitives.x[a], side), y = vectorJet(primitives.y[a], side);
    gradient[a].noalias() = x.J.transpose() * y.value + y.J.transpose() * x.value;
    if (x.moves && y.moves) {
      curvature[a].noalias() = x.J.transpose().lazyProduct(y.J);
      curvature[a] += curvature[a].transpose().eval();
    } else {
      curvature[a].setZero();
    }
    addRotationCurvature(x, y.value, side, curvature[a]);
    addRotationCurvature(y, x.value, side, curvature[a]);
    prim[a] = seededTwice(x.value.dot(y.value), a);
  }
  WrapperDual phi[kMaxConstraintRows];
  constraintFromPrimitives(law, prim, seededTwice(t, kWrapperTime), phi);

  ConstraintSecondDerivatives out;
  out.rows = c.rows;
  out.phi.setZero();
  out.G.setZero();
  out.phi_q.setZero();
  for (int i = 0; i < c.rows; ++i) {
    const double h_t = phi[i].value().derivatives()(kWrapperTime);
    Vec12 g = Vec12::Zero();
    Mat12 H = Mat12::Zero();
    Vec12 g_t = Vec12::Zero();  // ∂G/∂t over the twists: Σ h_at ∇p_a
    for (int a = 0; a < primitives.count; ++a) {
      const double h_a = phi[i].value().derivatives()(a);
      if (h_a != 0.0) {
        g += h_a * gradient[a];
        H += h_a * curvature[a];
      }
      const auto& second = phi[i].derivatives()(a).derivatives();
      for (int b = 0; b < primitives.count; ++b)
        if (second(b) != 0.0) H.noalias() += second(b) * gradient[a] * gradient[b].transpose();
      if (second(kWrapperTime) != 0.0) g_t += second(kWrapperTime) * gradient[a];
    }
    out.phi(i) = phi[i].value().value();
    out.G.row(i).head<12>() = g.transpose();
    out.G(i, kTimeDirection) = h_t;
    ConstraintSecondDerivatives::Mat13& dG = out.dG[i];
    dG.topLeftCorner<12, 12>() = H;
    dG.col(kTimeDirection).head<12>() = g_t;
    dG.row(kTimeDirection).head<12>() = g_t.transpose();  // h_ta = h_at
    dG(kTimeDirection, kTimeDirection) = phi[i].derivatives()(kWrapperTime).derivatives()(kWrapperTime);
    // From the twist a to the coordinates: ∂/∂φ = ∂/∂a T(φ).
    out.phi_q.row(i) = g.transpose();
    for (int s = 0; s < 2; ++s) {
      if (!side[s].rotates) continue;
      dG.middleCols<3>(6 * s + 3) = (dG.middleCols<3>(6 * s + 3) * side[s].T).eval();
      out.phi_q.row(i).segment<3>(6 * s + 3) = (out.phi_q.row(i).segment<3>(6 * s + 3) * side[s].T).eval();
    }
  }
  return out;
}

}  // namespace cranesim
