#pragma once
// Random numbers, vectors and rotations for the element kernel tests (reproducible by seed).

#include <cmath>
#include <random>

#include "cranesim/math/rotation.hpp"

namespace cranesim::test {

struct Rng {
  std::mt19937 gen;
  std::uniform_real_distribution<double> u{-1.0, 1.0};
  explicit Rng(unsigned seed) : gen(seed) {}
  double operator()() { return u(gen); }
  Vec3 vec(double scale = 1.0) { return scale * Vec3((*this)(), (*this)(), (*this)()); }
  /// A rotation of angle up to `max_angle` about a random axis.
  Mat3 rotation(double max_angle) { return axisAngle(vec().normalized(), max_angle * std::abs((*this)())); }
};

}  // namespace cranesim::test
