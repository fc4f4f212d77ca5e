#include "cranesim/model/wind_field.hpp"

#include <algorithm>
#include <numbers>

namespace cranesim {

WindField::WindField(const WindFieldSpec& spec, const Vec3& gravity)
    : spec_(spec),
      up_(gravity.norm() > 0.0 ? Vec3(-gravity.normalized()) : Vec3::UnitZ()),
      reference_height_(spec.profile.law == WindProfileLaw::Uniform
                            ? spec.reference_height
                            : std::max(spec.reference_height, spec.profile.minimum_height)) {
  if (spec.turbulence) {
    const TurbulenceSpec& t = *spec.turbulence;
    turbulence_.emplace(t.intensity * spec.speed, t.length_scale, spec.speed, t.period, t.frequency_max, t.seed);
  }
}

double WindField::gustFactor(double t) const {
  if (!spec_.gust) return 1.0;
  const GustSpec& g = *spec_.gust;
  const double rise_end = g.t_start + g.rise_time, end = g.t_start + g.duration, fall = end - g.rise_time;
  double s = 0.0;
  if (t <= g.t_start || t >= end) s = 0.0;
  else if (t < rise_end) s = 0.5 * (1.0 - std::cos(std::numbers::pi * (t - g.t_start) / g.rise_time));
  else if (t <= fall) s = 1.0;
  else s = 0.5 * (1.0 + std::cos(std::numbers::pi * (t - fall) / g.rise_time));
  return 1.0 + (g.factor - 1.0) * s;
}

}  // namespace cranesim
