#include "cranesim/model/closest_name.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

namespace cranesim {

std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t next = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
      diagonal = row[j];
      row[j] = next;
    }
  }
  return row[b.size()];
}

std::string closestName(const std::string& name, const std::vector<std::string>& candidates) {
  std::size_t best_distance = std::max<std::size_t>(2, name.size() / 4) + 1;
  std::string best;
  for (const std::string& candidate : candidates) {
    const std::size_t d = editDistance(name, candidate);
    if (d < best_distance) best_distance = d, best = candidate;
  }
  return best;
}

std::string unknownName(const std::string& what, const std::string& name, const std::vector<std::string>& names) {
  const std::string closest = closestName(name, names);
  std::string message = fmt::format("no {} named '{}'", what, name);
  if (!closest.empty()) message += fmt::format(" (did you mean '{}'?)", closest);
  if (names.empty()) return message + fmt::format("; the scene has no {}s", what);
  return message + fmt::format("; the scene's {}s: {}", what, listedNames(names));
}

std::string listedNames(const std::vector<std::string>& names) {
  return names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", "));
}

}  // namespace cranesim
