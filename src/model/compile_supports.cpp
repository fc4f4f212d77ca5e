#include "compile_supports.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "cranesim/model/anchored_support_element.hpp"
#include "cranesim/model/support_elements.hpp"

namespace cranesim {
namespace {

/// The model's mass as its elements carry it: the kinetic energy's form on a unit velocity along
/// `up` of every node's position.
double modelMass(const Model& model, const Vec3& up) {
  VecX along = VecX::Zero(model.nv);
  for (const Node& n : model.nodes)
    if (n.hasPosition())
      for (int k = 0; k < 3; ++k) along(n.v + k) = up(k);
  const VecX zero = VecX::Zero(model.nv);
  const ElementInput in{model.q0.data(), zero.data(), zero.data(), 0.0, model.gravity};
  double mass = 0.0;
  for (const auto& e : model.elements) {
    const std::vector<int>& at = e->velocityIndices();
    const int n = e->size();
    MatX M(n, n);
    e->mass(in, M.data());
    VecX u(n);
    for (int i = 0; i < n; ++i) u(i) = along(at[i]);
    mass += u.dot(M * u);
  }
  return mass;
}

/// A point of the supported body on the bed: its position in the body's axes and the bed area
/// it bears on.
struct BedPoint {
  Vec3 point;
  double area;
};

/// The supports' outline (pads' centres, tracks' ends) spans a polygon in the ground plane: a
/// carriage on supports in one line has no tipping line across it.
void requireSupportPolygon(const EnvelopeSupports& supports, const Mat3& drawn, const Vec3& up, const SourceLocation& where) {
  std::vector<Vec3> points;
  for (const auto* list : {&supports.pads, &supports.tracks})
    for (const EnvelopeSupport& s : *list)
      for (const Vec3& p : s.outline) points.push_back(drawn * p - up * up.dot(drawn * p));
  const auto farthest = [&](const auto& distance) {
    return *std::max_element(points.begin(), points.end(), [&](const Vec3& a, const Vec3& b) { return distance(a) < distance(b); });
  };
  const Vec3 a = points.front();
  const Vec3 b = farthest([&](const Vec3& p) { return (p - a).norm(); });
  const Vec3 c = farthest([&](const Vec3& p) { return std::abs(up.dot((b - a).cross(p - a))); });
  const double span = (b - a).norm();
  if (std::abs(up.dot((b - a).cross(c - a))) <= 1e-3 * span * span)
    throw SceneError(where, "the supports stand in one line seen from above: place the pads and tracks so that they span an area");
}

}  // namespace

void compileSupports(Model& model, const Scene& scene) {
  const GroundSupportsSpec& spec = *scene.ground_supports;
  const auto node = std::find_if(model.nodes.begin(), model.nodes.end(), [&](const Node& n) { return n.member.empty() && n.name == spec.body; });
  const int body = static_cast<int>(node - model.nodes.begin());
  const auto heldToGround = [&](int joint, int other) { return model.joints[joint].node == body && model.joints[other].node < 0; };
  for (const Constraint& c : model.constraints)
    if (heldToGround(c.joint1, c.joint2) || heldToGround(c.joint2, c.joint1))
      throw SceneError(spec.where_body, fmt::format("constraint '{}' holds the supported body '{}' to the ground: the supports carry a free "
                                                      "body; join the crane to it instead (the slewing ring from it to the superstructure)",
                                                      c.name, spec.body));
  const Vec3& up = model.envelope.up;
  const auto offset = [&](const std::string& joint) { return model.joints[static_cast<std::size_t>(model.findJoint(joint))].offset; };

  EnvelopeSupports supports{spec.body, body, spec.soil.allowable_pressure, {}, {}};
  std::vector<std::vector<BedPoint>> beds;  // per support: pads, then tracks
  for (const SupportPadSpec& pad : spec.pads) {
    supports.pads.push_back({pad.name, pad.area, 0.0, {offset(pad.joint)}});
    beds.push_back({{offset(pad.joint), pad.area}});
  }
  for (const SupportTrackSpec& track : spec.tracks) {
    const Vec3 from = offset(track.from), to = offset(track.to);
    const double length = (to - from).norm(), stretch = length / track.segments;
    if (length < 1e-3)
      throw SceneError(track.where_to, fmt::format("track '{}' runs {:.3g} m from '{}' to '{}': its joints must lie apart along it", track.name,
                                                   length, track.from, track.to));
    supports.tracks.push_back({track.name, track.width * stretch, length, {from, to}});
    std::vector<BedPoint> points;
    for (int k = 0; k < track.segments; ++k) points.push_back({from + (to - from) * ((k + 0.5) / track.segments), track.width * stretch});
    beds.push_back(std::move(points));
  }

  const Frame drawn = model.nodeFrame(model.q0.data(), body);
  requireSupportPolygon(supports, drawn.R, up, spec.where);

  // The drawing stands on the bed settled by the mean settlement s = W / Σk of the weight, so that
  // every spring carries from the start; the springs are smoothed over a fraction of it.
  const double k_s = spec.soil.subgrade_modulus;
  double bed_area = 0.0;
  for (const auto& points : beds)
    for (const BedPoint& p : points) bed_area += p.area;
  const double mass = modelMass(model, up), total_stiffness = k_s * bed_area;
  const double settlement = mass * model.gravity.norm() / total_stiffness;
  const double smoothing = std::max(settlement * spec.smoothing, 1e-9);
  std::size_t support = 0;
  for (auto* list : {&supports.pads, &supports.tracks})
    for (EnvelopeSupport& s : *list) {
      std::vector<SupportPoint> points;
      std::vector<double> footprints;
      for (const BedPoint& p : beds[support++]) {
        const double k = k_s * p.area;
        const double damping = 2.0 * spec.damping_ratio * std::sqrt(k * mass * k / total_stiffness);
        SupportBed bed;
        bed.up = up;
        bed.anchor = drawn.r + drawn.R * p.point;
        bed.level = up.dot(bed.anchor) + settlement + smoothing / 2.0;
        bed.law = {k, damping, smoothing};
        bed.shear_stiffness = spec.shear_ratio * k;
        bed.shear_damping = std::sqrt(spec.shear_ratio) * damping;
        bed.friction = spec.friction;
        points.push_back({p.point, bed});
        footprints.push_back(p.area);
      }
      std::vector<int> q, v;
      for (int i = 0; i < 6; ++i) q.push_back(model.nodes[body].q + i), v.push_back(model.nodes[body].v + i);
      s.element = static_cast<int>(model.elements.size());
      model.elements.push_back(std::make_unique<SupportElement>(points, body, q, v));
      // The support's anchor s = (d₁, d₂, θ): how far its bed has slid and turned from where it
      // was drawn; a node of no member's, kept out of the results' bodies.
      s.anchor = model.addNode(fmt::format("supports.{}.anchor", s.name), NodeKind::Point, "ground.supports");
      for (int i = 0; i < 3; ++i) q.push_back(model.nodes[s.anchor].q + i), v.push_back(model.nodes[s.anchor].v + i);
      model.elements.push_back(std::make_unique<AnchoredSupportElement>(std::move(points), footprints, body, s.anchor, std::move(q), std::move(v)));
    }
  model.envelope.node_in_contact[static_cast<std::size_t>(body)] = true;
  model.envelope.node_in_contact.resize(model.nodes.size(), true);  // the supports' anchors lie on the ground
  model.envelope.supports = std::move(supports);
}

}  // namespace cranesim
