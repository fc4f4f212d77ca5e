#include "cranesim/assembly/constraint_second_derivatives.hpp"

#include "cranesim/math/rotation.hpp"

namespace cranesim {
namespace {

constexpr int kBlocks = 4;  // [δr₁, δθ₁, δr₂, δθ₂]

bool hasBlock(unsigned blocks, int b) { return (blocks >> b) & 1u; }

/// h(p, t) of every equation with its first (Slope) or first and second (Curvature) derivatives
/// in the primitives' directions and time's (index kMaxConstraintPrimitives); a linear h needs
/// no second derivatives.
constexpr int kHDirections = kMaxConstraintPrimitives + 1;
using Slope = Dual<double, kHDirections>;
using Curvature = Dual<Slope, kHDirections>;

Slope seed(double value, int direction, const Slope*) { return seeded<double, kHDirections>(value, direction); }
Curvature seed(double value, int direction, const Curvature*) {
  return seeded<Slope, kHDirections>(seeded<double, kHDirections>(value, direction), direction);
}

template <class D> void evaluateH(const ConstraintLaw& law, const double* p, int count, double t, D* h) {
  D prim[kMaxConstraintPrimitives];
  for (int a = 0; a < count; ++a) prim[a] = seed(p[a], a, h);
  constraintFromPrimitives(law, prim, seed(t, kMaxConstraintPrimitives, h), h);
}

}  // namespace

ConstraintSecondDerivatives::Side ConstraintSecondDerivatives::side(const Model& model, int joint, const double* q) {
  const Joint& J = model.joints[joint];
  Side s;
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

Vec3 ConstraintSecondDerivatives::Jet::apply(const Vec12& delta) const {
  Vec3 out = Vec3::Zero();
  for (int b = 0; b < kBlocks; ++b)
    if (hasBlock(blocks, b)) out.noalias() += J.block<3, 3>(0, 3 * b) * delta.segment<3>(3 * b);
  return out;
}

void ConstraintSecondDerivatives::Jet::addTransposed(const Vec3& v, Vec12& out) const {
  for (int b = 0; b < kBlocks; ++b)
    if (hasBlock(blocks, b)) out.segment<3>(3 * b).noalias() += J.block<3, 3>(0, 3 * b).transpose() * v;
}

ConstraintSecondDerivatives::Jet ConstraintSecondDerivatives::jet(ConstraintVectorRef ref) const {
  Jet x;
  x.J.setZero();
  x.blocks = 0;
  x.lever[0] = x.lever[1] = Vec3::Zero();
  x.sign[0] = x.sign[1] = 0.0;
  const auto addRotation = [&](int s, const Vec3& u, double sign) {
    if (!side_[s].rotates) return;
    x.J.block<3, 3>(0, 6 * s + 3) = -sign * side_[s].R * skew<double>(u);
    x.blocks |= 1u << (2 * s + 1);
    x.lever[s] = u;
    x.sign[s] = sign;
  };
  switch (ref.kind) {
    case ConstraintVector::Separation:
      x.value = side_[0].rJ - side_[1].rJ;
      for (int s = 0; s < 2; ++s) {
        const double sign = s == 0 ? 1.0 : -1.0;
        if (!side_[s].moves) continue;
        x.J.block<3, 3>(0, 6 * s).diagonal().setConstant(sign);
        x.blocks |= 1u << (2 * s);
        addRotation(s, side_[s].offset, sign);
      }
      break;
    case ConstraintVector::Axis1:
    case ConstraintVector::Axis2: {
      const int s = ref.kind == ConstraintVector::Axis1 ? 0 : 1;
      x.value = side_[s].RJ.col(ref.index);
      addRotation(s, side_[s].relative.col(ref.index), 1.0);
      break;
    }
    case ConstraintVector::Inertial: x.value = Vec3::Unit(ref.index); break;
  }
  return x;
}

template <class Matrix> void ConstraintSecondDerivatives::toCoordinateColumns(Matrix& m) const {
  for (int s = 0; s < 2; ++s)
    if (side_[s].rotates) m.template middleCols<3>(6 * s + 3) = (m.template middleCols<3>(6 * s + 3) * side_[s].T).eval();
}

ConstraintSecondDerivatives::ConstraintSecondDerivatives(const Model& model, const Constraint& c, const double* q,
                                                         double t)
    : rows(c.rows), side_{side(model, c.joint1, q), side(model, c.joint2, q)} {
  const ConstraintLaw law = c.law();
  const ConstraintPrimitives primitives = constraintPrimitives(law);
  primitives_ = primitives.count;
  curved_ = !constraintIsLinear(law);

  // The primitives p_a = x_a · y_a and their twist gradients.
  double p[kMaxConstraintPrimitives];
  for (int a = 0; a < primitives_; ++a) {
    x_[a] = jet(primitives.x[a]);
    y_[a] = jet(primitives.y[a]);
    gradient_[a].setZero();
    x_[a].addTransposed(y_[a].value, gradient_[a]);
    y_[a].addTransposed(x_[a].value, gradient_[a]);
    p[a] = x_[a].value.dot(y_[a].value);
  }
  phi.setZero();
  h1_.setZero();
  if (curved_) {
    Curvature h[kMaxConstraintRows];
    evaluateH(law, p, primitives_, t, h);
    for (int i = 0; i < rows; ++i) {
      phi(i) = h[i].value().value();
      h1_.row(i) = h[i].value().derivatives().transpose();
      for (int a = 0; a < kHDirections; ++a) h2_[i].row(a) = h[i].derivatives()(a).derivatives().transpose();
    }
  } else {
    Slope h[kMaxConstraintRows];
    evaluateH(law, p, primitives_, t, h);
    for (int i = 0; i < rows; ++i) {
      phi(i) = h[i].value();
      h1_.row(i) = h[i].derivatives().transpose();
    }
  }
  G.setZero();
  for (int i = 0; i < rows; ++i) {
    for (int a = 0; a < primitives_; ++a)
      if (h1_(i, a) != 0.0) G.row(i).head<12>() += h1_(i, a) * gradient_[a].transpose();
    G(i, kTimeDirection) = h1_(i, kTime);
  }
  phi_q = G.leftCols<12>();
  toCoordinateColumns(phi_q);
}

void ConstraintSecondDerivatives::addCurvatures(const double* W, Eigen::Ref<Mat12> H) const {
  Mat12 M = Mat12::Zero();  // Σ_a W_a J_xᵀ J_y
  for (int a = 0; a < primitives_; ++a) {
    if (W[a] == 0.0) continue;
    const Jet &x = x_[a], &y = y_[a];
    for (int b = 0; b < kBlocks; ++b) {
      if (!hasBlock(x.blocks, b)) continue;
      const Mat3 Xb = W[a] * x.J.block<3, 3>(0, 3 * b).transpose();
      for (int d = 0; d < kBlocks; ++d)
        if (hasBlock(y.blocks, d)) M.block<3, 3>(3 * b, 3 * d).noalias() += Xb * y.J.block<3, 3>(0, 3 * d);
    }
    // W_x(y) and W_y(x) on the rotation blocks.
    for (const auto& [v, other] : {std::pair{&x, &y}, std::pair{&y, &x}})
      for (int s = 0; s < 2; ++s) {
        if (v->sign[s] == 0.0) continue;
        const double scale = W[a] * v->sign[s];
        const Vec3 w = side_[s].R.transpose() * other->value;
        const Vec3& u = v->lever[s];
        auto B = H.block<3, 3>(6 * s + 3, 6 * s + 3);
        B.noalias() += (scale * w) * u.transpose();
        B.diagonal().array() -= scale * w.dot(u);
      }
  }
  H += M + M.transpose();
}

double ConstraintSecondDerivatives::gradientDot(int a, const Vec13& u) const {
  return a == kTime ? u(kTimeDirection) : gradient_[a].dot(u.head<12>());
}

void ConstraintSecondDerivatives::addGradient(int a, double scale, RowRef row) const {
  if (a == kTime)
    row(kTimeDirection) += scale;
  else
    row.head<12>() += scale * gradient_[a].transpose();
}

ConstraintSecondDerivatives::Mat13 ConstraintSecondDerivatives::weighted(const double* w) const {
  double W[kMaxConstraintPrimitives] = {};
  for (int i = 0; i < rows; ++i)
    for (int a = 0; a < primitives_; ++a) W[a] += w[i] * h1_(i, a);
  Mat13 out = Mat13::Zero();
  addCurvatures(W, out.topLeftCorner<12, 12>());
  if (curved_) {
    HessianH W2 = HessianH::Zero();
    for (int i = 0; i < rows; ++i) W2 += w[i] * h2_[i];
    for (int n = 0; n <= primitives_; ++n)
      for (int m = 0; m <= primitives_; ++m) {
        const int a = hDirection(n), b = hDirection(m);
        if (W2(a, b) == 0.0) continue;
        Eigen::Matrix<double, 1, kConstraintDirections> gb = Eigen::Matrix<double, 1, kConstraintDirections>::Zero();
        addGradient(b, W2(a, b), gb);
        if (a == kTime)
          out.row(kTimeDirection) += gb;
        else
          out.topRows<12>().noalias() += gradient_[a] * gb;
      }
  }
  toCoordinateColumns(out);
  return out;
}

ConstraintSecondDerivatives::Rows13 ConstraintSecondDerivatives::twistContractions(const Vec13& u,
                                                                                   bool over_directions) const {
  const Vec12 ut = u.head<12>();
  Rows13 out = Rows13::Zero();
  for (int a = 0; a < primitives_; ++a) {
    const Jet &x = x_[a], &y = y_[a];
    // uᵀ ∇²p_a or ∇²p_a u: J_yᵀ (J_x u) + J_xᵀ (J_y u) (symmetric), and W_x(y), W_y(x) or their
    // transposes.
    Vec12 c = Vec12::Zero();
    y.addTransposed(x.apply(ut), c);
    x.addTransposed(y.apply(ut), c);
    for (const auto& [v, other] : {std::pair{&x, &y}, std::pair{&y, &x}})
      for (int s = 0; s < 2; ++s) {
        if (v->sign[s] == 0.0) continue;
        const Vec3 w = side_[s].R.transpose() * other->value;
        const Vec3& lever = v->lever[s];
        const Vec3 z = ut.segment<3>(6 * s + 3);
        const Vec3 along = over_directions ? Vec3(z.dot(w) * lever) : Vec3(lever.dot(z) * w);
        c.segment<3>(6 * s + 3) += v->sign[s] * (along - w.dot(lever) * z);
      }
    for (int i = 0; i < rows; ++i)
      if (h1_(i, a) != 0.0) out.row(i).head<12>() += h1_(i, a) * c.transpose();
  }
  // Σ h_ab ĝ_a ĝ_bᵀ contracted over its first index or, transposed, its second.
  if (curved_)
    for (int i = 0; i < rows; ++i)
      for (int n = 0; n <= primitives_; ++n) {
        const int a = hDirection(n);
        const double ua = gradientDot(a, u);
        if (ua == 0.0) continue;
        for (int m = 0; m <= primitives_; ++m) {
          const int b = hDirection(m);
          const double h = over_directions ? h2_[i](a, b) : h2_[i](b, a);
          if (h != 0.0) addGradient(b, h * ua, out.row(i));
        }
      }
  return out;
}

ConstraintSecondDerivatives::Rows13 ConstraintSecondDerivatives::directionContractions(const Vec13& u) const {
  Rows13 out = twistContractions(u, true);
  toCoordinateColumns(out);
  return out;
}

ConstraintSecondDerivatives::Rows13 ConstraintSecondDerivatives::coordinateContractions(const Vec13& u) const {
  Vec13 ua = u;  // in the twists a: δ = [dr, T(φ) dφ]
  for (int s = 0; s < 2; ++s)
    if (side_[s].rotates) ua.segment<3>(6 * s + 3) = side_[s].T * u.segment<3>(6 * s + 3);
  return twistContractions(ua, false);
}

ConstraintSecondDerivatives::Mat13 ConstraintSecondDerivatives::secondDerivative(int i) const {
  double w[kMaxConstraintRows] = {};
  w[i] = 1.0;
  return weighted(w);
}

}  // namespace cranesim
