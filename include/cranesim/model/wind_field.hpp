#pragma once
// The wind: a mean speed at a reference height, scaled with height by a profile law and in time
// by a discrete gust, plus turbulence along the same fixed horizontal direction. Heights are
// measured against gravity (the scene's "up" is −gravity/|gravity|, or +z without gravity)
// from the ground level.

#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>

#include "cranesim/math/autodiff.hpp"
#include "cranesim/math/turbulence.hpp"
#include "cranesim/math/types.hpp"

namespace cranesim {

/// How the mean speed grows with height z above the ground, as v(z)/v(z_ref):
/// - Uniform: 1 at every height;
/// - Power: (z/z_ref)^α, the power law of ISO 4302 and EN 13001-2 (α = 0.14);
/// - Logarithmic: ln(z/z₀)/ln(z_ref/z₀), the log law of EN 1991-1-4 (4.4) with the roughness
///   length z₀ of its terrain category (Table 4.1).
/// Below `minimum_height` z_min the speed is that at z_min (EN 1991-1-4's z_min of the category;
/// 1 m for the power law).
enum class WindProfileLaw { Uniform, Power, Logarithmic };

struct WindProfileSpec {
  WindProfileLaw law = WindProfileLaw::Uniform;
  double exponent = 0.14;          // α (power)
  double roughness_length = 0.05;  // z₀, m (logarithmic)
  double minimum_height = 1.0;     // z_min, m
};

/// A discrete gust: the mean speed times 1 + (factor − 1) s(t), s rising from 0 to 1 as
/// ½(1 − cos) in `rise_time` from `t_start`, held, and falling back as ½(1 + cos) in
/// `rise_time` to end at t_start + duration (≥ 2 rise_time): continuous in its first derivative.
struct GustSpec {
  double t_start = 0.0, rise_time = 1.0, duration = 2.0, factor = 1.0;
};

/// Turbulence along the mean direction: a TurbulenceSeries of the Kaimal spectrum with
/// σ = intensity · speed, repeating after `period`, up to `frequency_max`.
struct TurbulenceSpec {
  double intensity = 0.1;
  double length_scale = 340.2;  // m, IEC 61400-1's 8.1 Λ₁ with Λ₁ = 42 m
  double period = 600.0;        // s
  double frequency_max = 2.0;   // Hz
  std::uint64_t seed = 0;
};

struct WindFieldSpec {
  double speed = 0.0;              // m/s, mean at reference_height
  double reference_height = 10.0;  // m
  Vec3 direction = Vec3::UnitX();  // where the wind blows to; horizontal, unit
  double air_density = 1.25;       // kg/m³
  double ground_height = 0.0;      // m, the ground's height along "up" from the origin
  WindProfileSpec profile;
  std::optional<GustSpec> gust;
  std::optional<TurbulenceSpec> turbulence;
};

class WindField {
 public:
  WindField(const WindFieldSpec& spec, const Vec3& gravity);

  const WindFieldSpec& spec() const { return spec_; }
  const Vec3& up() const { return up_; }
  /// The turbulence series, if the wind has one.
  const TurbulenceSeries* turbulence() const { return turbulence_ ? &*turbulence_ : nullptr; }

  /// Height above the ground of a point r, m.
  template <class S> S height(const Vec3T<S>& r) const { return r.dot(up_.cast<S>()) - spec_.ground_height; }
  /// v(z)/v(z_ref) of the profile law.
  template <class S> S profileFactor(S z) const {
    using std::log, std::pow;
    if (spec_.profile.law == WindProfileLaw::Uniform) return S(1.0);
    if (valueOf(z) < spec_.profile.minimum_height) z = S(spec_.profile.minimum_height);
    if (spec_.profile.law == WindProfileLaw::Power) return pow(z / reference_height_, spec_.profile.exponent);
    return log(z / spec_.profile.roughness_length) / log(reference_height_ / spec_.profile.roughness_length);
  }
  /// The gust's factor on the mean speed at t.
  double gustFactor(double t) const;
  /// The turbulent speed at t, m/s (0 without turbulence).
  double turbulentSpeed(double t) const { return turbulence_ ? (*turbulence_)(t) : 0.0; }
  /// The wind's velocity at point r and time t, m/s.
  template <class S> Vec3T<S> velocity(const Vec3T<S>& r, double t) const {
    const S speed = spec_.speed * gustFactor(t) * profileFactor(height(r)) + turbulentSpeed(t);
    return spec_.direction.cast<S>() * speed;
  }

 private:
  WindFieldSpec spec_;
  Vec3 up_;
  double reference_height_;  // z_ref, raised to z_min
  std::optional<TurbulenceSeries> turbulence_;
};

}  // namespace cranesim
