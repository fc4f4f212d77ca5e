// Supports as scene elements against the hand statics of crane/support_statics.hpp: a carriage
// with a slewing upper carriage (its counterweight behind the slewing axis) and a hanging load on
// four pads over stiff ground, slewed around; the pad that lifts off as the load swings over a
// corner; two crawler tracks under an eccentric weight against the rigid track's trapezoid and
// triangle.
//
// What is compared: the elements' static solution stands on deformed springs, so the statics are
// evaluated on it: the pads where the equilibrium puts them and the weights' resultant through
// the bodies' centroids there (a tilted rigid carriage keeps its pads in a plane, so the springs'
// settlements stay linear in the pads' positions and the rigid plate's distribution is exact for
// every pad outside the springs' smoothing band).

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "cranesim/crane/envelope_monitor.hpp"
#include "cranesim/crane/support_reading.hpp"
#include "cranesim/crane/support_statics.hpp"
#include "cranesim/model/support_elements.hpp"
#include "cranesim/solvers/equilibrium_path.hpp"
#include "carriage_on_pads.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;
using Eigen::Vector2d;

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kHalfLength = 2.5, kHalfWidth = 2.0;  // m: the pads at (±2.5, ±2)
const char* const kPadNames[] = {"front_left", "rear_left", "rear_right", "front_right"};

/// The tests' carriage on pads (carriage_on_pads.hpp) with its default masses, slewed by
/// `slewed_deg`, on soil of modulus k_s.
std::string carriageOnPads(double slewed_deg, double subgrade_modulus, double smoothing = 0.1) {
  test::CarriageOnPads c;
  c.slewed_deg = slewed_deg;
  c.subgrade_modulus = subgrade_modulus;
  c.smoothing = smoothing;
  return test::carriageOnPadsYaml(c);
}

struct Standing {
  Scene scene;
  Model model;
  StaticResult eq;
};

Standing standing(const std::string& yaml) {
  Scene scene = parseScene(yaml, "<test>");
  Model model = compileModel(scene);
  StaticResult eq = solveEquilibrium(scene, model, 0.0);
  return {std::move(scene), std::move(model), std::move(eq)};
}

/// The force each point of a support carries at the equilibrium (their sum: the element's force).
std::vector<double> supportForces(const Standing& s, const EnvelopeSupport& support) {
  const VecX zero = VecX::Zero(s.model.nv);
  const ElementInput in{s.eq.q.data(), zero.data(), zero.data(), 0.0, s.model.gravity};
  const auto& element = dynamic_cast<const SupportElement&>(*s.model.elements[support.element]);
  const std::vector<double> out = element.pointForces(in);
  CHECK(element.contactForce(in) == Approx(std::accumulate(out.begin(), out.end(), 0.0)).epsilon(1e-12));
  return out;
}

double closure(const Standing& s, const EnvelopeSupport& support) {
  const VecX zero = VecX::Zero(s.model.nv);
  return dynamic_cast<const SupportElement&>(*s.model.elements[support.element]).closure({s.eq.q.data(), zero.data(), zero.data(), 0.0, s.model.gravity});
}

Vector2d horizontal(const Vec3& x) { return x.head<2>(); }

int bodyNode(const Model& model, const std::string& body) {
  const auto n = std::find_if(model.nodes.begin(), model.nodes.end(), [&](const Node& node) { return node.member.empty() && node.name == body; });
  return static_cast<int>(n - model.nodes.begin());
}

/// The weight of the scene's bodies and the point of its resultant at the equilibrium.
std::pair<double, Vector2d> weightResultant(const Standing& s) {
  double weight = 0.0;
  Vector2d moment = Vector2d::Zero();
  for (const RigidBodySpec& b : s.scene.bodies) {
    const Frame f = s.model.nodeFrame(s.eq.q.data(), bodyNode(s.model, b.name));
    const double w = b.mass * 9.81;
    weight += w;
    moment += w * horizontal(f.r + f.R * b.centroid);
  }
  return {weight, moment / weight};
}

std::vector<PadSpring> padSprings(const Standing& s, double stiffness) {
  std::vector<PadSpring> pads;
  for (const char* name : kPadNames)
    pads.push_back({horizontal(s.model.jointFrame(s.eq.q.data(), s.model.findJoint(fmt::format("carriage.{}", name))).r), stiffness});
  return pads;
}

}  // namespace

TEST_CASE("Four pads under a slewing crane carry the rigid plate's forces on stiff ground", "[supports]") {
  const double k_s = 1.0e10, area = 0.5;
  // 0° and 90°: four pads down; 40°, 60°, 135°, 220°, 300°: the resultant beyond the kern, a pad off.
  for (const double slewed : {0.0, 40.0, 60.0, 90.0, 135.0, 220.0, 300.0}) {
    CAPTURE(slewed);
    const Standing s = standing(carriageOnPads(slewed, k_s));
    REQUIRE(s.eq.converged);
    const auto [weight, resultant] = weightResultant(s);
    const std::vector<double> expected = rigidPlatePadForces(padSprings(s, k_s * area), weight, resultant);
    const auto& pads = s.model.envelope.supports->pads;
    REQUIRE(pads.size() == 4);
    int lifted = 0;
    for (std::size_t i = 0; i < pads.size(); ++i) {
      CAPTURE(pads[i].name);
      const double force = supportForces(s, pads[i])[0];
      CHECK(force == Approx(expected[i]).margin(1e-6 * weight));
      lifted += expected[i] == 0.0;
    }
    CHECK(lifted == (slewed == 0.0 || slewed == 90.0 ? 0 : 1));
  }
}

TEST_CASE("A pad lifts off at the slewing angle where the rigid plate's force changes sign", "[supports]") {
  // Slewing from 0° towards the front-left corner unloads the rear-right pad. The statics' sign
  // change (on the drawn geometry: the carriage tilts by 1e-5 rad on this ground) against the
  // angles where that pad's spring leaves its linear range (settlement ε, the smoothing band of
  // a hundredth of the mean settlement) and where it lifts off (settlement 0): the rigid plate's
  // law holds up to the first.
  const double k_s = 1.0e10, area = 0.5, smoothing = 0.01;
  const auto statics_force = [&](double slewed) {
    const Standing s = standing(carriageOnPads(slewed, k_s, smoothing));
    const auto [weight, resultant] = weightResultant(s);
    return rigidPlatePadForces(padSprings(s, k_s * area), weight, resultant)[2];
  };
  const auto settlement = [&](double slewed) {
    const Standing s = standing(carriageOnPads(slewed, k_s, smoothing));
    REQUIRE(s.eq.converged);
    return closure(s, s.model.envelope.supports->pads[2]);
  };
  const auto bisect = [](double low, double high, const auto& positive) {
    for (int i = 0; i < 30; ++i) {
      const double middle = 0.5 * (low + high);
      (positive(middle) ? low : high) = middle;
    }
    return 0.5 * (low + high);
  };
  const double band = smoothing * 35000 * 9.81 / (4 * k_s * area);
  const double sign_change = bisect(5.0, 30.0, [&](double a) { return statics_force(a) > 0.0; });
  const double linear_end = bisect(5.0, 30.0, [&](double a) { return settlement(a) > band; });
  const double lift_off = bisect(5.0, 30.0, [&](double a) { return settlement(a) > 0.0; });
  CAPTURE(sign_change, linear_end, lift_off);
  // ρ (cos θ / a + sin θ / b) = 1 for the resultant's swing ρ = (9 t · 8 m − 6 t · 1 m) / 35 t.
  const double rho = (9.0 * 8.0 - 6.0) / 35.0;
  const double hand = bisect(5.0, 30.0, [&](double a) { return rho * (std::cos(a * kDegree) / kHalfLength + std::sin(a * kDegree) / kHalfWidth) < 1.0; });
  CHECK(sign_change == Approx(hand).margin(0.01));
  CHECK(linear_end < sign_change);
  CHECK(sign_change < lift_off);
  CHECK(lift_off - linear_end < 1.0);  // deg: the smoothing band's width in slewing angle
}

namespace {

/// A 30 t crawler carriage on two tracks 5 m long, 3 m apart, 0.8 m wide, each borne by
/// `segments` stretches on soil of modulus 1e9 N/m³; its centroid `eccentricity` forward of the
/// tracks' middle.
std::string crawlerOnTracks(double eccentricity, int segments, double allowable = 1.0e6) {  // smoothing: a hundredth
  return fmt::format(R"(
name: crawler on two tracks
gravity: [0, 0, -9.81]
ground:
  supports:
    body: crawler
    soil: {{subgrade_modulus: 1.0e9, allowable_pressure: {}}}
    smoothing: 0.01
    tracks:
      - {{name: left, from: crawler.left_rear, to: crawler.left_front, width: 0.8, segments: {}}}
      - {{name: right, from: crawler.right_rear, to: crawler.right_front, width: 0.8, segments: {}}}
bodies:
  - name: crawler
    mass: 30000
    centroid: [{}, 0, 0.8]
    inertia: [40000, 60000, 80000]
    joints:
      - {{name: left_rear, position: [-2.5, 1.5, 0]}}
      - {{name: left_front, position: [2.5, 1.5, 0]}}
      - {{name: right_rear, position: [-2.5, -1.5, 0]}}
      - {{name: right_front, position: [2.5, -1.5, 0]}}
solver: {{t_end: 1, rtol: 1.0e-8, atol: 1.0e-10}}
)",
                     allowable, segments, segments, eccentricity);
}

/// The length of a rigid track's triangular bed pressure under an eccentricity beyond L/6.
double triangleLength(double eccentricity, double length) { return 3.0 * (length / 2 - eccentricity); }

}  // namespace

TEST_CASE("Two crawler tracks carry a rigid track's trapezoid, and its triangle once they lift", "[supports]") {
  const double length = 5.0, width = 0.8, force = 30000 * 9.81 / 2;  // N per track
  // 0.5 m: within the kern (L/6 = 0.83 m), a trapezoid; 1.25 m: the rear 1.25 m lifts off.
  for (const double eccentricity : {0.5, 1.25}) {
    CAPTURE(eccentricity);
    double error_by_segments[2];
    for (const int segments : {20, 80}) {
      CAPTURE(segments);
      const Standing s = standing(crawlerOnTracks(eccentricity, segments));
      REQUIRE(s.eq.converged);
      const double stretch = length / segments;
      const auto& tracks = s.model.envelope.supports->tracks;
      REQUIRE(tracks.size() == 2);
      double largest_error = 0.0, contact = 0.0;
      for (const EnvelopeSupport& track : tracks) {
        const std::vector<double> forces = supportForces(s, track);
        for (int k = 0; k < segments; ++k) {
          const double at = -length / 2 + (k + 0.5) * stretch;
          const double pressure = forces[k] / (width * stretch);
          largest_error = std::max(largest_error, std::abs(pressure - rigidTrackPressureAt(force, eccentricity, length, width, at)));
          contact += forces[k] > 0.0 ? stretch / 2 : 0.0;  // both tracks: their mean
        }
      }
      const TrackPressure expected = rigidTrackPressure(force, eccentricity, length, width);
      CAPTURE(largest_error / expected.peak, contact, expected.contact_length);
      CHECK(std::abs(contact - expected.contact_length) <= stretch);
      error_by_segments[segments == 80] = largest_error / expected.peak;
    }
    // The springs sample the continuous bed at their stretches' middles: the trapezoid's slope is
    // off by Σx² = n L²/12 (1 − 1/n²), O(1/n²); the triangle's edge falls within a stretch, where
    // its slope p/(3 (L/2 − e)) errs by a part of a stretch at most, O(1/n).
    if (eccentricity < length / 6) {
      CHECK(error_by_segments[0] < 3.0 / (20.0 * 20.0));
      CHECK(error_by_segments[1] < error_by_segments[0] / 10.0);
    } else {
      CHECK(error_by_segments[0] < length / (20.0 * triangleLength(eccentricity, length)));
      CHECK(error_by_segments[1] < length / (80.0 * triangleLength(eccentricity, length)));
    }
  }
}

TEST_CASE("The supports' reading: track peaks, the tipping line and margin, and the envelope's events", "[supports]") {
  // The crawler with its centroid 1.25 m forward: the tracks' front ends carry the peak, the
  // front edge x = 2.5 m is the tipping line, the margin W (2.5 m − x_c) with x_c where the
  // resultant acts; an allowable pressure below the peak is reported as leaving the envelope.
  const double weight = 30000 * 9.81, length = 5.0, stretch = length / 20;
  const Standing s = standing(crawlerOnTracks(1.25, 20, 5.0e4));  // the peak: about 98 kPa
  REQUIRE(s.eq.converged);
  const EnvelopeSupports& supports = *s.model.envelope.supports;
  const VecX zero = VecX::Zero(s.model.nv);
  const ElementInput in{s.eq.q.data(), zero.data(), zero.data(), 0.0, s.model.gravity};
  const SupportReading r = readSupports(s.model, supports, in);
  const auto [w, resultant] = weightResultant(s);
  CHECK(r.carried == Approx(weight).epsilon(1e-9));
  CHECK((r.resultant - resultant).norm() <= 1e-9);
  CHECK(r.tipping.from.x() == Approx(2.5).margin(1e-3));
  CHECK(r.tipping.to.x() == Approx(2.5).margin(1e-3));
  CHECK(r.tipping.margin == Approx(weight * (r.tipping.from.x() - resultant.x())).epsilon(1e-9));
  for (const TrackReading& t : r.tracks) {
    CHECK(t.force == Approx(weight / 2).epsilon(1e-6));
    CHECK(t.peak_at == Approx(length - stretch / 2));
    CHECK(t.peak_pressure == Approx(supportForces(s, supports.tracks[0]).back() / (0.8 * stretch)).epsilon(1e-6));
    CHECK(std::abs(t.contact_length - triangleLength(1.25, length)) <= stretch);
  }
  EnvelopeMonitor monitor(s.model);
  monitor.sample(0.0, s.eq.q.data(), zero.data());
  const std::vector<EnvelopeEvent> events = monitor.events();
  const auto over = std::find_if(events.begin(), events.end(), [](const EnvelopeEvent& e) { return e.what == "over the allowable pressure"; });
  REQUIRE(over != events.end());
  CHECK(over->leaves_envelope);
  CHECK(over->peak == Approx(r.tracks[0].peak_pressure));
  CHECK(std::count_if(events.begin(), events.end(), [](const EnvelopeEvent& e) { return e.what == "lifted off"; }) == 2);
  CHECK(monitor.lastSampleOutside());
}

TEST_CASE("The thesis crane on crawlers stands on the trapezoid of its tracks", "[supports][crane]") {
  // configs/crane_on_crawlers.yaml before its slew: the resultant lies within the tracks' kern,
  // both tracks carry along their whole length, their pressure the rigid track's trapezoid under
  // each track's force at the resultant's eccentricity (tracks from x = 6 m to −6 m: along −x).
  const Scene scene = test::loadScene("crane_on_crawlers.yaml");
  const Model model = compileModel(scene);
  const StaticResult eq = solveEquilibrium(scene, model, 0.0);
  REQUIRE(eq.converged);
  const EnvelopeSupports& supports = *model.envelope.supports;
  const VecX zero = VecX::Zero(model.nv);
  const SupportReading r = readSupports(model, supports, {eq.q.data(), zero.data(), zero.data(), 0.0, model.gravity});
  const double length = 12.0, width = 2.0, stretches = 24, eccentricity = -r.resultant.x();
  CAPTURE(eccentricity, r.carried);
  CHECK(eccentricity > 1.0);
  CHECK(eccentricity < length / 6);
  CHECK(r.tipping.margin == Approx(r.carried * (6.0 - eccentricity)).epsilon(1e-3));
  for (const TrackReading& t : r.tracks) {
    CHECK(t.contact_length == Approx(length));
    CHECK(t.force == Approx(r.carried / 2).epsilon(1e-3));
    CHECK(t.peak_at == Approx(length - length / stretches / 2));
    const double end_stretch = length / 2 - length / stretches / 2;
    CHECK(t.peak_pressure == Approx(rigidTrackPressureAt(t.force, eccentricity, length, width, end_stretch)).epsilon(3.0 / (stretches * stretches)));
  }
}
