#include "sensor_reader.hpp"

namespace cranesim {
namespace {

/// 0, or a value within [low, high] of `unit`.
double zeroOrWithin(const YamlField& f, double low, double high, const char* unit) {
  return f.number() == 0.0 ? 0.0 : f.within(low, high, unit);
}

}  // namespace

SwaySensorSpec readSwaySensor(const YamlField& f) {
  f.allowKeys({"angle_noise", "rate_noise", "delay", "seed"});
  SwaySensorSpec spec;
  if (const auto x = f.find("angle_noise")) spec.angle_noise = zeroOrWithin(*x, 1e-9, 0.2, "rad");
  if (const auto x = f.find("rate_noise")) spec.rate_noise = zeroOrWithin(*x, 1e-9, 1.0, "rad/s");
  if (const auto x = f.find("delay")) spec.delay = zeroOrWithin(*x, 1e-6, 5.0, "s");
  if (const auto x = f.find("seed")) spec.seed = x->seed();
  return spec;
}

}  // namespace cranesim
