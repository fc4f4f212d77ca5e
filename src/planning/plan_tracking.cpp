#include "cranesim/planning/plan_tracking.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "cranesim/control/crane_sway.hpp"
#include "cranesim/math/horizontal.hpp"
#include "cranesim/planning/quasi_static_plan.hpp"
#include "cranesim/session/session.hpp"

namespace cranesim {
namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The drives' model in the closed loop: two lags of τ after the command (a speed command), so
// the drive's value follows its command's integral about 2τ late; the feed-forward leads by that.
constexpr double kDriveLag = 0.05;
constexpr double kFeedForwardLead = 2.0 * kDriveLag;
// 1/s: the hoist winch's length is pulled back to the plan's within about a second.
constexpr double kHoistGain = 1.0;
// s: the initial sway's pull is let go over this time (short beside any sway period).
constexpr double kRelease = 0.5;

/// The value and rate of a control spline at t.
double valueAt(const TableProfile& spline, double t) { return Profile(spline)(t, Limit::Right); }
double rateAt(const TableProfile& spline, double t) {
  using D = Dual<double, 1>;
  return Profile(spline)(D(t, D::Derivatives::Ones()), Limit::Right).derivatives()(0);
}

/// m: how much longer the case's hoist rope is than the plan's (and its encoder's) at the start.
double hoistRopeLonger(const TrackingCase& c, const QuasiStaticPlan& plan) {
  return c.hoist_rope * plan.hoist_spline.y.front();
}

TableProfile shifted(TableProfile spline, double by) {
  for (double& y : spline.y) y += by;
  return spline;
}

RigidBodySpec& loadBody(Scene& scene, const std::string& end_point) {
  const std::string body = end_point.substr(0, end_point.find('.'));
  for (RigidBodySpec& b : scene.bodies)
    if (b.name == body) return b;
  throw std::logic_error("the end point '" + end_point + "' is not a body's joint (readTarget rules this out)");
}

Profile driveInput(double value, const DriveLimits& limits) {
  InputSpec spec;
  spec.command = InputCommand::Speed;
  spec.value = value;
  spec.order = 2;
  spec.time_constant = kDriveLag;
  if (limits.speed) spec.max_speed = *limits.speed;
  if (limits.acceleration) spec.max_acceleration = *limits.acceleration;
  return Profile(InputProfile{spec, nullptr});
}

/// Horizontal unit vectors at the load's start: outwards from the slewing axis, and across
/// (turned by the slewing spline's angle at time t for a slewing target).
Vec3 direction(const TargetSpec& target, const QuasiStaticPlan& plan, bool across, double t) {
  const Eigen::Vector2d start = target.origin + target.trajectory.start.head<2>();
  Vec3 radial = plan.plane.place(start.x(), start.y(), 0.0);
  radial.z() = 0.0;
  radial.normalize();
  double turn = 0.0;
  if (target.slewing) turn = valueAt(plan.slewing_spline, t) - valueAt(plan.slewing_spline, 0.0);
  const Vec3 turned(std::cos(turn) * radial.x() - std::sin(turn) * radial.y(),
                    std::sin(turn) * radial.x() + std::cos(turn) * radial.y(), 0.0);
  return across ? Vec3(-turned.y(), turned.x(), 0.0) : turned;
}

/// The verification scene with the case's differences; with `inputs`, its drives are speed
/// inputs the controller commands (within the target's drive limits).
Scene caseScene(const TargetSpec& target, const QuasiStaticPlan& plan, const TrackingCase& c, bool inputs) {
  Scene scene = verificationScene(target, plan);
  if (target.feedback->rtol) scene.solver.rtol = *target.feedback->rtol;
  if (target.feedback->atol) scene.solver.atol = *target.feedback->atol;
  scene.name += " — " + c.name + (inputs ? ", tracked" : ", open loop");
  RigidBodySpec& load = loadBody(scene, target.controls.end_point);
  load.mass *= c.load_mass;
  load.inertia *= c.load_mass;
  const double longer = hoistRopeLonger(c, plan);
  for (MemberSpec& m : scene.members) {
    if (m.name == target.controls.hoist_rope)
      m.length = inputs ? driveInput(plan.hoist_spline.y.front() + longer, target.drive_limits.hoist)
                        : Profile(shifted(plan.hoist_spline, longer));
    if (inputs && m.name == target.controls.luffing_rope)
      m.length = driveInput(plan.luffing_spline.y.front(), target.drive_limits.luffing);
  }
  if (inputs) {
    const std::string& slewing = target.feedback->slewing;
    const auto constraint = std::find_if(scene.constraints.begin(), scene.constraints.end(),
                                         [&](const ConstraintSpec& s) { return s.name == slewing && s.drive; });
    if (constraint == scene.constraints.end())
      throw std::logic_error("the feedback's slewing drive '" + slewing + "' is missing (readTarget rules this out)");
    constraint->drive = driveInput(target.slewing ? plan.slewing_spline.y.front() : (*constraint->drive)(0.0),
                                   target.drive_limits.slewing);
  }
  constexpr double g = 9.81;
  if (c.initial_sway != 0.0) {
    LoadSpec pull;
    pull.name = "initial_sway";
    pull.joint = target.controls.end_point;
    const double hanging = plan.hanging_length_start + longer;
    pull.force = direction(target, plan, false, 0.0) * (load.mass * g * c.initial_sway / hanging);
    pull.scale = Profile(TableProfile{{0.0, kRelease}, {1.0, 0.0}, {}, Interpolation::Linear});
    scene.loads.push_back(pull);
  }
  if (c.gust) {
    const double t0 = plan.lead_time + c.gust->start, t1 = t0 + c.gust->duration;
    LoadSpec gust;
    gust.name = "gust";
    gust.joint = target.controls.end_point;
    gust.force = direction(target, plan, c.gust->across, 0.5 * (t0 + t1)) * c.gust->force;
    gust.scale = Profile(CosineFullProfile{0.0, 1.0, t0, t1});
    scene.loads.push_back(gust);
  }
  if (c.wind) {
    scene.wind = *c.wind;
    if (scene.wind->field.gust) scene.wind->field.gust->t_start += plan.lead_time;
  }
  return scene;
}

/// What each run samples: the swing of the end point under its sheave, the hoist rope's
/// tension, and the drives' powers.
class Sampler {
 public:
  Sampler(Session& session, int hook, int sheave, const TargetSpec& target, int slewing, double arrival, double band)
      : session(session), hook(hook), sheave(sheave), luffing_rope(target.controls.luffing_rope),
        hoist_rope(target.controls.hoist_rope), slewing(slewing), arrival(arrival), band(band) {}

  void sample() {
    t.push_back(session.time());
    sway.push_back(horizontal(session.jointPosition(hook) - session.jointPosition(sheave)));
    const std::vector<double> tensions = session.ropeTensions(hoist_rope);
    const double top = tensions.empty() ? 0.0 : *std::max_element(tensions.begin(), tensions.end());
    if (t.size() == 1) static_tension = top;
    peak_tension = std::max(peak_tension, top);
    const double power[3] = {std::max(session.winchPower(luffing_rope), 0.0), std::max(session.winchPower(hoist_rope), 0.0),
                             std::max(session.drivePower(slewing), 0.0)};
    for (int d = 0; d < 3; ++d) {
      if (t.size() > 1) energy[d] += 0.5 * (t.back() - t[t.size() - 2]) * (last_power[d] + power[d]);
      last_power[d] = power[d];
    }
  }

  void finish(TrackingRun& run) const {
    for (std::size_t k = 0; k < t.size(); ++k) {
      if (t[k] >= arrival && t[k] <= arrival + 5.0) run.sway_at_arrival = std::max(run.sway_at_arrival, sway[k]);
      if (t[k] >= arrival + 5.0) run.sway_after_5_s = std::max(run.sway_after_5_s, sway[k]);
    }
    run.settling_time = -1.0;
    for (std::size_t k = t.size(); k-- > 0 && t[k] >= arrival;) {
      if (sway[k] > band) break;
      run.settling_time = t[k] - arrival;
    }
    run.peak_tension = peak_tension;
    run.dynamic_factor = static_tension > 0.0 ? peak_tension / static_tension : 0.0;
    std::copy(energy, energy + 3, run.energy);
  }

 private:
  Session& session;
  int hook, sheave;
  std::string luffing_rope, hoist_rope;
  int slewing;
  double arrival, band;
  std::vector<double> t, sway;
  double peak_tension = 0.0, static_tension = 0.0;
  double last_power[3] = {}, energy[3] = {};  // W, J: luffing, hoist, slewing
};

/// The swing the plan gives the load at every sample, radially and across, on the nominal crane.
using SwayReference = std::vector<Session::Sway>;

TrackingRun runCase(const TargetSpec& target, const QuasiStaticPlan& plan, const TrackingSpec& spec,
                    const TrackingCase& c, const SwayReference* reference, SwayReference* record) {
  const auto t0 = Clock::now();
  TrackingRun run;
  run.name = c.name;
  run.closed_loop = reference != nullptr;
  Session session(caseScene(target, plan, c, run.closed_loop));
  const std::string sheave = spec.sheave.empty() ? target.controls.hoist_rope + ".start" : spec.sheave;
  const int hook = session.joint(target.controls.end_point), pivot = session.joint(sheave);
  Sampler sampler(session, hook, pivot, target, session.constraint(spec.slewing), plan.lead_time + plan.path.t.back(),
                  spec.settle_band);

  std::optional<CraneSwayController> controller;
  int inputs[3] = {-1, -1, -1};  // luffing, hoist, slewing
  const double longer = hoistRopeLonger(c, plan);
  if (run.closed_loop) {
    CraneSwaySpec s;
    s.slewing = spec.slewing;
    s.luffing_rope = target.controls.luffing_rope;
    s.hoist_rope = target.controls.hoist_rope;
    s.hook = target.controls.end_point;
    s.sheave = sheave;
    s.across.sample_time = s.along.sample_time = spec.sample_time;
    s.hoist_gain = kHoistGain;
    s.sensor = c.sensor;
    controller.emplace(session, s);
    inputs[0] = session.input(s.luffing_rope);
    inputs[1] = session.input(s.hoist_rope);
    inputs[2] = session.input(s.slewing);
  }
  const double slewing_hold = controller ? session.inputValue(inputs[2]) : 0.0;
  const double t_end = session.model().solver.t_end;
  for (long k = 0;; ++k) {
    const double t = static_cast<double>(k) * spec.sample_time;
    sampler.sample();
    if (record) record->push_back(session.sway(hook, pivot));
    if (controller) {
      const auto tc = Clock::now();
      const std::size_t at = std::min(static_cast<std::size_t>(k), reference->size() - 1);
      CraneSwayReference r;
      r.luffing = valueAt(plan.luffing_spline, t);
      r.luffing_speed = rateAt(plan.luffing_spline, t + kFeedForwardLead);
      r.hoist = valueAt(plan.hoist_spline, t) + longer;
      r.hoist_speed = rateAt(plan.hoist_spline, t + kFeedForwardLead);
      r.slewing = target.slewing ? valueAt(plan.slewing_spline, t) : slewing_hold;
      r.slewing_speed = target.slewing ? rateAt(plan.slewing_spline, t + kFeedForwardLead) : 0.0;
      r.sway = (*reference)[at];
      controller->apply(r);
      run.controller_s += secondsSince(tc);
      for (int d = 0; d < 3; ++d) {
        const auto rates = session.model().inputs[static_cast<std::size_t>(inputs[d])].signal->derivatives(t);
        run.peaks[d][0] = std::max(run.peaks[d][0], std::abs(rates[1]));
        run.peaks[d][1] = std::max(run.peaks[d][1], std::abs(rates[2]));
      }
    }
    if (t >= t_end || !session.advanceTo(std::min(t + spec.sample_time, t_end))) break;
    ++run.samples;
  }
  run.outcome = session.outcome();
  if (!run.outcome.complete)
    throw std::runtime_error(fmt::format("feedback case '{}' ({}) stopped: {}", c.name,
                                         run.closed_loop ? "closed loop" : "open loop", run.outcome.message));
  sampler.finish(run);
  run.wall_s = secondsSince(t0);
  return run;
}

}  // namespace

void verifyTracking(const TargetSpec& target, QuasiStaticPlan& plan, const std::function<void(const std::string&)>& log) {
  const auto t0 = Clock::now();
  const TrackingSpec& spec = *target.feedback;
  SwayReference reference;
  TrackingCase planned;
  planned.name = "as planned";
  const TrackingRun nominal = runCase(target, plan, spec, planned, nullptr, &reference);
  if (log)
    log(fmt::format("feedback: the plan's reference swing sampled every {:g} s on the nominal crane ({:.1f} s)",
                    spec.sample_time, nominal.wall_s));
  std::vector<TrackingRun>& runs = plan.tracking;
  runs.clear();
  for (const TrackingCase& c : spec.cases) {
    for (const bool closed : {false, true}) {
      runs.push_back(runCase(target, plan, spec, c, closed ? &reference : nullptr, nullptr));
      const TrackingRun& r = runs.back();
      if (log)
        log(fmt::format("feedback: {:<24} {:<11} sway 0–5 s after arrival ≤ {:.3f} m, from 5 s ≤ {:.3f} m, within "
                        "{:g} m {}; dynamic factor {:.3f}; drives' work {:.2f} MJ; {:.1f} s{}",
                        c.name, closed ? "closed loop" : "open loop", r.sway_at_arrival, r.sway_after_5_s, spec.settle_band,
                        r.settling_time < 0.0 ? std::string("never") : fmt::format("from {:.1f} s", r.settling_time),
                        r.dynamic_factor, 1e-6 * (r.energy[0] + r.energy[1] + r.energy[2]), r.wall_s,
                        closed ? fmt::format(" (controller {:.3f} ms per sample)", 1e3 * r.controller_s / std::max(1L, r.samples))
                               : std::string()));
    }
  }
  if (log) {
    double open = 0.0, closed = 0.0;
    int settled = 0;
    for (const TrackingRun& r : runs) {
      (r.closed_loop ? closed : open) = std::max(r.closed_loop ? closed : open, r.sway_after_5_s);
      if (r.closed_loop && r.settling_time >= 0.0 && r.settling_time <= 5.0) ++settled;
    }
    log(fmt::format("feedback: from 5 s after arrival the load sways ≤ {:.3f} m tracked, ≤ {:.3f} m open loop; tracked "
                    "within {:g} m by 5 s after arrival in {} of {} cases",
                    closed, open, spec.settle_band, settled, spec.cases.size()));
  }
  plan.tracking_s = secondsSince(t0);
}

}  // namespace cranesim
