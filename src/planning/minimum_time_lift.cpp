#include "cranesim/planning/minimum_time_lift.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"  // Ipopt 3.11 headers
#include <IpIpoptApplication.hpp>
#include <IpSolveStatistics.hpp>
#pragma GCC diagnostic pop

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "cranesim/math/autodiff.hpp"
#include "cranesim/planning/ipopt_application.hpp"
#include "final_time_tnlp.hpp"
#include "cranesim/planning/rest_to_rest_path.hpp"

namespace cranesim {
namespace {

// A node's variables: q, q̇, q̈, q⃛ (3 each), α, β, α̇, β̇.
constexpr int kRate = 3, kAcceleration = 6, kJerk = 9, kSwing = 12, kNodeSize = 16;
// The states are the node's variables but the jerk; the pendulum and the drives depend on them only.
constexpr int kStateSize = 13;

/// The node variable of state c.
constexpr int stateVariable(int c) { return c < kJerk ? c : c + 3; }
/// The node variable that is state c's rate; −1 for α̇ and β̇, whose rates the pendulum gives.
constexpr int rateVariable(int c) { return c < kJerk ? c + 3 : c < 11 ? c + 5 : -1; }

/// Ipopt treats |bound| ≥ 1e19 as absent.
double ipoptBound(double bound) { return std::clamp(bound, -1e20, 1e20); }

template <class G> struct NodeEvaluation {
  std::array<G, 3> load;
  std::array<G, 2> swing_acceleration;
  std::array<G, 3> drive, speed, acceleration;
};

/// x(t) as a truncated Taylor series in two nested dual numbers: x + ẋ ε₁ + ẋ ε₂ + ẍ ε₁ε₂, so
/// that a function f(x(t)) carries ḟ in ε₁ and f̈ in ε₁ε₂.
template <class G> Dual<Dual<G, 1>, 1> inMotion(const G& x, const G& rate, const G& acceleration) {
  using Inner = Dual<G, 1>;
  Inner value(x), slope(rate);
  value.derivatives()(0) = rate;
  slope.derivatives()(0) = acceleration;
  Dual<Inner, 1> moving(value);
  moving.derivatives()(0) = slope;
  return moving;
}
/// x(t) to third order: the jet (x, ẋ, ẍ) nested once more with the jet (ẋ, ẍ, x⃛), so that
/// f(x(t)) carries f⃛ in ε₁ε₂ε₃.
template <class G> Dual<Dual<Dual<G, 1>, 1>, 1> inMotion(const G& x, const G& rate, const G& acceleration, const G& jerk) {
  Dual<Dual<Dual<G, 1>, 1>, 1> moving(inMotion(x, rate, acceleration));
  moving.derivatives()(0) = inMotion(rate, acceleration, jerk);
  return moving;
}
template <class G> const G& valueIn(const Dual<Dual<G, 1>, 1>& x) { return x.value().value(); }
template <class G> const G& rateIn(const Dual<Dual<G, 1>, 1>& x) { return x.value().derivatives()(0); }
template <class G> const G& accelerationIn(const Dual<Dual<G, 1>, 1>& x) { return x.derivatives()(0).derivatives()(0); }

/// The load, the pendulum's angular accelerations and the drives at a node whose states are s
/// (in G: double for values, a dual number for their gradient).
template <class G> NodeEvaluation<G> evaluateNode(const LiftKinematics& k, const std::array<G, kStateSize>& s) {
  using std::cos, std::sin;
  using T = Dual<Dual<G, 1>, 1>;
  const T u = inMotion(s[0], s[3], s[6]), v = inMotion(s[1], s[4], s[7]), phi = inMotion(s[2], s[5], s[8]);
  const T alpha = inMotion(s[9], s[11], G(0.0)), beta = inMotion(s[10], s[12], G(0.0));  // α̈, β̈ added below
  const T hoist = k.hoist_length - v;
  const T along = k.along(u, v), across = k.across(u, v);
  // The resting point r = c + R_z(φ)((x, y_m) − c) and the load p = r + ℓ_a ẑ + R_z(φ) D n.
  const Vec3& axis = k.plane.axisPoint();
  const T lever_x = k.end_x.evaluate(u, v) - axis.x();
  const double lever_y = k.plane.planeY() - axis.y();
  const T sa = sin(alpha), ca = cos(alpha), sb = sin(beta), cb = cos(beta), sp = sin(phi), cp = cos(phi);
  const T m_along = along * sa * cb, m_across = across * sb;
  const std::array<T, 3> p = {axis.x() + cp * (lever_x + m_along) - sp * (lever_y + m_across),
                              axis.y() + sp * (lever_x + m_along) + cp * (lever_y + m_across),
                              k.end_z.evaluate(u, v) + along * (1.0 - ca * cb)};
  NodeEvaluation<G> e;
  for (int i = 0; i < 3; ++i) e.load[i] = valueIn(p[i]);

  // (p̈ + g ẑ) in the plane's axes, with α̈ = β̈ = 0, against the directions the rope swings in.
  const G c_phi = cos(s[2]), s_phi = sin(s[2]);
  const G a_along = c_phi * accelerationIn(p[0]) + s_phi * accelerationIn(p[1]);
  const G a_across = -s_phi * accelerationIn(p[0]) + c_phi * accelerationIn(p[1]);
  const G a_up = accelerationIn(p[2]) + k.gravity;
  const G s_a = sin(s[9]), c_a = cos(s[9]), s_b = sin(s[10]), c_b = cos(s[10]);
  const G l_a = valueIn(along), l_c = valueIn(across);
  // e_α = (cos α, 0, sin α), e_β = (−sin α sin β, cos β, cos α sin β); p̈ gains D ∂n/∂α α̈ + D ∂n/∂β β̈.
  const std::array<G, 3> d_alpha = {l_a * c_b * c_a, G(0.0), l_a * c_b * s_a};
  const std::array<G, 3> d_beta = {-l_a * s_a * s_b, l_c * c_b, l_a * c_a * s_b};
  const G m11 = c_a * d_alpha[0] + s_a * d_alpha[2], m12 = c_a * d_beta[0] + s_a * d_beta[2];
  const G m21 = -s_a * s_b * d_alpha[0] + c_b * d_alpha[1] + c_a * s_b * d_alpha[2];
  const G m22 = -s_a * s_b * d_beta[0] + c_b * d_beta[1] + c_a * s_b * d_beta[2];
  const G r1 = -(c_a * a_along + s_a * a_up), r2 = -(-s_a * s_b * a_along + c_b * a_across + c_a * s_b * a_up);
  const G determinant = m11 * m22 - m12 * m21;
  e.swing_acceleration = {(r1 * m22 - m12 * r2) / determinant, (m11 * r2 - m21 * r1) / determinant};

  const std::array<T, 3> drives = {k.luffing.evaluate(u, v), hoist, k.slewing_start + phi};
  for (int d = 0; d < 3; ++d) {
    e.drive[d] = valueIn(drives[d]);
    e.speed[d] = rateIn(drives[d]);
    e.acceleration[d] = accelerationIn(drives[d]);
  }
  return e;
}

/// The luffing rope's jerk d³fl(u, v)/dt³ at a node, split as slope · (u⃛, v⃛) + rest: the slope
/// (∂fl/∂u, ∂fl/∂v) and the rest (the jerk with u⃛ = v⃛ = 0), both functions of the states s.
template <class G> struct LuffingJerk {
  G rest, slope_u, slope_v;
};
template <class G> LuffingJerk<G> luffingJerk(const LiftKinematics& k, const std::array<G, kStateSize>& s) {
  using T = Dual<Dual<Dual<G, 1>, 1>, 1>;
  const T u = inMotion(s[0], s[3], s[6], G(0.0)), v = inMotion(s[1], s[4], s[7], G(0.0));
  const T jerk = k.luffing.evaluate(u, v);
  Dual<G, 2> u_seeded(s[0]), v_seeded(s[1]);
  u_seeded.derivatives()(0) = 1.0;
  v_seeded.derivatives()(1) = 1.0;
  const Dual<G, 2> at = k.luffing.evaluate(u_seeded, v_seeded);
  return {jerk.derivatives()(0).derivatives()(0).derivatives()(0), at.derivatives()(0), at.derivatives()(1)};
}

std::array<double, kStateSize> statesOf(const LiftNode& node) {
  std::array<double, kStateSize> s{};
  for (int i = 0; i < 3; ++i) s[i] = node.q(i), s[3 + i] = node.rate(i), s[6 + i] = node.acceleration(i);
  for (int i = 0; i < 4; ++i) s[9 + i] = node.swing(i);
  return s;
}

LiftNode nodeOf(const double* z) {
  LiftNode node;
  node.q = Eigen::Vector3d(z[0], z[1], z[2]);
  node.rate = Eigen::Vector3d(z + kRate);
  node.acceleration = Eigen::Vector3d(z + kAcceleration);
  node.jerk = Eigen::Vector3d(z + kJerk);
  node.swing = Eigen::Vector4d(z + kSwing);
  return node;
}

void writeNode(const LiftNode& node, double* z) {
  for (int i = 0; i < 3; ++i)
    z[i] = node.q(i), z[kRate + i] = node.rate(i), z[kAcceleration + i] = node.acceleration(i), z[kJerk + i] = node.jerk(i);
  for (int i = 0; i < 4; ++i) z[kSwing + i] = node.swing(i);
}

using Gradient = Dual<double, kStateSize>;

/// A node's states seeded with their gradients.
std::array<Gradient, kStateSize> gradientStates(const double* z) {
  std::array<Gradient, kStateSize> s;
  for (int c = 0; c < kStateSize; ++c) s[c] = seeded<double, kStateSize>(z[stateVariable(c)], c);
  return s;
}

/// The parts' clearances from every obstacle at boom angle u, slewing angle φ and load p,
/// obstacle by obstacle, part by part (LiftPart).
template <class G>
std::vector<G> clearances(const LiftProblem& p, const LiftSampling& sampling, const G& u, const G& phi, const std::array<G, 3>& load) {
  std::vector<G> c;
  for (const Obstacle& o : p.obstacles) {
    const std::array<G, kLiftParts> parts = partClearances(p.crane.body, p.crane.plane, sampling, o.shape, u, phi, load);
    c.insert(c.end(), parts.begin(), parts.end());
  }
  return c;
}

/// The clearances' gradients in a node's states. They depend on u, φ and the load p alone, so
/// they are differentiated in those five and chained with p's gradient: dual numbers of 5
/// instead of 13 through the many point distances.
std::vector<Gradient> clearanceGradients(const LiftProblem& p, const LiftSampling& sampling, const std::array<Gradient, kStateSize>& s,
                                         const std::array<Gradient, 3>& load) {
  using Local = Dual<double, 5>;
  const Local u = seeded<double, 5>(s[0].value(), 0), phi = seeded<double, 5>(s[2].value(), 1);
  std::array<Local, 3> at;
  for (int i = 0; i < 3; ++i) at[i] = seeded<double, 5>(load[i].value(), 2 + i);
  std::vector<Gradient> chained;
  for (const Local& c : clearances(p, sampling, u, phi, at)) {
    Gradient g(c.value());
    g.derivatives() = c.derivatives()(2) * load[0].derivatives() + c.derivatives()(3) * load[1].derivatives() +
                      c.derivatives()(4) * load[2].derivatives();
    g.derivatives()(0) += c.derivatives()(0);
    g.derivatives()(2) += c.derivatives()(1);
    chained.push_back(g);
  }
  return chained;
}

/// A drive's speed or acceleration limited at every node: one ranged constraint each.
struct DriveRow {
  int drive = 0;
  bool acceleration = false;
  double limit = 0.0;
};

class MinimumTimeLiftNlp final : public FinalTimeTnlp {
 public:
  MinimumTimeLiftNlp(const LiftProblem& problem, std::vector<double> start)
      : FinalTimeTnlp(std::move(start)),
        p_(problem),
        N_(problem.intervals),
        sampling_(problem.crane.body, problem.clearance_margin),
        clearance_rows_(static_cast<int>(problem.obstacles.size()) * kLiftParts) {
    for (int d = 0; d < 3; ++d) {
      if (std::isfinite(p_.drives[d].speed)) rows_.push_back({d, false, p_.drives[d].speed});
      if (std::isfinite(p_.drives[d].acceleration)) rows_.push_back({d, true, p_.drives[d].acceleration});
    }
  }

  bool get_nlp_info(Ipopt::Index& n, Ipopt::Index& m, Ipopt::Index& nnz_jac_g, Ipopt::Index& nnz_h_lag,
                    IndexStyleEnum& index_style) override {
    n = finalTimeIndex() + 1;
    m = firstClearanceRow() + clearance_rows_ * (N_ - 1);
    nnz_jac_g = jacobianLayout().total;
    nnz_h_lag = 0;
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Ipopt::Index n, Ipopt::Number* x_l, Ipopt::Number* x_u, Ipopt::Index m, Ipopt::Number* g_l,
                       Ipopt::Number* g_u) override {
    std::fill(x_l, x_l + n, -1e20);
    std::fill(x_u, x_u + n, 1e20);
    for (int k = 0; k <= N_; ++k) {
      double* lower = x_l + kNodeSize * k;
      double* upper = x_u + kNodeSize * k;
      for (int i = 0; i < 3; ++i) {
        lower[i] = p_.q_min(i), upper[i] = p_.q_max(i);
        lower[kJerk + i] = ipoptBound(-p_.jerk_limit(i)), upper[kJerk + i] = ipoptBound(p_.jerk_limit(i));
      }
      for (int i : {kSwing, kSwing + 1}) lower[i] = -1.0, upper[i] = 1.0;  // rad: far beyond any sway of a lift
      if (k == 0 || k == N_) {
        const Eigen::Vector3d& q = k == 0 ? p_.start : p_.end;
        for (int i = 0; i < 3; ++i) lower[i] = upper[i] = q(i);
        for (int i = kRate; i < kJerk; ++i) lower[i] = upper[i] = 0.0;
        for (int i = kSwing; i < kNodeSize; ++i) lower[i] = upper[i] = 0.0;
      }
    }
    x_l[n - 1] = 1e-3;
    std::fill(g_l, g_l + kStateSize * N_, 0.0);
    std::fill(g_u, g_u + kStateSize * N_, 0.0);
    for (int r = kStateSize * N_; r < firstLuffingJerkRow(); ++r) {
      const double limit = rows_[(r - kStateSize * N_) % rows_.size()].limit;
      g_l[r] = -limit, g_u[r] = limit;
    }
    std::fill(g_l + firstLuffingJerkRow(), g_l + firstClearanceRow(), -p_.luffing_jerk_limit);
    std::fill(g_u + firstLuffingJerkRow(), g_u + firstClearanceRow(), p_.luffing_jerk_limit);
    std::fill(g_l + firstClearanceRow(), g_l + m, p_.clearance_margin);
    std::fill(g_u + firstClearanceRow(), g_u + m, 1e20);
    return true;
  }

  bool eval_g(Ipopt::Index, const Ipopt::Number* z, bool, Ipopt::Index, Ipopt::Number* g) override {
    std::vector<NodeEvaluation<double>> nodes(N_ + 1);
    std::vector<std::array<double, kStateSize>> rates(N_ + 1);
    const int drive_rows = static_cast<int>(rows_.size());
    eachNode([&](int k) {
      const double* node = z + kNodeSize * k;
      const std::array<double, kStateSize> states = statesOf(nodeOf(node));
      nodes[k] = evaluateNode(p_.crane, states);
      for (int c = 0; c < kStateSize; ++c) rates[k][c] = rateVariable(c) >= 0 ? node[rateVariable(c)] : nodes[k].swing_acceleration[c - 11];
      double* drive = g + kStateSize * N_ + drive_rows * k;
      for (const DriveRow& row : rows_) *drive++ = row.acceleration ? nodes[k].acceleration[row.drive] : nodes[k].speed[row.drive];
      if (luffingJerkRows() > 0) {
        const LuffingJerk<double> j = luffingJerk(p_.crane, states);
        g[firstLuffingJerkRow() + k] = j.rest + j.slope_u * node[kJerk] + j.slope_v * node[kJerk + 1];
      }
      if (clearance_rows_ > 0 && k > 0 && k < N_) {
        double* clearance = g + firstClearanceRow() + clearance_rows_ * (k - 1);
        for (double c : clearances(p_, sampling_, node[0], node[2], nodes[k].load)) *clearance++ = c;
      }
    });
    const double h = z[finalTimeIndex()] / N_;
    for (int k = 0; k < N_; ++k)
      for (int c = 0; c < kStateSize; ++c) {
        const int i = stateVariable(c);
        g[kStateSize * k + c] = z[kNodeSize * (k + 1) + i] - z[kNodeSize * k + i] - 0.5 * h * (rates[k][c] + rates[k + 1][c]);
      }
    return true;
  }

  bool eval_jac_g(Ipopt::Index, const Ipopt::Number* z, bool, Ipopt::Index, Ipopt::Index, Ipopt::Index* rows,
                  Ipopt::Index* cols, Ipopt::Number* values) override {
    int e = 0;
    if (values == nullptr) {
      for (int k = 0; k < N_; ++k)
        for (int c = 0; c < kStateSize; ++c) {
          for (int i = 0; i < 2 * kNodeSize; ++i) rows[e] = kStateSize * k + c, cols[e++] = kNodeSize * k + i;
          rows[e] = kStateSize * k + c, cols[e++] = finalTimeIndex();
        }
      int r = kStateSize * N_;
      for (int k = 0; k <= N_; ++k)
        for (std::size_t d = 0; d < rows_.size(); ++d, ++r)
          for (int c = 0; c < kStateSize; ++c) rows[e] = r, cols[e++] = kNodeSize * k + stateVariable(c);
      for (int k = 0; k < (luffingJerkRows() > 0 ? N_ + 1 : 0); ++k, ++r) {
        for (int c = 0; c < kStateSize; ++c) rows[e] = r, cols[e++] = kNodeSize * k + stateVariable(c);
        for (int i : {kJerk, kJerk + 1}) rows[e] = r, cols[e++] = kNodeSize * k + i;
      }
      for (int k = 1; k < N_; ++k)
        for (int i = 0; i < clearance_rows_; ++i, ++r)
          for (int c = 0; c < kStateSize; ++c) rows[e] = r, cols[e++] = kNodeSize * k + stateVariable(c);
      return true;
    }
    // Per node: its rates f_c and their gradients in its variables, and the rows of the drives,
    // the luffing rope's jerk and the clearances, written where the structure above puts them.
    std::vector<std::array<std::array<double, kNodeSize>, kStateSize>> rate_gradients(N_ + 1);
    std::vector<std::array<double, kStateSize>> rates(N_ + 1);
    const JacobianLayout layout = jacobianLayout();
    const int drive_rows = static_cast<int>(rows_.size());
    eachNode([&](int k) {
      const double* node = z + kNodeSize * k;
      const std::array<Gradient, kStateSize> states = gradientStates(node);
      const NodeEvaluation<Gradient> evaluation = evaluateNode(p_.crane, states);
      for (int c = 0; c < kStateSize; ++c) {
        auto& gradient = rate_gradients[k][c];
        gradient.fill(0.0);
        if (rateVariable(c) >= 0) {
          gradient[rateVariable(c)] = 1.0;
          rates[k][c] = node[rateVariable(c)];
          continue;
        }
        const Gradient& f = evaluation.swing_acceleration[c - 11];
        rates[k][c] = f.value();
        for (int i = 0; i < kStateSize; ++i) gradient[stateVariable(i)] = f.derivatives()(i);
      }
      double* value = values + layout.drives + drive_rows * kStateSize * k;
      for (const DriveRow& row : rows_) {
        const Gradient& drive = row.acceleration ? evaluation.acceleration[row.drive] : evaluation.speed[row.drive];
        for (int c = 0; c < kStateSize; ++c) *value++ = drive.derivatives()(c);
      }
      if (luffingJerkRows() > 0) {
        const LuffingJerk<Gradient> j = luffingJerk(p_.crane, states);
        value = values + layout.jerks + kJerkRowEntries * k;
        for (int c = 0; c < kStateSize; ++c)
          *value++ = j.rest.derivatives()(c) + j.slope_u.derivatives()(c) * node[kJerk] + j.slope_v.derivatives()(c) * node[kJerk + 1];
        *value++ = j.slope_u.value();
        *value++ = j.slope_v.value();
      }
      if (clearance_rows_ > 0 && k > 0 && k < N_) {
        value = values + layout.clearances + clearance_rows_ * kStateSize * (k - 1);
        for (const Gradient& clearance : clearanceGradients(p_, sampling_, states, evaluation.load))
          for (int c = 0; c < kStateSize; ++c) *value++ = clearance.derivatives()(c);
      }
    });
    const double h = z[finalTimeIndex()] / N_;
    for (int k = 0; k < N_; ++k)
      for (int c = 0; c < kStateSize; ++c) {
        for (int j : {k, k + 1})
          for (int i = 0; i < kNodeSize; ++i)
            values[e++] = (i == stateVariable(c) ? (j == k ? -1.0 : 1.0) : 0.0) - 0.5 * h * rate_gradients[j][c][i];
        values[e++] = -0.5 / N_ * (rates[k][c] + rates[k + 1][c]);
      }
    return true;
  }

 private:
  /// Where each block of rows starts among the Jacobian's entries, in the order eval_jac_g's
  /// structure lists them (the defects first), and their number.
  struct JacobianLayout {
    int drives, jerks, clearances, total;
  };
  JacobianLayout jacobianLayout() const {
    JacobianLayout l;
    l.drives = kStateSize * N_ * (2 * kNodeSize + 1);
    l.jerks = l.drives + static_cast<int>(rows_.size()) * (N_ + 1) * kStateSize;
    l.clearances = l.jerks + luffingJerkRows() * kJerkRowEntries;
    l.total = l.clearances + clearance_rows_ * (N_ - 1) * kStateSize;
    return l;
  }
  /// A luffing-jerk row's entries: the node's states and the jerks of u and v.
  static constexpr int kJerkRowEntries = kStateSize + 2;

  /// Runs `body` on every node 0 … N on TBB's threads. Each node writes only its own results,
  /// so they are the same, bit for bit, on any number of threads.
  template <class Body> void eachNode(const Body& body) const {
    tbb::parallel_for(0, N_ + 1, [&](int k) { body(k); });
  }

  int finalTimeIndex() const { return kNodeSize * (N_ + 1); }
  int firstLuffingJerkRow() const { return kStateSize * N_ + static_cast<int>(rows_.size()) * (N_ + 1); }
  int luffingJerkRows() const { return std::isfinite(p_.luffing_jerk_limit) ? N_ + 1 : 0; }
  int firstClearanceRow() const { return firstLuffingJerkRow() + luffingJerkRows(); }

  const LiftProblem& p_;
  const int N_;
  std::vector<DriveRow> rows_;
  const LiftSampling sampling_;
  const int clearance_rows_;  // per node: obstacles × parts; the nodes between the ends have them
};

/// The guess at N + 1 equally spaced nodes (linear interpolation between its own), then t_f.
std::vector<double> startingPoint(const LiftGuess& guess, int N) {
  std::vector<double> z(kNodeSize * (N + 1) + 1);
  const int M = static_cast<int>(guess.nodes.size()) - 1;
  for (int k = 0; k <= N; ++k) {
    const double position = M * static_cast<double>(k) / N;
    const int j = std::min(static_cast<int>(position), std::max(M - 1, 0));
    const double w = M == 0 ? 0.0 : position - j;
    std::array<double, kNodeSize> a{}, b{};
    writeNode(guess.nodes[j], a.data());
    writeNode(guess.nodes[std::min(j + 1, M)], b.data());
    for (int i = 0; i < kNodeSize; ++i) z[kNodeSize * k + i] = (1.0 - w) * a[i] + w * b[i];
  }
  z.back() = guess.final_time;
  return z;
}

}  // namespace

PendulumState pendulumAt(const LiftKinematics& crane, const LiftNode& node) {
  const NodeEvaluation<double> e = evaluateNode(crane, statesOf(node));
  return {Vec3(e.load[0], e.load[1], e.load[2]), Eigen::Vector2d(e.swing_acceleration[0], e.swing_acceleration[1])};
}

NodeClearance clearanceAt(const LiftProblem& problem, const LiftNode& node) {
  const std::array<double, kStateSize> s = statesOf(node);
  const std::vector<double> c = clearances(problem, LiftSampling(problem.crane.body, problem.clearance_margin), s[0], s[2],
                                           evaluateNode(problem.crane, s).load);
  NodeClearance nearest;
  for (std::size_t i = 0; i < c.size(); ++i)
    if (c[i] < nearest.clearance)
      nearest = {c[i], static_cast<int>(i) / kLiftParts, static_cast<LiftPart>(static_cast<int>(i) % kLiftParts)};
  return nearest;
}

DriveState drivesAt(const LiftKinematics& crane, const LiftNode& node) {
  const NodeEvaluation<double> e = evaluateNode(crane, statesOf(node));
  DriveState d;
  for (int i = 0; i < 3; ++i) d.value(i) = e.drive[i], d.speed(i) = e.speed[i], d.acceleration(i) = e.acceleration[i];
  const LuffingJerk<double> j = luffingJerk(crane, statesOf(node));
  d.jerk = Eigen::Vector3d(j.rest + j.slope_u * node.jerk(0) + j.slope_v * node.jerk(1), -node.jerk(1), node.jerk(2));
  return d;
}

LiftGuess restToRestGuess(const LiftProblem& problem, double duration) {
  LiftGuess guess{duration, {}};
  const Eigen::Vector3d travel = problem.end - problem.start;
  const int N = problem.intervals;
  for (int k = 0; k <= N; ++k) {
    const double tau = static_cast<double>(k) / N;
    LiftNode node;
    node.q = problem.start + travel * restToRest(tau, 0);
    node.rate = travel * restToRest(tau, 1) / duration;
    node.acceleration = travel * restToRest(tau, 2) / std::pow(duration, 2);
    node.jerk = travel * restToRest(tau, 3) / std::pow(duration, 3);
    guess.nodes.push_back(node);
  }
  return guess;
}

LiftGuess waypointGuess(const LiftProblem& problem, const std::vector<Eigen::Vector3d>& waypoints) {
  if (waypoints.size() < 2) throw std::invalid_argument("a waypoint guess needs a start and an end");
  // Each move's least duration at its shape: its drives' speeds scale as 1/T, their accelerations
  // as 1/T² and the coordinates' jerks as 1/T³; their peaks over the move at T = 1 set T.
  std::vector<double> durations;
  for (std::size_t i = 0; i + 1 < waypoints.size(); ++i) {
    const Eigen::Vector3d travel = waypoints[i + 1] - waypoints[i];
    double duration = 0.0;
    for (int j = 1; j < 200; ++j) {
      const double tau = j / 200.0;
      LiftNode node;
      node.q = waypoints[i] + travel * restToRest(tau, 0);
      node.rate = travel * restToRest(tau, 1);
      node.acceleration = travel * restToRest(tau, 2);
      node.jerk = travel * restToRest(tau, 3);
      const DriveState d = drivesAt(problem.crane, node);
      // The luffing rope's jerk through the map: each of its terms (fl_u u⃛, fl_uu u̇ ü, fl_uuu u̇³, …)
      // scales as 1/T³ as well.
      for (int drive = 0; drive < 3; ++drive)
        duration = std::max({duration, std::abs(d.speed(drive)) / problem.drives[drive].speed,
                             std::sqrt(std::abs(d.acceleration(drive)) / problem.drives[drive].acceleration),
                             std::cbrt(std::abs(node.jerk(drive)) / problem.jerk_limit(drive)),
                             drive == kLuffingDrive ? std::cbrt(std::abs(d.jerk(drive)) / problem.luffing_jerk_limit) : 0.0});
    }
    durations.push_back(duration);
  }
  double total = 0.0;
  for (double d : durations) total += d;
  if (!(total > 0.0)) return restToRestGuess(problem, 1.0);

  LiftGuess guess{total, {}};
  const int N = problem.intervals;
  std::size_t move = 0;
  double begun = 0.0;  // when the move began
  for (int k = 0; k <= N; ++k) {
    const double t = total * k / N;
    while (move + 1 < durations.size() && t >= begun + durations[move]) begun += durations[move++];
    const double T = durations[move];
    const double tau = T > 0.0 ? std::min((t - begun) / T, 1.0) : 1.0;
    const Eigen::Vector3d travel = waypoints[move + 1] - waypoints[move];
    LiftNode node;
    node.q = waypoints[move] + travel * restToRest(tau, 0);
    if (T > 0.0) {
      node.rate = travel * restToRest(tau, 1) / T;
      node.acceleration = travel * restToRest(tau, 2) / std::pow(T, 2);
      node.jerk = travel * restToRest(tau, 3) / std::pow(T, 3);
    }
    guess.nodes.push_back(node);
  }
  return guess;
}

LiftTrajectory solveMinimumTimeLift(const LiftProblem& problem, const LiftGuess& guess) {
  if (problem.intervals < 2) throw std::invalid_argument("intervals must be ≥ 2");
  if (guess.nodes.empty() || !(guess.final_time > 0.0)) throw std::invalid_argument("the guess needs nodes and a positive duration");
  for (const DriveBounds& d : problem.drives)
    if (!(d.speed > 0.0) || !(d.acceleration > 0.0)) throw std::invalid_argument("drive limits must be > 0");
  if (!(problem.jerk_limit.array() > 0.0).all() || !(problem.luffing_jerk_limit > 0.0))
    throw std::invalid_argument("jerk limits must be > 0");
  if (!problem.obstacles.empty() && !(problem.crane.body.boom_length > 0.0))
    throw std::invalid_argument("obstacles need the crane's body (a boom of positive length)");

  const auto started = std::chrono::steady_clock::now();
  Ipopt::SmartPtr<Ipopt::IpoptApplication> ipopt =
      ipoptApplication({problem.print_level, problem.tolerance, problem.max_iterations});
  ipopt->Options()->SetStringValue("hessian_approximation", "limited-memory");
  // L-BFGS's low-rank term goes into the KKT matrix that MUMPS factors (2m more rows) instead of
  // being applied by Sherman–Morrison–Woodbury, which costs 2m more solves per factorisation; on
  // these matrices MUMPS' solves took longer than its factorisations. Measured on the shipped
  // lifts: Ipopt's linear algebra 1.9–3.3× faster, the iterates the same on all but one
  // (docs/planning.md).
  ipopt->Options()->SetStringValue("limited_memory_aug_solver", "extended");
  // Around obstacles the soft minima's curvature leaves L-BFGS creeping: t_f settles while the
  // dual infeasibility keeps jumping back above 1e-3. So the solve stops once t_f has changed by
  // less than 1e-5 of itself over 10 iterations, the constraints met to 1e-6 and complementarity
  // to 1e-4, whatever the dual infeasibility (measured on the shipped obstacle lifts: 53–109
  // iterations instead of 64–122, the same t_f to 10 ms).
  if (!problem.obstacles.empty()) {
    auto& options = *ipopt->Options();
    options.SetNumericValue("acceptable_tol", 1e2);  // the overall error includes the dual infeasibility
    options.SetNumericValue("acceptable_constr_viol_tol", 1e-6);
    options.SetNumericValue("acceptable_compl_inf_tol", 1e-4);
    options.SetNumericValue("acceptable_obj_change_tol", 1e-5);
    options.SetIntegerValue("acceptable_iter", 10);
  }
  const Ipopt::SmartPtr<MinimumTimeLiftNlp> nlp = new MinimumTimeLiftNlp(problem, startingPoint(guess, problem.intervals));
  const Ipopt::ApplicationReturnStatus status = ipopt->OptimizeTNLP(Ipopt::SmartPtr<Ipopt::TNLP>(GetRawPtr(nlp)));
  if (status != Ipopt::Solve_Succeeded && status != Ipopt::Solved_To_Acceptable_Level) {
    const std::string what = "Ipopt: minimum-time lift ended with " + ipoptStatusInWords(status);
    if (problem.obstacles.empty() || nlp->solution.empty()) throw std::runtime_error(what);
    NodeClearance closest;
    double when = 0.0;
    for (int k = 1; k < problem.intervals; ++k) {
      const NodeClearance c = clearanceAt(problem, nodeOf(nlp->solution.data() + kNodeSize * k));
      if (c.clearance < closest.clearance) closest = c, when = nlp->solution.back() * k / problem.intervals;
    }
    // Ipopt's constraint tolerance is 1e-4 at most; a violation beyond it is one it could not mend.
    if (closest.clearance < problem.clearance_margin - 1e-3) throw LiftBlocked(what, closest, when);
    throw std::runtime_error(what);
  }

  LiftTrajectory trajectory;
  trajectory.final_time = nlp->solution.back();
  for (int k = 0; k <= problem.intervals; ++k) {
    const LiftNode node = nodeOf(nlp->solution.data() + kNodeSize * k);
    trajectory.t.push_back(trajectory.final_time * k / problem.intervals);
    trajectory.nodes.push_back(node);
    trajectory.load.push_back(pendulumAt(problem.crane, node).load);
    trajectory.drives.push_back(drivesAt(problem.crane, node));
    if (!problem.obstacles.empty()) trajectory.clearance.push_back(clearanceAt(problem, node).clearance);
  }
  trajectory.iterations = ipopt->Statistics()->IterationCount();
  trajectory.solve_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return trajectory;
}

}  // namespace cranesim
