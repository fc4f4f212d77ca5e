#include "cranesim/model/carriage_tipping.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "cranesim/model/support_elements.hpp"

namespace cranesim {
namespace {

/// Points lying in one line to this fraction of their span (rounding: a carriage's points in one
/// line stay in one line as it turns, to 1e-15 of their span).
constexpr double kInLine = 1e-9;

/// A point carries when its force exceeds this fraction of all the supports carry: a point
/// entering the bed's smoothing band carries a force quadratic in its settlement, and one
/// barely in it (1e-9 of the weight, a Newton iterate past the tipping point) adds no
/// stiffness about the edge the others stand on.
constexpr double kCarrying = 1e-6;

/// What the points span seen along `up`: an area, a line, or one point.
enum class Span { Area, Line, Point };

Span spanSeenFromAbove(const std::vector<Vec3>& points, const Vec3& up) {
  std::vector<Vec3> seen;
  for (const Vec3& p : points) seen.push_back(p - up * up.dot(p));
  const auto farthest = [&](const auto& distance) {
    return *std::max_element(seen.begin(), seen.end(), [&](const Vec3& a, const Vec3& b) { return distance(a) < distance(b); });
  };
  const Vec3 a = seen.front();
  const Vec3 b = farthest([&](const Vec3& p) { return (p - a).norm(); });
  const double span = (b - a).norm();
  if (span == 0.0) return Span::Point;
  const Vec3 along = (b - a) / span;
  const Vec3 c = farthest([&](const Vec3& p) { return (p - a).cross(along).norm(); });
  return (c - a).cross(along).norm() <= kInLine * span ? Span::Line : Span::Area;
}

}  // namespace

std::string carriageTipped(const Model& model, const VecX& q, double t) {
  if (!model.envelope.supports) return {};
  const EnvelopeSupports& supports = *model.envelope.supports;
  const VecX zero = VecX::Zero(model.nv);
  const ElementInput in{q.data(), zero.data(), zero.data(), t, model.gravity};
  const auto elementOf = [&](const EnvelopeSupport& s) -> const SupportElement& {
    return dynamic_cast<const SupportElement&>(*model.elements[static_cast<std::size_t>(s.element)]);
  };
  double carried = 0.0;
  for (const auto* list : {&supports.pads, &supports.tracks})
    for (const EnvelopeSupport& s : *list) carried += elementOf(s).contactForce(in);
  std::vector<Vec3> carrying;
  std::string carriers;
  for (const auto* list : {&supports.pads, &supports.tracks})
    for (const EnvelopeSupport& s : *list) {
      const SupportElement& element = elementOf(s);
      const std::vector<double> forces = element.pointForces(in);
      const std::vector<Vec3> positions = element.pointPositions(in);
      std::size_t count = 0;
      for (std::size_t k = 0; k < forces.size(); ++k)
        if (forces[k] > kCarrying * carried) carrying.push_back(positions[k]), ++count;
      if (count == 0) continue;
      carriers += carriers.empty() ? "" : ", ";
      carriers += s.length > 0.0 && count < forces.size()
                      ? fmt::format("{} ({:.3g} m of its {:.3g} m)", s.name, s.length * static_cast<double>(count) / static_cast<double>(forces.size()), s.length)
                      : s.name;
    }
  if (carrying.empty()) return fmt::format("the carriage '{}' has lifted off: none of its supports carries", supports.body);
  const Span span = spanSeenFromAbove(carrying, model.envelope.up);
  if (span == Span::Area) return {};
  return fmt::format("the carriage '{}' has tipped: the supports that carry ({}) stand {} seen from above, {} it rests on with "
                     "the supports' resultant on it or beyond",
                     supports.body, carriers, span == Span::Line ? "in one line" : "at one point", span == Span::Line ? "an edge" : "a corner");
}

}  // namespace cranesim
