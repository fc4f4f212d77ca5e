#include "cranesim/crane/support_statics.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace cranesim {
namespace {

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

/// The convex hull, counter-clockwise (Andrew's monotone chain).
std::vector<Eigen::Vector2d> convexHull(std::vector<Eigen::Vector2d> points) {
  std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  std::vector<Eigen::Vector2d> hull(2 * points.size());
  std::size_t k = 0;
  for (int pass = 0; pass < 2; ++pass) {
    const std::size_t start = k;
    for (std::size_t n = 0; n < points.size(); ++n) {
      const auto& p = pass == 0 ? points[n] : points[points.size() - 1 - n];
      while (k >= start + 2 && cross(hull[k - 1] - hull[k - 2], p - hull[k - 2]) <= 0.0) --k;
      hull[k++] = p;
    }
    --k;
  }
  hull.resize(k);
  return hull;
}

/// The distance of `point` inside the edge a → b of a counter-clockwise polygon (< 0 outside it).
double insideEdge(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& point) {
  return cross(b - a, point - a) / (b - a).norm();
}

std::vector<Eigen::Vector2d> supportPolygon(const std::vector<Eigen::Vector2d>& supports) {
  std::vector<Eigen::Vector2d> hull = convexHull(supports);
  if (hull.size() < 3) throw std::invalid_argument("the supports span no polygon");
  return hull;
}

}  // namespace

std::vector<double> rigidPlatePadForces(const std::vector<PadSpring>& pads, double weight,
                                        const Eigen::Vector2d& resultant) {
  std::vector<bool> down(pads.size(), true);
  std::vector<double> forces(pads.size(), 0.0);
  for (std::size_t round = 0; round <= pads.size(); ++round) {
    // Σ k_i·w_i·(1, x_i, y_i) = W·(1, x_c, y_c) with w_i = a + b·x_i + c·y_i.
    Eigen::Matrix3d stiffness = Eigen::Matrix3d::Zero();
    for (std::size_t i = 0; i < pads.size(); ++i) {
      if (!down[i]) continue;
      const Eigen::Vector3d row(1.0, pads[i].position.x(), pads[i].position.y());
      stiffness += pads[i].stiffness * row * row.transpose();
    }
    const Eigen::Vector3d load(weight, weight * resultant.x(), weight * resultant.y());
    const Eigen::Vector3d plane = stiffness.completeOrthogonalDecomposition().solve(load);
    bool changed = false;
    for (std::size_t i = 0; i < pads.size(); ++i) {
      const double w = plane.dot(Eigen::Vector3d(1.0, pads[i].position.x(), pads[i].position.y()));
      forces[i] = down[i] ? pads[i].stiffness * w : 0.0;
      if (down[i] && w < 0.0) {
        down[i] = false;
        changed = true;
      }
    }
    if (!changed) {
      double carried = 0.0;
      for (const double f : forces) carried += f;
      if (std::abs(carried - weight) > 1e-9 * weight)
        throw std::runtime_error("the resultant lies outside the pads' polygon: the carriage tips");
      return forces;
    }
  }
  throw std::runtime_error("the resultant lies outside the pads' polygon: the carriage tips");
}

TrackPressure rigidTrackPressure(double force, double eccentricity, double length, double width) {
  const double e = std::abs(eccentricity);
  const double towards = eccentricity < 0.0 ? -1.0 : 1.0;
  if (e <= length / 6.0)
    return {force / (width * length) * (1.0 + 6.0 * e / length), towards * length / 2.0, length};
  const double contact = 3.0 * (length / 2.0 - e);
  return {2.0 * force / (width * contact), towards * length / 2.0, contact};
}

double rigidTrackPressureAt(double force, double eccentricity, double length, double width,
                            double position) {
  const double e = std::abs(eccentricity);
  const double s = eccentricity < 0.0 ? -position : position;  // along the eccentricity
  if (e <= length / 6.0) return force / (width * length) * (1.0 + 12.0 * e * s / (length * length));
  const TrackPressure p = rigidTrackPressure(force, e, length, width);
  const double from_end = length / 2.0 - s;  // the triangle falls to 0 at contact_length
  return std::max(0.0, p.peak * (1.0 - from_end / p.contact_length));
}

TippingLine tippingLine(const std::vector<Eigen::Vector2d>& supports, double weight,
                        const Eigen::Vector2d& resultant) {
  const std::vector<Eigen::Vector2d> hull = supportPolygon(supports);
  TippingLine nearest;
  double nearest_distance = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2d& a = hull[i];
    const Eigen::Vector2d& b = hull[(i + 1) % hull.size()];
    const double inside = insideEdge(a, b, resultant);
    if (inside < nearest_distance) {
      nearest_distance = inside;
      nearest = {a, b, weight * inside};
    }
  }
  return nearest;
}

double tippingForce(const std::vector<Eigen::Vector2d>& supports, double weight,
                    const Eigen::Vector2d& resultant, const Eigen::Vector2d& load) {
  const std::vector<Eigen::Vector2d> hull = supportPolygon(supports);
  double force = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2d& a = hull[i];
    const Eigen::Vector2d& b = hull[(i + 1) % hull.size()];
    const double resultant_inside = insideEdge(a, b, resultant), load_inside = insideEdge(a, b, load);
    if (resultant_inside < 0.0) return 0.0;  // it tips already
    if (load_inside < 0.0) force = std::min(force, weight * resultant_inside / -load_inside);
  }
  return force;
}

}  // namespace cranesim
