#pragma once
// What the C++ benchmarks report of their repeated runs.

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace cranesim_bench {

/// The median of the values that are numbers (a failed run's NaN is left out): the middle one,
/// or the mean of the middle two; NaN when there is none.
inline double median(std::vector<double> x) {
  x.erase(std::remove_if(x.begin(), x.end(), [](double v) { return std::isnan(v); }), x.end());
  if (x.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(x.begin(), x.end());
  const std::size_t n = x.size();
  return n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
}

}  // namespace cranesim_bench
