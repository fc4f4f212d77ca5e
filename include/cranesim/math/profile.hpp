#pragma once
// Time functions for drives and loads: the specified drive functions of Appendix E and
// tabulated cubic splines. Templated on the scalar so drives get exact time derivatives.

#include <cmath>
#include <memory>
#include <variant>
#include <vector>

#include "cranesim/math/autodiff.hpp"
#include "cranesim/math/input_signal.hpp"

namespace cranesim {

struct ConstantProfile {
  double value = 0.0;
};

/// y = value + rate · (t − t_start) for t ≥ t_start, value before.
struct RampProfile {
  double value = 0.0, rate = 0.0, t_start = 0.0;
};

/// Trapezoidal velocity, three stages (E-1..E-5): moves by `distance` from `from` in
/// `duration`, accelerating for `t_accel` and decelerating for `t_decel`.
struct TrapezoidProfile {
  double from = 0.0, distance = 0.0, t_start = 0.0, duration = 1.0, t_accel = 0.1, t_decel = 0.1;
};

/// Cosine step (E-6): from `from` to `to` between t_start and t_end.
struct CosineStepProfile {
  double from = 0.0, to = 0.0, t_start = 0.0, t_end = 1.0;
};

/// Full cosine (E-9): from `base` to `peak` at (t_start + t_end)/2 and back to `base`.
struct CosineFullProfile {
  double base = 0.0, peak = 0.0, t_start = 0.0, t_end = 1.0;
};

/// Hyperbolic tangent transition (E-13) with confidence coefficient λ(c) (Table E-1).
struct TanhProfile {
  double from = 0.0, to = 0.0, t_start = 0.0, t_end = 1.0, lambda = 2.6476;
};

/// How a table passes between its knots: a C² cubic spline, straight lines, or steps that
/// hold each value until the next knot.
enum class Interpolation { Cubic, Linear, Step };

/// A table through (t_i, y_i), held constant outside [t_0, t_n]. `slopes` are the cubic
/// spline's first derivatives at the knots (computed once when the table is read; unused by
/// the linear and step tables).
struct TableProfile {
  std::vector<double> t, y, slopes;
  Interpolation interpolation = Interpolation::Cubic;
};

/// A drive its caller commands while the model runs (math/input_signal.hpp). A scene holds the
/// spec only and reads as the drive's value at rest; a compiled model gives each input its
/// signal, shared by every copy of the profile within that model (Model::inputs).
struct InputProfile {
  InputSpec spec;
  std::shared_ptr<InputSignal> signal;
};

/// λ(c) of Table E-1: atanh(c), the argument at which tanh reaches the confidence c.
inline double tanhConfidenceCoefficient(double confidence) { return std::atanh(confidence); }

/// Knot slopes of the interpolating cubic spline: clamped to zero at both ends when
/// `zero_end_slopes` (smooth start and stop), natural otherwise.
std::vector<double> splineSlopes(const std::vector<double>& t, const std::vector<double>& y,
                                 bool zero_end_slopes);

/// Which one-sided value a profile takes exactly at a breakpoint: the integrator approaches
/// a breakpoint from the left and restarts from it to the right.
enum class Limit { Left, Right };

/// The rates of a parameter that follows a profile (a rope's length): one-sided as Limit, or
/// none: held at its value at t (statics).
enum class ParameterRates { Left, Right, Held };

class Profile {
 public:
  using Kind = std::variant<ConstantProfile, RampProfile, TrapezoidProfile, CosineStepProfile,
                            CosineFullProfile, TanhProfile, TableProfile, InputProfile>;

  Profile() = default;
  explicit Profile(Kind kind, double scale = 1.0) : kind_(std::move(kind)), scale_(scale) {}

  template <class S> S operator()(const S& t, Limit limit = Limit::Left) const {
    return std::visit([&](const auto& p) { return S(scale_ * evaluate(p, t, limit)); }, kind_);
  }

  /// Times where a derivative up to the second jumps; the integrator restarts there.
  std::vector<double> breakpoints() const;

  bool isConstant() const { return std::holds_alternative<ConstantProfile>(kind_); }

  /// The input this profile is, or null.
  const InputProfile* input() const { return std::get_if<InputProfile>(&kind_); }
  InputProfile* input() { return std::get_if<InputProfile>(&kind_); }

  /// Whether the value itself jumps somewhere (a step table).
  bool jumps() const {
    const auto* table = std::get_if<TableProfile>(&kind_);
    return table && table->interpolation == Interpolation::Step;
  }

 private:
  /// Whether time tv lies before breakpoint b, seen from the given side.
  static bool before(double tv, double b, Limit limit) { return limit == Limit::Left ? tv <= b : tv < b; }

  template <class S> static S evaluate(const ConstantProfile& p, const S&, Limit) { return S(p.value); }

  template <class S> static S evaluate(const RampProfile& p, const S& t, Limit limit) {
    if (before(valueOf(t), p.t_start, limit)) return S(p.value);
    return p.value + p.rate * (t - p.t_start);
  }

  template <class S> static S evaluate(const TrapezoidProfile& p, const S& t, Limit limit) {
    const double t1 = p.t_accel, t3 = p.t_decel, t0 = p.duration, t2 = t0 - t1 - t3;
    const double a1 = 2.0 * p.distance / (t1 * (2.0 * t0 - t1 - t3));   // (E-5)
    const double a3 = -2.0 * p.distance / (t3 * (2.0 * t0 - t1 - t3));  // (E-5)
    const double vmax = a1 * t1, s1 = 0.5 * a1 * t1 * t1, s2 = vmax * t2;
    const S tau = t - p.t_start;
    const double tv = valueOf(tau);
    if (before(tv, 0.0, limit)) return S(p.from);
    if (before(tv, t1, limit)) return p.from + 0.5 * a1 * tau * tau;
    if (before(tv, t1 + t2, limit)) return p.from + s1 + vmax * (tau - t1);
    if (before(tv, t0, limit)) {
      const S d = tau - (t1 + t2);
      return p.from + s1 + s2 + vmax * d + 0.5 * a3 * d * d;
    }
    return S(p.from + p.distance);
  }

  template <class S> static S evaluate(const CosineStepProfile& p, const S& t, Limit limit) {
    using std::cos;
    const double tv = valueOf(t);
    if (before(tv, p.t_start, limit)) return S(p.from);
    if (!before(tv, p.t_end, limit)) return S(p.to);
    return 0.5 * (p.from + p.to) +
           0.5 * (p.from - p.to) * cos((t - p.t_start) * std::numbers::pi / (p.t_end - p.t_start));
  }

  template <class S> static S evaluate(const CosineFullProfile& p, const S& t, Limit limit) {
    using std::cos;
    const double tv = valueOf(t);
    if (before(tv, p.t_start, limit) || !before(tv, p.t_end, limit)) return S(p.base);
    return 0.5 * (p.base + p.peak) +
           0.5 * (p.base - p.peak) *
               cos(2.0 * std::numbers::pi * (t - p.t_start) / (p.t_end - p.t_start));
  }

  template <class S> static S evaluate(const TanhProfile& p, const S& t, Limit) {
    using std::tanh;
    return 0.5 * (p.from + p.to) +
           0.5 * (p.to - p.from) *
               tanh(p.lambda * (2.0 * t - (p.t_start + p.t_end)) / (p.t_end - p.t_start));
  }

  /// The signal's value and derivatives at t's value, carried to t's derivative parts by their
  /// Taylor polynomial (exact up to the third derivative).
  template <class S> static S evaluate(const InputProfile& p, const S& t, Limit limit) {
    const double tv = valueOf(t);
    if (!p.signal) return S(p.spec.value);
    const std::array<double, 4> d = p.signal->derivatives(tv, limit == Limit::Left);
    const S h = t - tv;
    return d[0] + h * (d[1] + h * (0.5 * d[2] + h * (d[3] / 6.0)));
  }

  template <class S> static S evaluate(const TableProfile& p, const S& t, Limit limit) {
    const double tv = valueOf(t);
    if (before(tv, p.t.front(), limit)) return S(p.y.front());
    if (!before(tv, p.t.back(), limit)) return S(p.y.back());
    // The interval (t_{i−1}, t_i] seen from the left, [t_{i−1}, t_i) from the right: at an
    // interior knot a linear table's slope and a step table's value are one-sided.
    std::size_t i = 1;
    if (limit == Limit::Left)
      while (p.t[i] < tv) ++i;
    else
      while (p.t[i] <= tv) ++i;
    const double h = p.t[i] - p.t[i - 1];
    const S s = (t - p.t[i - 1]) / h;
    if (p.interpolation == Interpolation::Step) return S(p.y[i - 1]);
    if (p.interpolation == Interpolation::Linear) return p.y[i - 1] + s * (p.y[i] - p.y[i - 1]);
    const S s2 = s * s, s3 = s2 * s;
    // Cubic Hermite basis (A-9..A-11).
    return (2.0 * s3 - 3.0 * s2 + 1.0) * p.y[i - 1] + (s3 - 2.0 * s2 + s) * (h * p.slopes[i - 1]) +
           (-2.0 * s3 + 3.0 * s2) * p.y[i] + (s3 - s2) * (h * p.slopes[i]);
  }

  Kind kind_ = ConstantProfile{};
  double scale_ = 1.0;
};

}  // namespace cranesim
