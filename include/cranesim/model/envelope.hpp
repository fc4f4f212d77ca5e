#pragma once
// What a run checks to stay within the crane's physical envelope, compiled from the scene
// (model/compile_contacts.cpp) and checked at every output sample (crane/envelope_monitor.hpp):
// ropes against their breaking force, the boom against its angle limit and its backstop, parts
// against the ground's surface, the supports' pads and tracks against the soil's allowable
// pressure and the carriage's stability.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "cranesim/math/types.hpp"

namespace cranesim {

struct EnvelopeRope {
  std::string name;
  double breaking_force = 0.0;  // N
  std::vector<int> elements;    // its rope elements
};

/// The boom's angle: the line from the foot hinge's joint to the head joint above the
/// horizontal, in degrees, measured on past the vertical (up to 180°, a boom lying backwards):
/// `forward` is the boom's drawn horizontal direction in the superstructure joint's axes (the
/// slewing constraint's joint on the turning side), which turns with the crane.
struct EnvelopeBoom {
  int foot_joint = -1, head_joint = -1, superstructure_joint = -1;
  Vec3 forward = Vec3::UnitX();
  double limit_deg = 90.0;
  int backstop_element = -1;  // −1: none
  double backstop_angle_deg = 0.0;
};

/// The parts that rest on the ground (a body, a member) and their contact elements.
struct GroundContactPart {
  std::string name;
  std::vector<int> elements;
};

/// One support of the crane's carriage (model/support_elements.hpp): a pad, or a track whose
/// points are its stretches' middles in order from its `from` joint to its `to` joint.
struct EnvelopeSupport {
  std::string name;
  double bearing_area = 0.0;  // m² under each point: the pad's area, or a stretch's width × length
  double length = 0.0;        // m: a track's length; 0 for a pad
  std::vector<Vec3> outline;  // in the body's axes: the pad's centre, or the track's two ends
  int element = -1;           // the element that carries all its points
  int anchor = -1;            // the node its bed slides by (model/anchored_support_element.hpp)
};

/// The carriage's supports on the ground and the pressure the soil allows.
struct EnvelopeSupports {
  std::string body;
  int node = -1;
  double allowable_pressure = 0.0;  // Pa
  std::vector<EnvelopeSupport> pads, tracks;
};

struct Envelope {
  std::vector<EnvelopeRope> ropes;
  std::optional<EnvelopeBoom> boom;
  /// The ground's surface: its height along `up`; the nodes resting on it through contacts.
  std::optional<double> ground_height;
  Vec3 up = Vec3::UnitZ();
  std::vector<GroundContactPart> ground_contacts;
  std::vector<bool> node_in_contact;  // per node
  std::optional<EnvelopeSupports> supports;
};

/// The boom angle (EnvelopeBoom) from the foot and head positions, `up`, and the boom's forward
/// direction now; in degrees: the elevation of the boom's line while its head is forward of the
/// foot, 180° minus it once the head has passed over to the back.
inline double boomAngle(const Vec3& foot, const Vec3& head, const Vec3& up, const Vec3& forward) {
  const Vec3 boom = head - foot;
  const double rise = std::asin(std::clamp(boom.dot(up) / boom.norm(), -1.0, 1.0)) * 180.0 / std::numbers::pi;
  return boom.dot(forward) >= 0.0 ? rise : 180.0 - rise;
}

}  // namespace cranesim
