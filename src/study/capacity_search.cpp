#include "cranesim/study/capacity_search.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>

namespace cranesim {
namespace {

/// What an inadmissible row violates: the figures of its failed criteria, or why it has none.
std::string violations(const Study& study, const CaseRow& row) {
  if (row.status != kCaseComplete) return fmt::format("{}: {}", row.status, row.message);
  std::string names;
  for (const StudyCriterion& c : study.criteria)
    if (c.holds(row.figures[c.figure]) != 1.0) names += (names.empty() ? "" : ", ") + study.figures[c.figure].name;
  return names;
}

}  // namespace

bool admissible(const Study& study, const CaseRow& row) {
  if (row.status != kCaseComplete) return false;
  for (const StudyCriterion& c : study.criteria)
    if (c.holds(row.figures[c.figure]) != 1.0) return false;
  return true;
}

CaseRow searchCapacity(const Study& study, const LoadedCase& evaluate) {
  const CapacitySpec& spec = *study.capacity;
  double steps = 0.0;
  const auto at = [&](double load) {
    CaseRow row = evaluate(load);
    steps += row.steps;
    return row;
  };
  double low = spec.from, high = spec.to;
  CaseRow light = at(low);
  if (light.status != kCaseComplete) return light;
  if (!admissible(study, light)) {
    light.inadmissible_load = low;
    light.limited_by = violations(study, light);
    return light;
  }
  CaseRow heavy = at(high);
  if (heavy.status == kCaseInterrupted) return heavy;
  if (admissible(study, heavy)) {
    heavy.capacity = high;
    heavy.steps = steps;
    return heavy;
  }
  while (high - low > spec.tolerance) {
    const double middle = 0.5 * (low + high);
    CaseRow row = at(middle);
    if (row.status == kCaseInterrupted) return row;
    if (admissible(study, row)) low = middle, light = std::move(row);
    else high = middle, heavy = std::move(row);
  }
  light.capacity = low;
  light.inadmissible_load = high;
  light.limited_by = violations(study, heavy);
  light.steps = steps;
  return light;
}

}  // namespace cranesim
