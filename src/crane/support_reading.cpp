#include "cranesim/crane/support_reading.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "cranesim/model/support_elements.hpp"

namespace cranesim {

std::pair<Vec3, Vec3> groundPlaneAxes(const Vec3& up) {
  const Vec3 seed = std::abs(up.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 first = (seed - up * up.dot(seed)).normalized();
  return {first, up.cross(first)};
}

SupportReading readSupports(const Model& model, const EnvelopeSupports& supports, const ElementInput& in) {
  const auto [e1, e2] = groundPlaneAxes(model.envelope.up);
  const Frame body = model.nodeFrame(in.q, supports.node);
  const auto inPlane = [&](const Vec3& point) {
    const Vec3 at = body.r + body.R * point;
    return Eigen::Vector2d(e1.dot(at), e2.dot(at));
  };
  const auto forcesOf = [&](const EnvelopeSupport& s) { return dynamic_cast<const SupportElement&>(*model.elements[s.element]).pointForces(in); };
  SupportReading reading;
  Eigen::Vector2d moment = Eigen::Vector2d::Zero();
  std::vector<Eigen::Vector2d>& polygon = reading.polygon;
  for (const EnvelopeSupport& pad : supports.pads) {
    const double force = forcesOf(pad)[0];
    reading.pads.push_back({force, force / pad.bearing_area});
    polygon.push_back(inPlane(pad.outline[0]));
    moment += force * polygon.back();
    reading.carried += force;
  }
  for (const EnvelopeSupport& track : supports.tracks) {
    TrackReading t;
    const std::vector<double> forces = forcesOf(track);
    const auto n = static_cast<double>(forces.size());
    const Vec3 from = track.outline[0], to = track.outline[1];
    for (std::size_t k = 0; k < forces.size(); ++k) {
      const double force = forces[k], along = (k + 0.5) / n;
      t.force += force;
      if (force > 0.0) t.contact_length += track.length / n;
      if (force / track.bearing_area > t.peak_pressure) t.peak_pressure = force / track.bearing_area, t.peak_at = along * track.length;
      moment += force * inPlane(from + (to - from) * along);
    }
    reading.tracks.push_back(t);
    reading.carried += t.force;
    polygon.push_back(inPlane(from));
    polygon.push_back(inPlane(to));
  }
  if (reading.carried > 0.0) {
    reading.resultant = moment / reading.carried;
  } else {
    for (const Eigen::Vector2d& p : polygon) reading.resultant += p / static_cast<double>(polygon.size());
  }
  reading.tipping = tippingLine(polygon, reading.carried, reading.resultant);
  return reading;
}

double SupportReading::peakPressure() const {
  double peak = 0.0;
  for (const PadReading& p : pads) peak = std::max(peak, p.pressure);
  for (const TrackReading& t : tracks) peak = std::max(peak, t.peak_pressure);
  return peak;
}

std::string describeSupportReading(const EnvelopeSupports& supports, const SupportReading& reading) {
  std::string out = fmt::format("{:<24} {:>12} {:>14} {:>14}\n", "support", "force [N]", "pressure [kPa]", "peak at [m]");
  for (std::size_t p = 0; p < supports.pads.size(); ++p)
    out += fmt::format("{:<24} {:>12.5g} {:>14.4g} {:>14}\n", supports.pads[p].name, reading.pads[p].force, reading.pads[p].pressure / 1e3, "");
  for (std::size_t t = 0; t < supports.tracks.size(); ++t) {
    const TrackReading& r = reading.tracks[t];
    out += fmt::format("{:<24} {:>12.5g} {:>14.4g} {:>14.4g}{}\n", supports.tracks[t].name, r.force, r.peak_pressure / 1e3, r.peak_at,
                       r.contact_length < supports.tracks[t].length ? fmt::format("  (in contact over {:.4g} m of {:.4g} m)", r.contact_length,
                                                                                 supports.tracks[t].length)
                                                                     : "");
  }
  const TippingLine& line = reading.tipping;
  out += fmt::format("allowable pressure {:.4g} kPa; tipping line ({:.4g}, {:.4g}) → ({:.4g}, {:.4g}) m, stability margin {:.5g} N·m "
                     "(the resultant {:.4g} m inside)\n",
                     supports.allowable_pressure / 1e3, line.from.x(), line.from.y(), line.to.x(), line.to.y(), line.margin,
                     reading.carried > 0.0 ? line.margin / reading.carried : 0.0);
  return out;
}

std::string summarizeSupportReadings(const EnvelopeSupports& supports, const std::vector<double>& time,
                                     const std::vector<SupportReading>& readings) {
  if (readings.empty()) return {};
  double peak = -1.0, peak_time = 0.0, lowest = readings[0].tipping.margin, lowest_time = time[0];
  std::string peak_support;
  for (std::size_t s = 0; s < readings.size(); ++s) {
    const SupportReading& r = readings[s];
    for (std::size_t p = 0; p < r.pads.size(); ++p)
      if (r.pads[p].pressure > peak) peak = r.pads[p].pressure, peak_time = time[s], peak_support = supports.pads[p].name;
    for (std::size_t t = 0; t < r.tracks.size(); ++t)
      if (r.tracks[t].peak_pressure > peak) peak = r.tracks[t].peak_pressure, peak_time = time[s], peak_support = supports.tracks[t].name;
    if (r.tipping.margin < lowest) lowest = r.tipping.margin, lowest_time = time[s];
  }
  return fmt::format("supports: peak pressure {:.4g} kPa under {} at t = {:.4g} s (allowable {:.4g} kPa); lowest stability margin "
                     "{:.5g} N·m at t = {:.4g} s\n",
                     peak / 1e3, peak_support, peak_time, supports.allowable_pressure / 1e3, lowest, lowest_time);
}

}  // namespace cranesim
