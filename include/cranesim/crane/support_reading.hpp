#pragma once
// What a crane's supports (model/support_elements.hpp) carry now: each pad's force and pressure,
// each track's peak pressure and where along it, and the carriage's stability seen from above,
// the tipping line and margin of the supports' vertical resultant (crane/support_statics.hpp)
// on the polygon of the pads' centres and the tracks' ends.

#include <string>
#include <vector>

#include "cranesim/crane/support_statics.hpp"
#include "cranesim/model/model.hpp"

namespace cranesim {

struct PadReading {
  double force = 0.0;     // N
  double pressure = 0.0;  // Pa: force over the pad's area
};

struct TrackReading {
  double force = 0.0;          // N
  double peak_pressure = 0.0;  // Pa: the largest of its stretches' force over area
  double peak_at = 0.0;        // m from its `from` end to the middle of that stretch
  double contact_length = 0.0; // m: the stretches that carry
};

struct SupportReading {
  std::vector<PadReading> pads;
  std::vector<TrackReading> tracks;
  double carried = 0.0;  // N: the supports' vertical forces in all
  /// In the ground plane's axes (groundPlaneAxes): the resultant's point and the nearest edge of
  /// the support polygon with the margin W·d about it (negative: the resultant lies outside).
  Eigen::Vector2d resultant = Eigen::Vector2d::Zero();
  TippingLine tipping;
  std::vector<Eigen::Vector2d> polygon;  // the pads' centres and the tracks' ends, in those axes
  /// The largest bed pressure under any pad or track, Pa (0 without supports carrying).
  double peakPressure() const;
};

/// Two unit vectors spanning the ground plane normal to `up`, with up: right-handed; the inertial
/// x and y for up = z.
std::pair<Vec3, Vec3> groundPlaneAxes(const Vec3& up);

/// The supports' reading at q, v (`in`). Without force on any support (the carriage in the air)
/// the resultant is the polygon's centroid and the margin 0.
SupportReading readSupports(const Model& model, const EnvelopeSupports& supports, const ElementInput& in);

/// A table of the reading: each pad's force and pressure, each track's force and peak pressure,
/// against the allowable pressure; the tipping line and margin.
std::string describeSupportReading(const EnvelopeSupports& supports, const SupportReading& reading);

/// A run's extremes in one line: the highest pressure under any support (which, when) and the
/// lowest stability margin (when).
std::string summarizeSupportReadings(const EnvelopeSupports& supports, const std::vector<double>& time,
                                     const std::vector<SupportReading>& readings);

}  // namespace cranesim
