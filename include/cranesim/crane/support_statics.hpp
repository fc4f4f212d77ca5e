#pragma once
// The statics of a rigid carriage on its supports, seen from above (x, y in the ground plane):
//
// - pads: a rigid plate on linear vertical springs (stiffness k_i = k_s·A_i, k_s the soil's
//   modulus of subgrade reaction) that may lift off. The plate settles w(x, y) = a + b·x + c·y;
//   a pad carries k_i·max(w_i, 0). With all pads down this is the linear distribution; with some
//   lifted, the active set is found by repeating the solve without them.
// - a track: a rigid track on a Winkler bed of width b and length L under a force N at an
//   eccentricity e from its middle: the trapezoid p = N/(b·L)·(1 ± 6e/L) while |e| ≤ L/6, the
//   triangle of length 3·(L/2 − |e|) with peak 2N/(3·b·(L/2 − |e|)) beyond.
// - the tipping line: the edge of the support polygon (the convex hull of the supports) nearest
//   the resultant's point; the stability margin is the restoring minus the overturning moment of
//   the vertical resultant about that edge, W·d with d the resultant's distance inside the
//   polygon (negative outside: the crane tips).
// - the tipping force: the vertical force that, added at a point outside the polygon (the hook
//   load), moves the resultant onto the polygon's edge: about each edge e the margin
//   W·d_e + ΔF·d_e(load) vanishes at ΔF = W·d_e / (−d_e(load)); the resultant, moving towards
//   the load, crosses the edge of the smallest such ΔF first.

#include <Eigen/Core>
#include <vector>

namespace cranesim {

struct PadSpring {
  Eigen::Vector2d position;  // m
  double stiffness = 0.0;    // N/m
};

/// The pads' vertical forces (N, ≥ 0) under a vertical load `weight` (N, > 0) acting at
/// `resultant` (m); throws if the resultant lies outside the pads' polygon (no equilibrium).
std::vector<double> rigidPlatePadForces(const std::vector<PadSpring>& pads, double weight,
                                        const Eigen::Vector2d& resultant);

struct TrackPressure {
  double peak = 0.0;          // Pa
  double peak_position = 0.0; // m from the track's middle, towards the eccentricity
  double contact_length = 0.0;// m; the whole length unless the track lifts off
};

/// A rigid track's bed pressure under `force` (N) at `eccentricity` (m) from its middle.
TrackPressure rigidTrackPressure(double force, double eccentricity, double length, double width);
/// The bed pressure (Pa) at `position` (m from the middle) of the same track.
double rigidTrackPressureAt(double force, double eccentricity, double length, double width,
                            double position);

struct TippingLine {
  Eigen::Vector2d from, to;  // the support polygon's edge nearest the resultant
  double margin = 0.0;       // N·m: restoring − overturning moment about it (W·d)
};

/// The tipping line and stability margin of a vertical load `weight` at `resultant` on the
/// polygon spanned by `supports` (at least three points not on one line).
TippingLine tippingLine(const std::vector<Eigen::Vector2d>& supports, double weight,
                        const Eigen::Vector2d& resultant);

/// The vertical force (N) that, added at `load` to a vertical load `weight` acting at
/// `resultant`, brings the resultant onto the edge of the polygon spanned by `supports`: the
/// carriage is about to tip over it. Infinite when `load` lies inside the polygon; 0 when the
/// resultant lies outside it (the carriage tips already).
double tippingForce(const std::vector<Eigen::Vector2d>& supports, double weight,
                    const Eigen::Vector2d& resultant, const Eigen::Vector2d& load);

}  // namespace cranesim
