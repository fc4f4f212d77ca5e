#include "cranesim/control/crane_sway.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>

#include "cranesim/math/horizontal.hpp"
#include "cranesim/model/compile.hpp"
#include "cranesim/solvers/scene_equilibrium.hpp"

namespace cranesim {
namespace {

/// The drive's value per unit of input `index` (π/180 for a drive in degrees, else 1): its
/// profile evaluated with a signal that holds 1.
double inputUnit(const Model& model, int index) {
  const ModelInput& input = model.inputs[static_cast<std::size_t>(index)];
  for (const Constraint& c : model.constraints)
    if (c.name == input.name && c.drive && c.drive->input()) {
      Profile unit = *c.drive;
      InputSpec spec = unit.input()->spec;
      spec.value = 1.0;
      unit.input()->signal = std::make_shared<InputSignal>(spec, 0.0);
      return unit(0.0);
    }
  return 1.0;
}

/// The luffing rope's input spec in `scene`, to set its value.
InputSpec& luffingSpec(Scene& scene, const std::string& rope) {
  for (MemberSpec& m : scene.members)
    if (m.name == rope && m.length && m.length->input()) return m.length->input()->spec;
  throw std::invalid_argument(fmt::format("the luffing rope '{}' is not a rope length input", rope));
}

}  // namespace

CraneSwayController::CraneSwayController(Session& session, const CraneSwaySpec& spec)
    : session_(session), slewing_(session.input(spec.slewing)), luffing_(session.input(spec.luffing_rope)),
      hoist_(session.input(spec.hoist_rope)), hook_(session.joint(spec.hook)), sheave_(session.joint(spec.sheave)),
      slewing_unit_(inputUnit(session.model(), slewing_)), across_(spec.across), along_(spec.along),
      sensor_(spec.sensor, spec.across.sample_time),
      slewing_reference_(session.inputValue(slewing_)), luffing_reference_(session.inputValue(luffing_)),
      hoist_reference_(session.inputValue(hoist_)), hoist_gain_(spec.hoist_gain) {
  // dR/dl by central differences of the equilibria at the table's lengths ± 1 cm.
  const InputSpec& luffing = session.model().inputs[static_cast<std::size_t>(luffing_)].signal->spec();
  const double now = session.inputValue(luffing_);
  const double low = std::isfinite(luffing.min) ? luffing.min : now - 2.0, high = std::isfinite(luffing.max) ? luffing.max : now + 2.0;
  constexpr int kPoints = 7;
  constexpr double kStep = 0.01;
  Scene scene = session.scene();
  const auto headRadius = [&](double length) {
    luffingSpec(scene, spec.luffing_rope).value = length;
    const Model model = compileModel(scene);
    const Assembler assembler(model);
    const StaticResult eq = sceneEquilibrium(scene, model, assembler, true);
    return horizontal(model.jointFrame(eq.q.data(), model.findJoint(spec.sheave)).r);
  };
  for (int k = 0; k < kPoints; ++k) {
    const double length = low + (high - low) * k / (kPoints - 1);
    table_length_.push_back(length);
    table_ratio_.push_back((headRadius(length + kStep) - headRadius(length - kStep)) / (2.0 * kStep));
  }
  if (spec.shaping_period > 0.0) {
    const Vec3 head = session.jointPosition(sheave_);
    const double rope = (session.jointPosition(hook_) - head).norm();
    pendulum_offset_ = across_.spec().gravity * std::pow(spec.shaping_period / (2.0 * std::numbers::pi), 2) - rope;
    const auto acceleration = [&](int input) {
      return session.model().inputs[static_cast<std::size_t>(input)].signal->spec().max_acceleration;
    };
    const ShapedHeadPath::Limits limits{acceleration(slewing_) * slewing_unit_,
                                        acceleration(luffing_) * headPerLuff(luffing_reference_)};
    shaped_.emplace(Eigen::Vector2d(head.x(), head.y()), spec.shaping_period, limits, across_.spec().sample_time,
                    across_.spec().gravity);
    shaped_luffing_ = luffing_reference_;
    slewing_start_ = slewing_reference_;
  }
  if (spec.sensor.delay > 0.0) late_head_speeds_.emplace(spec.sensor.delay, spec.across.sample_time);
  if (spec.boom_period > 0.0)
    smoothed_hoist_.emplace(static_cast<std::size_t>(std::max(1L, std::lround(spec.boom_period / across_.spec().sample_time))), 0.0);
}

double CraneSwayController::shapingPeriod(double rope_length) const {
  // A pendulum of the rope's length plus the offset found at the start: T = 2π √((l + offset)/g).
  const double length = std::max(rope_length + pendulum_offset_, 0.01 * rope_length);
  return 2.0 * std::numbers::pi * std::sqrt(length / across_.spec().gravity);
}

double CraneSwayController::headPerLuff(double length) const {
  const auto upper = std::upper_bound(table_length_.begin(), table_length_.end(), length);
  if (upper == table_length_.begin()) return table_ratio_.front();
  if (upper == table_length_.end()) return table_ratio_.back();
  const std::size_t k = static_cast<std::size_t>(upper - table_length_.begin());
  const double w = (length - table_length_[k - 1]) / (table_length_[k] - table_length_[k - 1]);
  return (1.0 - w) * table_ratio_[k - 1] + w * table_ratio_[k];
}

std::vector<double> CraneSwayController::apply(double slewing_speed, double luffing_speed, double hoist_speed) {
  const double dt = across_.spec().sample_time;
  CraneSwayReference reference;
  reference.slewing = slewing_reference_;
  reference.slewing_speed = slewing_speed;
  reference.luffing = luffing_reference_;
  reference.luffing_speed = luffing_speed;
  reference.hoist = hoist_reference_;
  if (smoothed_hoist_) hoist_speed = (*smoothed_hoist_)(hoist_speed);
  reference.hoist_speed = hoist_speed;
  if (shaped_) {
    const double rope = (session_.jointPosition(hook_) - session_.jointPosition(sheave_)).norm();
    const ShapedHeadPath::Sample r = shaped_->advance(slewing_speed * slewing_unit_,
                                                      luffing_speed * headPerLuff(luffing_reference_), shapingPeriod(rope));
    const double ratio = headPerLuff(shaped_luffing_);
    reference.slewing = slewing_start_ + r.slewing / slewing_unit_;
    reference.slewing_speed = r.slewing_speed / slewing_unit_;
    reference.luffing = shaped_luffing_;
    reference.luffing_speed = r.radius_speed / ratio;
    reference.sway = {r.radial, r.across, r.radial_rate, r.across_rate};
    shaped_luffing_ += reference.luffing_speed * dt;
  }
  slewing_reference_ += slewing_speed * dt;
  luffing_reference_ += luffing_speed * dt;
  hoist_reference_ += hoist_speed * dt;
  return apply(reference);
}

std::vector<double> CraneSwayController::apply(const CraneSwayReference& reference) {
  const Vec3 head = session_.jointPosition(sheave_);
  const double radius = horizontal(head);
  const double length = (session_.jointPosition(hook_) - head).norm();

  const double slewing = session_.inputValue(slewing_), slewing_rate = session_.inputRate(slewing_);
  const double to_head = radius * slewing_unit_;
  const double luffing = session_.inputValue(luffing_), luffing_rate = session_.inputRate(luffing_);
  const double ratio = headPerLuff(luffing);
  Session::Sway sway = sensor_.read(session_.sway(hook_, sheave_));
  if (late_head_speeds_) {
    const Eigen::Vector2d head_speeds(ratio * luffing_rate, to_head * slewing_rate);
    sway = predictOverDelay(sway, sensor_.delay(), across_.spec().gravity, length, head_speeds - (*late_head_speeds_)(head_speeds));
  }
  const double across = across_.command(length, to_head * (slewing - reference.slewing), to_head * slewing_rate,
                                        to_head * reference.slewing_speed, sway.across - reference.sway.across,
                                        sway.across_rate - reference.sway.across_rate);
  const double along = along_.command(length, ratio * (luffing - reference.luffing), ratio * luffing_rate,
                                      ratio * reference.luffing_speed, sway.radial - reference.sway.radial,
                                      sway.radial_rate - reference.sway.radial_rate);
  const double hoist = reference.hoist_speed + hoist_gain_ * (reference.hoist - session_.inputValue(hoist_));

  std::vector<double> held(session_.model().inputs.size());
  for (std::size_t k = 0; k < held.size(); ++k) held[k] = session_.model().inputs[k].signal->held();
  held[static_cast<std::size_t>(slewing_)] = session_.setInput(slewing_, across / to_head);
  held[static_cast<std::size_t>(luffing_)] = session_.setInput(luffing_, along / ratio);
  held[static_cast<std::size_t>(hoist_)] = session_.setInput(hoist_, hoist);
  return held;
}

}  // namespace cranesim
