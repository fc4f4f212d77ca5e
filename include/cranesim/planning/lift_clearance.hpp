#pragma once
// The crane's parts as the minimum-time lift keeps them clear of obstacles (docs/planning.md,
// "Lifts that clear obstacles"), and their smooth clearance, the NLP's constraints.
//
// The parts are rigid and placed by the map's controls q = (u, v, φ) and the load's position p:
// the boom the chord from its foot to its head at the boom angle u (the map's boom angle is that
// chord's elevation, so only its length, the start's, and its bending are approximated), a
// capsule of the lattice sections' radius; the hoist rope the segment from the sheave (fixed on
// the head) to p; the load a sphere about p. The slewing angle φ turns them about the slewing axis.
//
// Smoothness: outside a convex set the signed distance d of a point is C¹, its gradient the unit
// vector from the nearest point (exact in double; composed with a point in dual numbers as
// d + ∇d · (x − x₀)). A segment's distance, the least over its points, is not: where it comes
// nearest moves along it and jumps when it lies parallel to a face. So a segment is sampled at n
// points x_i, h apart, and their soft minimum taken,
//   m = d_min − τ log Σ exp(−(d_i − d_min) / τ),   min d_i − τ log n ≤ m ≤ min d_i,
// smooth in the points. Between two samples that both lie ≥ D from a convex set the segment
// stays ≥ √(D² − h²/4) from it (the set's nearest point y has both ends outside the ball of
// radius D about y), so m ≥ √(R² + h²/4) keeps every point of the segment ≥ R from it: the
// clearance of a part of radius r is m − r − (√(R² + h²/4) − R) with R = margin + r.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "cranesim/math/autodiff.hpp"
#include "cranesim/planning/obstacle.hpp"
#include "cranesim/planning/slewing_plane.hpp"

namespace cranesim {

/// The parts the lift keeps clear, in world coordinates at the map's slewing angle (φ = 0).
struct LiftBody {
  Vec3 boom_foot = Vec3::Zero();
  Vec3 boom_out = -Vec3::UnitX();  // horizontal unit vector from the foot towards the head
  double boom_length = 0.0, boom_radius = 0.0;
  /// Where the hoist rope leaves the head, from the head: along the boom's chord and along its
  /// upward normal in the boom's plane, m.
  double sheave_along = 0.0, sheave_up = 0.0;
  double rope_radius = 0.0, load_radius = 0.0;
  /// The longest the rope between the sheave and the load gets, m (sets its samples).
  double rope_longest = 0.0;
};

enum LiftPart { kBoomPart, kRopePart, kLoadPart };
inline constexpr int kLiftParts = 3;
inline const char* liftPartName(int part) { return part == kBoomPart ? "boom" : part == kRopePart ? "hoist rope" : "load"; }

/// The soft minimum's width τ and what sampling may cost at most, m.
inline constexpr double kSoftMinimumWidth = 0.01;
inline constexpr double kSamplingAllowance = 0.01;

/// A segment's samples: as many as keep the allowance √(R² + h²/4) − R ≤ kSamplingAllowance at
/// its longest, R = margin + radius (at least 2), and that allowance at the spacing they give.
struct SegmentSampling {
  int points = 2;
  double allowance = 0.0;
  SegmentSampling() = default;
  SegmentSampling(double longest, double reach) {
    const double spacing = 2.0 * std::sqrt(std::pow(reach + kSamplingAllowance, 2) - reach * reach);
    points = std::max(2, static_cast<int>(std::ceil(longest / spacing)) + 1);
    const double h = longest / (points - 1);
    allowance = std::sqrt(reach * reach + 0.25 * h * h) - reach;
  }
};

template <class G> using LiftPoint = std::array<G, 3>;

/// The signed distance of a point, in G (double, or a dual number carrying its derivatives).
template <class G> G pointDistance(const ObstacleShape& shape, const LiftPoint<G>& x) {
  const Vec3 at(valueOf(x[0]), valueOf(x[1]), valueOf(x[2]));
  const DistanceWithGradient d = signedDistanceWithGradient(shape, at);
  return d.distance + d.gradient.x() * (x[0] - at.x()) + d.gradient.y() * (x[1] - at.y()) + d.gradient.z() * (x[2] - at.z());
}

/// The soft minimum m of the distances of `sampling.points` points from a to b, less the
/// allowance: a lower bound on the segment's distance (see above). Samples farther than 40 τ
/// beyond the nearest weigh < 1e-17 and are left out.
template <class G>
G segmentDistance(const ObstacleShape& shape, const LiftPoint<G>& a, const LiftPoint<G>& b, const SegmentSampling& sampling) {
  const auto sample = [&](int i) {
    const double s = static_cast<double>(i) / (sampling.points - 1);
    return LiftPoint<G>{a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1]), a[2] + s * (b[2] - a[2])};
  };
  const Vec3 from(valueOf(a[0]), valueOf(a[1]), valueOf(a[2])), to(valueOf(b[0]), valueOf(b[1]), valueOf(b[2]));
  const auto distance = [&](int i) { return signedDistance(shape, Vec3(from + (to - from) * i / (sampling.points - 1.0))); };
  // Every 16th sample first. The distance changes by at most the spacing h from sample to sample,
  // so between two of them i, j no sample comes nearer than (d_i + d_j − |j − i| h) / 2; stretches
  // that stay beyond the soft minimum's reach of the nearest so far are left out.
  constexpr int kStride = 16;
  const double h = (to - from).norm() / (sampling.points - 1), reach = 40.0 * kSoftMinimumWidth;
  std::vector<double> d(sampling.points, std::numeric_limits<double>::infinity());
  for (int i = 0; i < sampling.points; i += kStride) d[i] = distance(i);
  d.back() = distance(sampling.points - 1);
  double nearest = *std::min_element(d.begin(), d.end());
  for (int i = 0; i + 1 < sampling.points; i += kStride) {
    const int j = std::min(i + kStride, sampling.points - 1);
    if (0.5 * (d[i] + d[j] - (j - i) * h) > nearest + reach) continue;
    for (int k = i + 1; k < j; ++k) nearest = std::min(nearest, d[k] = distance(k));
  }
  using std::exp, std::log;
  G sum(0.0);
  for (int i = 0; i < sampling.points; ++i)
    if (d[i] - nearest < reach) sum += exp(-(pointDistance(shape, sample(i)) - nearest) / kSoftMinimumWidth);
  return nearest - kSoftMinimumWidth * log(sum) - sampling.allowance;
}

/// A point of the map's plane (at φ = 0) turned by φ about the slewing axis.
template <class G> LiftPoint<G> turnedBy(const SlewingPlane& plane, const LiftPoint<G>& x, const G& phi) {
  using std::cos, std::sin;
  const Vec3& c = plane.axisPoint();
  const G cp = cos(phi), sp = sin(phi), dx = x[0] - c.x(), dy = x[1] - c.y();
  return {c.x() + cp * dx - sp * dy, c.y() + sp * dx + cp * dy, x[2]};
}

/// The boom's foot and head and the rope's sheave at boom angle u (°) and slewing angle φ.
template <class G> struct BoomPoints {
  LiftPoint<G> foot, head, sheave;
};
template <class G> BoomPoints<G> boomPoints(const LiftBody& body, const SlewingPlane& plane, const G& u, const G& phi) {
  using std::cos, std::sin;
  const G angle = u * (std::numbers::pi / 180.0), c = cos(angle), s = sin(angle);
  const Vec3 &f = body.boom_foot, &o = body.boom_out;
  // The chord's direction e = c o + s ẑ and its upward normal in the plane −s o + c ẑ.
  const LiftPoint<G> e = {c * o.x(), c * o.y(), s}, up = {-s * o.x(), -s * o.y(), c};
  LiftPoint<G> head, sheave;
  for (int i = 0; i < 3; ++i) {
    head[i] = f(i) + body.boom_length * e[i];
    sheave[i] = head[i] + body.sheave_along * e[i] + body.sheave_up * up[i];
  }
  const LiftPoint<G> foot = {G(f.x()), G(f.y()), G(f.z())};
  return {turnedBy(plane, foot, phi), turnedBy(plane, head, phi), turnedBy(plane, sheave, phi)};
}

/// How each part is sampled for a clearance margin.
struct LiftSampling {
  SegmentSampling boom, rope;
  LiftSampling() = default;
  LiftSampling(const LiftBody& body, double margin)
      : boom(body.boom_length, margin + body.boom_radius), rope(body.rope_longest, margin + body.rope_radius) {}
};

/// The parts' clearances from one obstacle (indexed by LiftPart), at boom angle u, slewing angle φ
/// and the load at p: the boom's and rope's smoothed as above, the load's exact.
template <class G>
std::array<G, kLiftParts> partClearances(const LiftBody& body, const SlewingPlane& plane, const LiftSampling& sampling,
                                         const ObstacleShape& shape, const G& u, const G& phi, const LiftPoint<G>& p) {
  const BoomPoints<G> boom = boomPoints(body, plane, u, phi);
  std::array<G, kLiftParts> c;
  c[kBoomPart] = segmentDistance(shape, boom.foot, boom.head, sampling.boom) - body.boom_radius;
  c[kRopePart] = segmentDistance(shape, boom.sheave, p, sampling.rope) - body.rope_radius;
  c[kLoadPart] = pointDistance(shape, p) - body.load_radius;
  return c;
}

}  // namespace cranesim
