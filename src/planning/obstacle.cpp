#include "cranesim/planning/obstacle.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace cranesim {
namespace {

double cross(const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); }

/// A signed distance and its gradient in the point.
using Distance = DistanceWithGradient;

/// The signed distance of a set extruded vertically, from the signed distance `across` of the
/// point's x–y to the set's cross-section and its height above or below the slab, `along`
/// (negative inside the slab): exact when `across` is, and so is its gradient.
Distance extruded(const Distance& across, const Distance& along) {
  const double a = std::max(across.distance, 0.0), b = std::max(along.distance, 0.0);
  if (a > 0.0 || b > 0.0) {
    const double d = std::hypot(a, b);
    return {d, (a * across.gradient + b * along.gradient) / d};
  }
  return across.distance >= along.distance ? across : along;
}

/// Height outside the slab bottom ≤ z ≤ top (negative inside: minus the distance to its nearer face).
Distance outsideSlab(double z, double bottom, double top) {
  return bottom - z > z - top ? Distance{bottom - z, -Vec3::UnitZ()} : Distance{z - top, Vec3::UnitZ()};
}

/// Signed distance in the plane from p to a convex counter-clockwise polygon, with its gradient.
Distance polygonDistance(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p) {
  double nearest = std::numeric_limits<double>::infinity();
  Eigen::Vector2d away = Eigen::Vector2d::Zero();  // from the nearest point of the boundary to p
  Eigen::Vector2d normal = Eigen::Vector2d::UnitX();  // the nearest edge's outward normal
  bool inside = true;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d edge = polygon[(i + 1) % polygon.size()] - a;
    const double s = std::clamp((p - a).dot(edge) / edge.squaredNorm(), 0.0, 1.0);
    const Eigen::Vector2d offset = p - a - s * edge;
    if (offset.norm() < nearest) nearest = offset.norm(), away = offset, normal = Eigen::Vector2d(edge.y(), -edge.x()).normalized();
    if (cross(edge, p - a) < 0.0) inside = false;
  }
  // The unit vector from the boundary towards p, outwards: the gradient of ±nearest.
  const Eigen::Vector2d outwards = nearest > 0.0 ? Eigen::Vector2d((inside ? -1.0 : 1.0) * away / nearest) : normal;
  return {inside ? -nearest : nearest, Vec3(outwards.x(), outwards.y(), 0.0)};
}

struct PointDistance {
  const Vec3& p;
  Distance operator()(const BoxShape& box) const {
    const double c = box.cos_yaw, s = box.sin_yaw;
    const auto toWorld = [&](const Vec3& v) { return Vec3(c * v.x() - s * v.y(), s * v.x() + c * v.y(), v.z()); };
    const Vec3 r = p - box.centre;
    const Vec3 local(c * r.x() + s * r.y(), -s * r.x() + c * r.y(), r.z());
    const Vec3 side = local.unaryExpr([](double x) { return x < 0.0 ? -1.0 : 1.0; });
    const Vec3 q = local.cwiseAbs() - 0.5 * box.size;
    const Vec3 out = q.cwiseMax(0.0);
    if (const double d = out.norm(); d > 0.0) return {d, toWorld(side.cwiseProduct(out / d))};
    Eigen::Index face = 0;
    const double d = q.maxCoeff(&face);
    return {d, toWorld(side(face) * Vec3::Unit(face))};
  }
  Distance operator()(const CylinderShape& cylinder) const {
    const Eigen::Vector2d radial = (p - cylinder.base).head<2>();
    const Eigen::Vector2d outwards = radial.norm() > 0.0 ? Eigen::Vector2d(radial.normalized()) : Eigen::Vector2d::UnitX();
    return extruded({radial.norm() - cylinder.radius, Vec3(outwards.x(), outwards.y(), 0.0)},
                    outsideSlab(p.z(), cylinder.base.z(), cylinder.base.z() + cylinder.height));
  }
  Distance operator()(const PrismShape& prism) const {
    return extruded(polygonDistance(prism.footprint, p.head<2>()), outsideSlab(p.z(), prism.bottom, prism.top));
  }
};

}  // namespace

DistanceWithGradient signedDistanceWithGradient(const ObstacleShape& shape, const Vec3& p) {
  return std::visit(PointDistance{p}, shape);
}

double signedDistance(const ObstacleShape& shape, const Vec3& p) { return signedDistanceWithGradient(shape, p).distance; }

double signedDistance(const ObstacleShape& shape, const Capsule& part) {
  const auto along = [&](double s) { return signedDistance(shape, Vec3(part.a + s * (part.b - part.a))); };
  constexpr double golden = 0.6180339887498949;  // (√5 − 1) / 2
  double low = 0.0, high = 1.0;
  double x1 = high - golden * (high - low), x2 = low + golden * (high - low);
  double f1 = along(x1), f2 = along(x2);
  while (high - low > kSegmentParameterTolerance) {
    if (f1 <= f2) {
      high = x2, x2 = x1, f2 = f1;
      x1 = high - golden * (high - low), f1 = along(x1);
    } else {
      low = x1, x1 = x2, f1 = f2;
      x2 = low + golden * (high - low), f2 = along(x2);
    }
  }
  // The ends too: a minimum at an end is approached but never sampled by the search.
  return std::min({f1, f2, along(0.0), along(1.0)}) - part.radius;
}

bool makeConvexCounterClockwise(std::vector<Eigen::Vector2d>& polygon) {
  const std::size_t n = polygon.size();
  if (n < 3) return false;
  int positive = 0, negative = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double turn = cross(polygon[(i + 1) % n] - polygon[i], polygon[(i + 2) % n] - polygon[(i + 1) % n]);
    (turn > 0.0 ? positive : negative) += 1;
  }
  if (positive != static_cast<int>(n) && negative != static_cast<int>(n)) return false;
  // Equal turns can still wind twice round (a pentagram): the turning angles must add up to 2π.
  double winding = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d u = polygon[(i + 1) % n] - polygon[i], v = polygon[(i + 2) % n] - polygon[(i + 1) % n];
    winding += std::atan2(cross(u, v), u.dot(v));
  }
  if (std::abs(std::abs(winding) - 2.0 * std::numbers::pi) > 1e-6) return false;
  if (negative == static_cast<int>(n)) std::reverse(polygon.begin(), polygon.end());
  return true;
}

}  // namespace cranesim
