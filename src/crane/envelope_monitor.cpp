#include "cranesim/crane/envelope_monitor.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <numbers>

#include "cranesim/model/carriage_tipping.hpp"
#include "cranesim/model/contact_elements.hpp"
#include "cranesim/model/reeved_rope.hpp"

namespace cranesim {
namespace {

/// The largest tension along a rope's elements (its parts, for a reeved rope).
double largestTension(const Model& model, const EnvelopeRope& rope, const ElementInput& in) {
  double largest = 0.0;
  for (const int e : rope.elements) {
    if (const auto* reeved = dynamic_cast<const ReevedRope*>(model.elements[e].get())) {
      double parts[ReevedRope::kMaxParts];
      reeved->partTensions(in, parts);
      largest = std::max(largest, *std::max_element(parts, parts + reeved->parts()));
      continue;
    }
    double points[kTensionPoints];
    model.elements[e]->tensions(in, points);
    largest = std::max(largest, *std::max_element(points, points + kTensionPoints));
  }
  return largest;
}

/// The first sample where `above(value)` holds and the sample of the extreme (`worse`) while it
/// does; none: the series never satisfies it.
template <class Above, class Worse>
std::optional<EnvelopeEvent> eventOf(const std::vector<double>& time, const std::vector<double>& values, Above above, Worse worse) {
  std::optional<EnvelopeEvent> event;
  for (std::size_t s = 0; s < values.size(); ++s) {
    if (!above(values[s])) continue;
    if (!event) {
      event = EnvelopeEvent{};
      event->first_time = event->peak_time = time[s];
      event->peak = values[s];
    } else if (worse(values[s], event->peak)) {
      event->peak_time = time[s];
      event->peak = values[s];
    }
  }
  return event;
}

/// A value with an engineer's prefix: 15.1 MN, 2.9 kN·m.
std::string withUnit(double value, const std::string& unit) {
  if (unit == "deg") return fmt::format("{:.4g}°", value);
  if (unit == "m") return fmt::format("{:.4g} m", value);
  const double a = std::abs(value);
  if (a >= 1e6) return fmt::format("{:.4g} M{}", value / 1e6, unit);
  if (a >= 1e3) return fmt::format("{:.4g} k{}", value / 1e3, unit);
  return fmt::format("{:.4g} {}", value, unit);
}

/// Whether a support presses the soil beyond its allowable pressure, or the margin is negative.
bool supportsOutside(const SupportReading& r, double allowable) {
  const auto over = [&](double pressure) { return pressure > allowable; };
  return r.tipping.margin < 0.0 || std::any_of(r.pads.begin(), r.pads.end(), [&](const PadReading& p) { return over(p.pressure); }) ||
         std::any_of(r.tracks.begin(), r.tracks.end(), [&](const TrackReading& t) { return over(t.peak_pressure); });
}

}  // namespace

EnvelopeMonitor::EnvelopeMonitor(const Model& model) : model_(model) {
  const Envelope& e = model.envelope;
  for (const EnvelopeRope& rope : e.ropes) rope_tension_.push_back({rope.name, {}});
  for (const GroundContactPart& part : e.ground_contacts) contact_force_.push_back({part.name, {}}), contact_depth_.push_back({part.name, {}});
  if (!e.ground_height) return;
  for (std::size_t n = 0; n < model.nodes.size(); ++n) {
    if (e.node_in_contact[n]) continue;
    const std::string part = model.nodes[n].member.empty() ? model.nodes[n].name : model.nodes[n].member;
    auto it = std::find_if(lowest_.begin(), lowest_.end(), [&](const EnvelopeSeries& s) { return s.name == part; });
    if (it == lowest_.end()) {
      lowest_.push_back({part, {}});
      part_nodes_.emplace_back();
      it = lowest_.end() - 1;
    }
    part_nodes_[static_cast<std::size_t>(it - lowest_.begin())].push_back(static_cast<int>(n));
  }
}

bool EnvelopeMonitor::empty() const {
  return rope_tension_.empty() && contact_force_.empty() && lowest_.empty() && !model_.envelope.boom && !model_.envelope.supports;
}

void EnvelopeMonitor::sample(double t, const double* q, const double* v) {
  if (empty()) return;
  const Envelope& e = model_.envelope;
  const ElementInput in{q, v, nullptr, t, model_.gravity};
  time_.push_back(t);
  for (std::size_t r = 0; r < e.ropes.size(); ++r) rope_tension_[r].values.push_back(largestTension(model_, e.ropes[r], in));
  if (const auto& boom = e.boom) {
    const Vec3 forward = model_.jointFrame(q, boom->superstructure_joint).R * boom->forward;
    boom_angle_.push_back(cranesim::boomAngle(model_.jointFrame(q, boom->foot_joint).r, model_.jointFrame(q, boom->head_joint).r, e.up, forward));
    if (boom->backstop_element >= 0) {
      const auto& backstop = dynamic_cast<const ContactElement&>(*model_.elements[boom->backstop_element]);
      backstop_moment_.push_back(backstop.contactForce(in));
      backstop_compression_.push_back(backstop.closure(in) * 180.0 / std::numbers::pi);
    }
  }
  for (std::size_t p = 0; p < e.ground_contacts.size(); ++p) {
    double force = 0.0, depth = -std::numeric_limits<double>::infinity();
    for (const int c : e.ground_contacts[p].elements) {
      const auto& contact = dynamic_cast<const ContactElement&>(*model_.elements[c]);
      force += contact.contactForce(in);
      depth = std::max(depth, contact.closure(in));
    }
    contact_force_[p].values.push_back(force);
    contact_depth_[p].values.push_back(depth);
  }
  for (std::size_t p = 0; p < lowest_.size(); ++p) {
    double lowest = std::numeric_limits<double>::infinity();
    for (const int n : part_nodes_[p]) lowest = std::min(lowest, e.up.dot(model_.nodeFrame(q, n).r));
    lowest_[p].values.push_back(lowest);
  }
  if (const auto& supports = e.supports) {
    supports_.push_back(readSupports(model_, *supports, in));
    tipped_why_.push_back(carriageTipped(model_, Eigen::Map<const VecX>(q, model_.nq), t));
    tipped_.push_back(tipped_why_.back().empty() ? 0.0 : 1.0);
  }
  last_outside_ = false;
  if (e.supports) last_outside_ |= supportsOutside(supports_.back(), e.supports->allowable_pressure) || lastSampleTipped();
  for (std::size_t r = 0; r < e.ropes.size(); ++r) last_outside_ |= rope_tension_[r].values.back() > e.ropes[r].breaking_force;
  if (e.boom) last_outside_ |= boom_angle_.back() > e.boom->limit_deg;
  for (const EnvelopeSeries& s : lowest_) last_outside_ |= s.values.back() < *e.ground_height;
}

void EnvelopeMonitor::keep(std::size_t kept) {
  if (kept >= time_.size()) return;
  time_.resize(kept);
  if (!supports_.empty()) supports_.resize(kept), tipped_.resize(kept), tipped_why_.resize(kept);
  for (auto* series : {&boom_angle_, &backstop_moment_, &backstop_compression_})
    if (!series->empty()) series->resize(kept);
  for (auto* group : {&rope_tension_, &lowest_, &contact_force_, &contact_depth_})
    for (EnvelopeSeries& s : *group) s.values.resize(kept);
}

std::vector<EnvelopeEvent> EnvelopeMonitor::events() const {
  const Envelope& e = model_.envelope;
  const auto larger = [](double a, double b) { return a > b; };
  std::vector<EnvelopeEvent> out;
  const auto add = [&](std::optional<EnvelopeEvent> event, const char* what, const std::string& part, bool leaves, double limit,
                       const char* unit) {
    if (!event) return;
    event->what = what, event->part = part, event->leaves_envelope = leaves, event->limit = limit, event->unit = unit;
    out.push_back(std::move(*event));
  };
  for (std::size_t r = 0; r < e.ropes.size(); ++r) {
    const double limit = e.ropes[r].breaking_force;
    add(eventOf(time_, rope_tension_[r].values, [&](double x) { return x > limit; }, larger), "rope overload", e.ropes[r].name, true,
        limit, "N");
  }
  if (const auto& boom = e.boom) {
    add(eventOf(time_, boom_angle_, [&](double x) { return x > boom->limit_deg; }, larger), "boom past its angle limit", "boom", true,
        boom->limit_deg, "deg");
    add(eventOf(time_, backstop_moment_, [](double x) { return x > 0.0; }, larger), "on its backstop", "boom", false, 0.0, "N·m");
    if (!out.empty() && out.back().what == "on its backstop")
      out.back().depth = *std::max_element(backstop_compression_.begin(), backstop_compression_.end()), out.back().depth_unit = "deg";
  }
  if (e.ground_height) {
    const double ground = *e.ground_height;
    for (const EnvelopeSeries& s : lowest_)
      add(eventOf(time_, s.values, [&](double x) { return x < ground; }, [](double a, double b) { return a < b; }), "below ground",
          s.name, true, ground, "m");
  }
  for (std::size_t p = 0; p < contact_force_.size(); ++p) {
    const std::size_t before = out.size();
    add(eventOf(time_, contact_force_[p].values, [](double x) { return x > 0.0; }, larger), "on the ground", contact_force_[p].name, false,
        0.0, "N");
    if (out.size() > before)
      out.back().depth = *std::max_element(contact_depth_[p].values.begin(), contact_depth_[p].values.end()), out.back().depth_unit = "m";
  }
  if (const auto& supports = e.supports) {
    const double allowable = supports->allowable_pressure;
    const auto smaller = [](double a, double b) { return a < b; };
    const auto series = [&](const auto& reading) {
      std::vector<double> values;
      for (const SupportReading& r : supports_) values.push_back(reading(r));
      return values;
    };
    for (std::size_t p = 0; p < supports->pads.size(); ++p) {
      const std::vector<double> pressure = series([&](const SupportReading& r) { return r.pads[p].pressure; });
      add(eventOf(time_, pressure, [&](double x) { return x > allowable; }, larger), "over the allowable pressure", supports->pads[p].name,
          true, allowable, "Pa");
      add(eventOf(time_, pressure, [](double x) { return x <= 0.0; }, smaller), "lifted off", supports->pads[p].name, false, 0.0, "Pa");
    }
    for (std::size_t t = 0; t < supports->tracks.size(); ++t) {
      const EnvelopeSupport& track = supports->tracks[t];
      add(eventOf(time_, series([&](const SupportReading& r) { return r.tracks[t].peak_pressure; }), [&](double x) { return x > allowable; },
                  larger),
          "over the allowable pressure", track.name, true, allowable, "Pa");
      add(eventOf(time_, series([&](const SupportReading& r) { return r.tracks[t].contact_length; }),
                  [&](double x) { return x < track.length * (1.0 - 1e-9); }, smaller),
          "lifted off", track.name, false, track.length, "m");
    }
    add(eventOf(time_, series([](const SupportReading& r) { return r.tipping.margin; }), [](double x) { return x < 0.0; }, smaller),
        "stability margin below zero", supports->body, true, 0.0, "N·m");
    const std::size_t before = out.size();
    add(eventOf(time_, tipped_, [](double x) { return x > 0.0; }, larger), "tipped", supports->body, true, 0.0, "");
    if (out.size() > before) {
      const auto first = std::find_if(tipped_why_.begin(), tipped_why_.end(), [](const std::string& why) { return !why.empty(); });
      out.back().why = *first;
    }
  }
  std::stable_sort(out.begin(), out.end(), [](const EnvelopeEvent& a, const EnvelopeEvent& b) { return a.first_time < b.first_time; });
  return out;
}

bool leavesEnvelope(const std::vector<EnvelopeEvent>& events) {
  return std::any_of(events.begin(), events.end(), [](const EnvelopeEvent& e) { return e.leaves_envelope; });
}

std::string describeEnvelopeEvents(const std::vector<EnvelopeEvent>& events) {
  std::string out;
  for (const EnvelopeEvent& e : events) {
    if (e.what == "rope overload")
      out += fmt::format("rope overload: {} carried {} at t = {:.4g} s, above its breaking force {} (from t = {:.4g} s)\n", e.part,
                         withUnit(e.peak, e.unit), e.peak_time, withUnit(e.limit, e.unit), e.first_time);
    else if (e.what == "boom past its angle limit")
      out += fmt::format("boom past its angle limit: {} at t = {:.4g} s, beyond the envelope's {} (from t = {:.4g} s)\n",
                         withUnit(e.peak, e.unit), e.peak_time, withUnit(e.limit, e.unit), e.first_time);
    else if (e.what == "below ground")
      out += fmt::format("below ground: {} reached {} at t = {:.4g} s, {:.3g} m below the ground's surface at {} (from t = {:.4g} s)\n",
                         e.part, withUnit(e.peak, e.unit), e.peak_time, e.limit - e.peak, withUnit(e.limit, e.unit), e.first_time);
    else if (e.what == "over the allowable pressure")
      out += fmt::format("over the allowable pressure: {} pressed the soil with {} at t = {:.4g} s, above the allowable {} (from t = {:.4g} s)\n",
                         e.part, withUnit(e.peak, e.unit), e.peak_time, withUnit(e.limit, e.unit), e.first_time);
    else if (e.what == "stability margin below zero")
      out += fmt::format("stability margin below zero: {} at t = {:.4g} s, the supports' resultant outside their polygon (from t = {:.4g} s)\n",
                         withUnit(e.peak, e.unit), e.peak_time, e.first_time);
    else if (e.what == "tipped")
      out += fmt::format("tipped: from t = {:.4g} s, {}\n", e.first_time, e.why);
    else if (e.what == "lifted off" && e.unit == "m")
      out += fmt::format("{} lifted off: from t = {:.4g} s, down to {} of its {} in contact at t = {:.4g} s\n", e.part, e.first_time,
                         withUnit(e.peak, e.unit), withUnit(e.limit, e.unit), e.peak_time);
    else if (e.what == "lifted off")
      out += fmt::format("{} lifted off: from t = {:.4g} s\n", e.part, e.first_time);
    else
      out += fmt::format("{} {}: from t = {:.4g} s, at most {} at t = {:.4g} s, {} by at most {}\n", e.part, e.what, e.first_time,
                         withUnit(e.peak, e.unit), e.peak_time, e.what == "on its backstop" ? "compressed" : "pressed in",
                         withUnit(e.depth, e.depth_unit));
  }
  return out;
}

}  // namespace cranesim
