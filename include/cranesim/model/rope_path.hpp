#pragma once
// The path points of a reeved rope (the winch, the sheaves' centres, the dead end) on the nodes
// of the bodies and members they sit on, as the reeved rope elements see them: their positions
// and velocities from the element's local coordinates, and the forces on them gathered back
// onto the nodes as [f, p × Rᵀ f] (the force at the point p on a node's [ṙ, ω]).

#include <array>
#include <vector>

#include "cranesim/math/rotation.hpp"

namespace cranesim {

struct RopePath {
  /// Nodes one rope may run over; their rotations sit on the stack in every call.
  static constexpr int kMaxNodes = 6;
  /// Values of one slot at most (a node's [r, φ], or a sheave's material coordinate): the
  /// elements' tangents are differentiated one slot at a time in as many directions.
  static constexpr int kMaxSlotValues = 7;
  using SlotDual = Dual<double, kMaxSlotValues>;

  /// One of the path's nodes: where its values start in the local vectors, how many, and
  /// whether values 3…5 are a rotation (vector; body angular velocity).
  struct Slot {
    int at = 0;
    int size = 3;
    bool rotates = false;
  };
  /// A path point: `offset` in the axes of the node in `slot`, or with slot < 0 the point itself,
  /// fixed.
  struct Point {
    int slot = -1;
    Vec3 offset = Vec3::Zero();
  };
  template <class S> using Rotations = std::array<Mat3T<S>, kMaxNodes>;

  std::vector<Point> points;
  std::vector<Slot> slots;

  /// The points x = r + R p and their velocities ẋ = ṙ + R (ω × p) (4-5), ω in body axes, from
  /// the local q and v (into x[0 …), xd[0 …)), with the nodes' rotations R.
  template <class S, class Local, class Points>
  void place(const Local& q, const Local& v, Points& x, Points& xd, Rotations<S>& R) const {
    for (std::size_t s = 0; s < slots.size(); ++s)
      if (slots[s].rotates) R[s] = rotationMatrix<S>(Vec3T<S>(q.template segment<3>(slots[s].at + 3)));
    for (std::size_t p = 0; p < points.size(); ++p) {
      const int slot = points[p].slot;
      if (slot < 0) movePoint<S>(p, q, v, 0, R[0], x[p], xd[p]);
      else movePoint<S>(p, q, v, slots[slot].at, R[slot], x[p], xd[p]);
    }
  }

  /// Point p alone, its node's values from `at` on in q and v (elsewhere than its slot's place:
  /// a massive rope's cable sees that one node), its node's rotation into R (untouched for a
  /// point without one).
  template <class S, class Local>
  void placePoint(std::size_t p, const Local& q, const Local& v, int at, Vec3T<S>& x, Vec3T<S>& xd, Mat3T<S>& R) const {
    const int slot = points[p].slot;
    if (slot >= 0 && slots[slot].rotates) R = rotationMatrix<S>(Vec3T<S>(q.template segment<3>(at + 3)));
    movePoint<S>(p, q, v, at, R, x, xd);
  }

  /// Point p's position and velocity, its node's values from `at` on, R its node's rotation.
  template <class S, class Local>
  void movePoint(std::size_t p, const Local& q, const Local& v, int at, const Mat3T<S>& R, Vec3T<S>& x, Vec3T<S>& xd) const {
    const Point& point = points[p];
    if (point.slot < 0) {
      x = point.offset.cast<S>();
      xd.setZero();
      return;
    }
    x = q.template segment<3>(at);
    xd = v.template segment<3>(at);
    if (!slots[point.slot].rotates) return;
    const Vec3T<S> offset = point.offset.cast<S>();
    x += R * offset;
    xd += R * Vec3T<S>(Vec3T<S>(v.template segment<3>(at + 3)).cross(offset));
  }

  /// Adds the forces f[p] on the path points to the local residual r as [f, p × Rᵀ f], R the
  /// nodes' rotations (place).
  template <class S, class Forces, class Local> void gather(const Rotations<S>& R, const Forces& f, Local& r) const {
    for (std::size_t p = 0; p < points.size(); ++p) {
      const int slot = points[p].slot;
      if (slot >= 0) gatherPoint<S>(p, R[slot], f[p], r, slots[slot].at);
    }
  }

  /// The force f on point p added to r from `at` on (placePoint), R its node's rotation.
  template <class S, class Local> void gatherPoint(std::size_t p, const Mat3T<S>& R, const Vec3T<S>& f, Local& r, int at) const {
    const Point& point = points[p];
    if (point.slot < 0) return;
    r.template segment<3>(at) += f;
    if (slots[point.slot].rotates) r.template segment<3>(at + 3) += point.offset.cast<S>().cross(Vec3T<S>(R.transpose() * f));
  }
};

}  // namespace cranesim
