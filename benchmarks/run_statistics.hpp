#pragma once
// What the C++ benchmarks report of their repeated runs.

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <string>
#include <thread>
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

/// This machine as the benchmarks' tables name it: "<cores> cores, <CPU model>" (the model from
/// /proc/cpuinfo), as benchmarks/benchmark_csv.py's machine() does.
inline std::string machineName() {
  std::string model = "unknown CPU";
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);)
    if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos) {
      model = line.substr(line.find(':') + 1);
      model.erase(0, model.find_first_not_of(" \t"));
      break;
    }
  return std::to_string(std::thread::hardware_concurrency()) + " cores, " + model;
}

}  // namespace cranesim_bench
