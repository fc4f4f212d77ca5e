#pragma once
// Whether a run stays within the crane's physical envelope (model/envelope.hpp), recorded at
// every output sample and judged from the records, so that a run restored to an earlier time
// forgets what came after it:
//
// - a rope's largest tension (over its elements and tension points) against its breaking force;
// - the boom angle against the limit of the crane's envelope, and the backstop's moment;
// - the lowest point of every part (a body's origin, a member's nodes) that does not rest on
//   the ground through a contact, against the ground's surface; the contacts' normal forces;
// - the supports' pad and track pressures against the soil's allowable pressure, the
//   carriage's stability margin against 0 (crane/support_reading.hpp), and whether it has
//   tipped: its carrying supports in one line or at one point seen from above, or none carrying
//   (model/carriage_tipping.hpp) — a carriage on an edge, whose margin is 0 only to rounding.
//
// Events say what left the envelope, when first, and how far at worst; touching the backstop
// or the ground is an event too, but one within the envelope.

#include <string>
#include <vector>

#include "cranesim/crane/support_reading.hpp"
#include "cranesim/model/model.hpp"

namespace cranesim {

struct EnvelopeEvent {
  /// "rope overload", "boom past its angle limit", "below ground", "on its backstop", "on the
  /// ground", "over the allowable pressure", "stability margin below zero", "lifted off",
  /// "tipped"
  std::string what;
  std::string part;
  bool leaves_envelope = false;
  double first_time = 0.0;  // s
  double peak_time = 0.0;   // s
  double peak = 0.0;        // N, deg, m (a height) or N·m, as `unit` says
  double limit = 0.0;       // the same unit; for contacts 0
  std::string unit;
  /// A contact's deepest closure while it lasted: the ground's penetration (m), the backstop's
  /// compression (deg).
  double depth = 0.0;
  std::string depth_unit;
  /// A tipped carriage's first tipped sample: which supports carried (model/carriage_tipping.hpp).
  std::string why;
};

/// A named series, one value per sample.
struct EnvelopeSeries {
  std::string name;
  std::vector<double> values;
};

class EnvelopeMonitor {
 public:
  explicit EnvelopeMonitor(const Model& model);

  /// Records the sample at time t, coordinates q and velocities v.
  void sample(double t, const double* q, const double* v);
  /// Forgets the samples from index `kept` on.
  void keep(std::size_t kept);

  /// The events of the samples so far, in the order they began.
  std::vector<EnvelopeEvent> events() const;
  /// Whether the last sample lies outside the envelope (cheap: for stopping a run there).
  bool lastSampleOutside() const { return last_outside_; }
  /// Whether the carriage had tipped at the last sample.
  bool lastSampleTipped() const { return !tipped_.empty() && tipped_.back() > 0.0; }

  const std::vector<double>& time() const { return time_; }
  const std::vector<double>& boomAngle() const { return boom_angle_; }
  const std::vector<double>& backstopMoment() const { return backstop_moment_; }
  const std::vector<double>& backstopCompression() const { return backstop_compression_; }  // deg, ≤ 0 open
  const std::vector<EnvelopeSeries>& ropeTensions() const { return rope_tension_; }   // N, the largest along each rope
  const std::vector<EnvelopeSeries>& lowestPoints() const { return lowest_; }         // m, along up
  const std::vector<EnvelopeSeries>& contactForces() const { return contact_force_; }  // N, each resting part's in all
  const std::vector<EnvelopeSeries>& contactDepths() const { return contact_depth_; }  // m, each resting part's deepest
  const std::vector<SupportReading>& supports() const { return supports_; }             // with ground.supports
  const std::vector<double>& tipped() const { return tipped_; }                          // with ground.supports: 1 tipped, 0 standing
  bool empty() const;

 private:
  const Model& model_;
  std::vector<double> time_, boom_angle_, backstop_moment_, backstop_compression_;
  std::vector<EnvelopeSeries> rope_tension_, lowest_, contact_force_, contact_depth_;
  std::vector<std::vector<int>> part_nodes_;  // per entry of lowest_: its nodes without a contact
  std::vector<SupportReading> supports_;
  std::vector<double> tipped_;
  std::vector<std::string> tipped_why_;  // per sample: model/carriage_tipping.hpp's reason, or empty
  bool last_outside_ = false;
};

/// Whether any of the events leaves the envelope.
bool leavesEnvelope(const std::vector<EnvelopeEvent>& events);

/// One line per event, e.g. "rope overload: hoist_rope 15.1 MN at t = 2.02 s, above its breaking
/// force 13.1 MN (from t = 2.01 s)".
std::string describeEnvelopeEvents(const std::vector<EnvelopeEvent>& events);

}  // namespace cranesim
