#pragma once
// Forward-mode automatic differentiation: Dual<T, N> carries a value and its derivatives in N
// directions, a fixed-size vector (no heap allocation). Nesting Dual<Dual<double, N>, M> gives
// second derivatives: the constraints' small function of their dot products and time
// (assembly/constraint_second_derivatives.hpp) and the tests' reference for their closed form.
//
// Every operation evaluates at once into a plain Dual: no expression templates. Eigen's
// AutoDiffScalar, which this replaces with the same interface (value(), derivatives()), builds
// an expression type per operation; inside Eigen's own matrix expressions these types nest
// deeply, which made the element kernels the slowest code of the project to compile and their
// Jacobians copy-bound at run time.
//
// Arithmetic mixes a Dual<T, N> with T and with plain numbers; comparisons compare values
// (the kernels branch on values only, never on derivative parts).

#include <cmath>
#include <type_traits>

#include "cranesim/math/types.hpp"

namespace cranesim {

template <class T, int N> class Dual;

/// A factor that combines with Dual<T, N> without a conversion: T itself, or a plain number.
template <class U, class T>
concept DualFactor = std::is_same_v<U, T> || std::is_arithmetic_v<U>;

template <class T, int N> class Dual {
 public:
  using Derivatives = Eigen::Matrix<T, N, 1>;

  /// Uninitialised, as Eigen's scalars (Eigen writes every coefficient it creates).
  Dual() = default;
  Dual(const T& value) : value_(value), derivatives_(Derivatives::Zero()) {}
  template <class A>
    requires(std::is_arithmetic_v<A> && !std::is_same_v<T, double>)
  Dual(const A& value) : value_(value), derivatives_(Derivatives::Zero()) {}
  Dual(const T& value, const Derivatives& derivatives) : value_(value), derivatives_(derivatives) {}

  const T& value() const { return value_; }
  T& value() { return value_; }
  const Derivatives& derivatives() const { return derivatives_; }
  Derivatives& derivatives() { return derivatives_; }

  Dual& operator+=(const Dual& b) {
    value_ += b.value_;
    for (int k = 0; k < N; ++k) derivatives_(k) += b.derivatives_(k);
    return *this;
  }
  Dual& operator-=(const Dual& b) {
    value_ -= b.value_;
    for (int k = 0; k < N; ++k) derivatives_(k) -= b.derivatives_(k);
    return *this;
  }
  Dual& operator*=(const Dual& b) { return *this = *this * b; }
  Dual& operator/=(const Dual& b) { return *this = *this / b; }
  template <DualFactor<T> U> Dual& operator+=(const U& b) {
    value_ += b;
    return *this;
  }
  template <DualFactor<T> U> Dual& operator-=(const U& b) {
    value_ -= b;
    return *this;
  }
  template <DualFactor<T> U> Dual& operator*=(const U& b) {
    value_ *= b;
    for (int k = 0; k < N; ++k) derivatives_(k) *= b;
    return *this;
  }
  template <DualFactor<T> U> Dual& operator/=(const U& b) { return *this *= T(1.0) / b; }

  friend Dual operator-(const Dual& a) {
    Dual r;
    r.value_ = -a.value_;
    for (int k = 0; k < N; ++k) r.derivatives_(k) = -a.derivatives_(k);
    return r;
  }
  friend Dual operator+(const Dual& a) { return a; }

  friend Dual operator+(const Dual& a, const Dual& b) {
    Dual r;
    r.value_ = a.value_ + b.value_;
    for (int k = 0; k < N; ++k) r.derivatives_(k) = a.derivatives_(k) + b.derivatives_(k);
    return r;
  }
  friend Dual operator-(const Dual& a, const Dual& b) {
    Dual r;
    r.value_ = a.value_ - b.value_;
    for (int k = 0; k < N; ++k) r.derivatives_(k) = a.derivatives_(k) - b.derivatives_(k);
    return r;
  }
  friend Dual operator*(const Dual& a, const Dual& b) {
    Dual r;
    r.value_ = a.value_ * b.value_;
    for (int k = 0; k < N; ++k) r.derivatives_(k) = a.derivatives_(k) * b.value_ + a.value_ * b.derivatives_(k);
    return r;
  }
  /// (a/b)' = (a' − (a/b) b') / b.
  friend Dual operator/(const Dual& a, const Dual& b) {
    Dual r;
    const T inverse = T(1.0) / b.value_;
    r.value_ = a.value_ * inverse;
    for (int k = 0; k < N; ++k) r.derivatives_(k) = (a.derivatives_(k) - r.value_ * b.derivatives_(k)) * inverse;
    return r;
  }

  template <DualFactor<T> U> friend Dual operator+(const Dual& a, const U& b) {
    Dual r = a;
    r.value_ += b;
    return r;
  }
  template <DualFactor<T> U> friend Dual operator+(const U& a, const Dual& b) { return b + a; }
  template <DualFactor<T> U> friend Dual operator-(const Dual& a, const U& b) {
    Dual r = a;
    r.value_ -= b;
    return r;
  }
  template <DualFactor<T> U> friend Dual operator-(const U& a, const Dual& b) {
    Dual r;
    r.value_ = a - b.value_;
    for (int k = 0; k < N; ++k) r.derivatives_(k) = -b.derivatives_(k);
    return r;
  }
  template <DualFactor<T> U> friend Dual operator*(const Dual& a, const U& b) {
    Dual r;
    r.value_ = a.value_ * b;
    for (int k = 0; k < N; ++k) r.derivatives_(k) = a.derivatives_(k) * b;
    return r;
  }
  template <DualFactor<T> U> friend Dual operator*(const U& a, const Dual& b) { return b * a; }
  template <DualFactor<T> U> friend Dual operator/(const Dual& a, const U& b) { return a * (T(1.0) / b); }
  /// (a/b)' = −(a/b) b' / b.
  template <DualFactor<T> U> friend Dual operator/(const U& a, const Dual& b) {
    Dual r;
    const T inverse = T(1.0) / b.value_;
    r.value_ = a * inverse;
    for (int k = 0; k < N; ++k) r.derivatives_(k) = -(r.value_ * inverse) * b.derivatives_(k);
    return r;
  }

  friend bool operator<(const Dual& a, const Dual& b) { return a.value_ < b.value_; }
  friend bool operator>(const Dual& a, const Dual& b) { return a.value_ > b.value_; }
  friend bool operator<=(const Dual& a, const Dual& b) { return a.value_ <= b.value_; }
  friend bool operator>=(const Dual& a, const Dual& b) { return a.value_ >= b.value_; }
  friend bool operator==(const Dual& a, const Dual& b) { return a.value_ == b.value_; }
  friend bool operator!=(const Dual& a, const Dual& b) { return a.value_ != b.value_; }
  template <DualFactor<T> U> friend bool operator<(const Dual& a, const U& b) { return a.value_ < b; }
  template <DualFactor<T> U> friend bool operator>(const Dual& a, const U& b) { return a.value_ > b; }
  template <DualFactor<T> U> friend bool operator<=(const Dual& a, const U& b) { return a.value_ <= b; }
  template <DualFactor<T> U> friend bool operator>=(const Dual& a, const U& b) { return a.value_ >= b; }
  template <DualFactor<T> U> friend bool operator==(const Dual& a, const U& b) { return a.value_ == b; }
  template <DualFactor<T> U> friend bool operator!=(const Dual& a, const U& b) { return a.value_ != b; }
  template <DualFactor<T> U> friend bool operator<(const U& a, const Dual& b) { return a < b.value_; }
  template <DualFactor<T> U> friend bool operator>(const U& a, const Dual& b) { return a > b.value_; }
  template <DualFactor<T> U> friend bool operator<=(const U& a, const Dual& b) { return a <= b.value_; }
  template <DualFactor<T> U> friend bool operator>=(const U& a, const Dual& b) { return a >= b.value_; }

 private:
  T value_;
  Derivatives derivatives_;
};

namespace dual_detail {
/// f(x) for a function f with value `f` and slope `df` at x.value(): the chain rule.
template <class T, int N> Dual<T, N> chain(const Dual<T, N>& x, const T& f, const T& df) {
  Dual<T, N> r;
  r.value() = f;
  for (int k = 0; k < N; ++k) r.derivatives()(k) = df * x.derivatives()(k);
  return r;
}
}  // namespace dual_detail

// Elementary functions, found by argument-dependent lookup beside std's (`using std::sin;`).
template <class T, int N> Dual<T, N> sqrt(const Dual<T, N>& x) {
  using std::sqrt;
  const T s = sqrt(x.value());
  return dual_detail::chain(x, s, T(0.5) / s);
}
template <class T, int N> Dual<T, N> sin(const Dual<T, N>& x) {
  using std::cos, std::sin;
  return dual_detail::chain(x, sin(x.value()), cos(x.value()));
}
template <class T, int N> Dual<T, N> cos(const Dual<T, N>& x) {
  using std::cos, std::sin;
  return dual_detail::chain(x, cos(x.value()), T(-sin(x.value())));
}
template <class T, int N> Dual<T, N> tan(const Dual<T, N>& x) {
  using std::tan;
  const T t = tan(x.value());
  return dual_detail::chain(x, t, T(1.0 + t * t));
}
template <class T, int N> Dual<T, N> asin(const Dual<T, N>& x) {
  using std::asin, std::sqrt;
  return dual_detail::chain(x, asin(x.value()), T(1.0 / sqrt(1.0 - x.value() * x.value())));
}
template <class T, int N> Dual<T, N> acos(const Dual<T, N>& x) {
  using std::acos, std::sqrt;
  return dual_detail::chain(x, acos(x.value()), T(-1.0 / sqrt(1.0 - x.value() * x.value())));
}
template <class T, int N> Dual<T, N> atan(const Dual<T, N>& x) {
  using std::atan;
  return dual_detail::chain(x, atan(x.value()), T(1.0 / (1.0 + x.value() * x.value())));
}
template <class T, int N> Dual<T, N> exp(const Dual<T, N>& x) {
  using std::exp;
  const T e = exp(x.value());
  return dual_detail::chain(x, e, e);
}
template <class T, int N> Dual<T, N> log(const Dual<T, N>& x) {
  using std::log;
  return dual_detail::chain(x, log(x.value()), T(1.0 / x.value()));
}
template <class T, int N> Dual<T, N> tanh(const Dual<T, N>& x) {
  using std::tanh;
  const T t = tanh(x.value());
  return dual_detail::chain(x, t, T(1.0 - t * t));
}
template <class T, int N> Dual<T, N> abs(const Dual<T, N>& x) { return x.value() < 0.0 ? -x : x; }
template <class T, int N> Dual<T, N> pow(const Dual<T, N>& x, double p) {
  using std::pow;
  return dual_detail::chain(x, pow(x.value(), p), T(p * pow(x.value(), p - 1.0)));
}
/// θ = atan2(y, x): θ' = (x y' − y x') / (x² + y²).
template <class T, int N> Dual<T, N> atan2(const Dual<T, N>& y, const Dual<T, N>& x) {
  using std::atan2;
  Dual<T, N> r;
  r.value() = atan2(y.value(), x.value());
  const T inverse = 1.0 / (x.value() * x.value() + y.value() * y.value());
  const T cx = x.value() * inverse, cy = y.value() * inverse;
  for (int k = 0; k < N; ++k) r.derivatives()(k) = cx * y.derivatives()(k) - cy * x.derivatives()(k);
  return r;
}

/// The plain value of a (possibly nested) dual number.
inline double valueOf(double x) { return x; }
template <class T, int N> double valueOf(const Dual<T, N>& x) { return valueOf(x.value()); }

/// A dual number equal to `value` whose derivative is 1 in direction `k` and 0 elsewhere.
template <class T, int N> Dual<T, N> seeded(const T& value, int k) {
  Dual<T, N> x(value);
  x.derivatives()(k) = T(1.0);
  return x;
}

/// A dual number equal to `value` with all derivatives zero.
template <class T, int N> Dual<T, N> constant(const T& value) { return Dual<T, N>(value); }

}  // namespace cranesim

namespace Eigen {

template <class T, int N> struct NumTraits<cranesim::Dual<T, N>> : NumTraits<T> {
  using Real = cranesim::Dual<T, N>;
  using NonInteger = Real;
  using Nested = Real;
  using Literal = typename NumTraits<T>::Literal;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 1,
    ReadCost = (N + 1) * NumTraits<T>::ReadCost,
    AddCost = (N + 1) * NumTraits<T>::AddCost,
    MulCost = (2 * N + 1) * NumTraits<T>::MulCost
  };
};

template <class T, int N, class BinaryOp> struct ScalarBinaryOpTraits<cranesim::Dual<T, N>, T, BinaryOp> {
  using ReturnType = cranesim::Dual<T, N>;
};
template <class T, int N, class BinaryOp> struct ScalarBinaryOpTraits<T, cranesim::Dual<T, N>, BinaryOp> {
  using ReturnType = cranesim::Dual<T, N>;
};
// A nested dual with the plain numbers at its core (Dual<Dual<double, M>, N> and double): products
// with constant matrices cost a third of those with the constants converted to nested duals.
template <class T, int M, int N, class BinaryOp>
struct ScalarBinaryOpTraits<cranesim::Dual<cranesim::Dual<T, M>, N>, T, BinaryOp> {
  using ReturnType = cranesim::Dual<cranesim::Dual<T, M>, N>;
};
template <class T, int M, int N, class BinaryOp>
struct ScalarBinaryOpTraits<T, cranesim::Dual<cranesim::Dual<T, M>, N>, BinaryOp> {
  using ReturnType = cranesim::Dual<cranesim::Dual<T, M>, N>;
};

}  // namespace Eigen

namespace cranesim {

/// ∂f/∂q of f(q) (12 → 12) by forward AD in the 12 coordinate directions; f is called with
/// Eigen::Matrix<Dual<double, 12>, 12, 1>.
template <class Function>
Eigen::Matrix<double, 12, 12> coordinateDerivative(const Eigen::Matrix<double, 12, 1>& q, const Function& f) {
  using D = Dual<double, 12>;
  Eigen::Matrix<D, 12, 1> qd;
  for (int k = 0; k < 12; ++k) qd(k) = seeded<double, 12>(q(k), k);
  const Eigen::Matrix<D, 12, 1> r = f(qd);
  Eigen::Matrix<double, 12, 12> J;
  for (int i = 0; i < 12; ++i) J.row(i) = r(i).derivatives().transpose();
  return J;
}

/// ∂f/∂(q_first … q_first+N−1) of f(q) (12 → 12) by forward AD in those N directions alone, and
/// f(q) itself into `value`; f is called with Eigen::Matrix<Dual<double, N>, 12, 1>.
template <int N, class Function>
Eigen::Matrix<double, 12, N> segmentDerivative(const Eigen::Matrix<double, 12, 1>& q, int first, const Function& f,
                                               Eigen::Matrix<double, 12, 1>& value) {
  using D = Dual<double, N>;
  Eigen::Matrix<D, 12, 1> qd = q.cast<D>();
  for (int k = 0; k < N; ++k) qd(first + k) = seeded<double, N>(q(first + k), k);
  const Eigen::Matrix<D, 12, 1> r = f(qd);
  Eigen::Matrix<double, 12, N> J;
  for (int i = 0; i < 12; ++i) {
    value(i) = r(i).value();
    J.row(i) = r(i).derivatives().transpose();
  }
  return J;
}

}  // namespace cranesim
