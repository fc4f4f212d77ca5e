#pragma once
// How a crane's sway sensor gives the hoist rope's angles to a controller: late by a transport
// delay and with white noise (control/sway_sensor.hpp models it).

#include <cstdint>

namespace cranesim {

struct SwaySensorSpec {
  double angle_noise = 0.0;  // rad: σ of the noise on each angle
  double rate_noise = 0.0;   // rad/s: σ of the noise on each angular rate
  double delay = 0.0;        // s
  std::uint64_t seed = 0;    // of the noise (a 64-bit Mersenne twister)
};

}  // namespace cranesim
