#include "cranesim/study/least_stable_angle.hpp"

#include <cmath>
#include <limits>
#include <map>

namespace cranesim {
namespace {

/// The rows computed so far, by angle, and how bad each is: the figure (worst: max) or minus it
/// (worst: min); +inf for an analysis that did not complete.
class AngleEvaluations {
 public:
  AngleEvaluations(const Study& study, const AngledCase& evaluate) : spec_(*study.least_stable), evaluate_(evaluate) {}

  /// The row at `angle`, computed once.
  const CaseRow& at(double angle) {
    auto found = rows_.find(angle);
    if (found == rows_.end()) {
      found = rows_.emplace(angle, evaluate_(angle)).first;
      steps_ += found->second.steps;
      if (found->second.status == kCaseInterrupted) interrupted_ = &found->second;
    }
    return found->second;
  }

  double badness(double angle) {
    const CaseRow& row = at(angle);
    if (row.status != kCaseComplete) return std::numeric_limits<double>::infinity();
    const double value = row.figures[spec_.figure];
    if (std::isnan(value)) return std::numeric_limits<double>::infinity();
    return spec_.worst_is_max ? value : -value;
  }

  /// The row of an evaluation a signal stopped, if any.
  const CaseRow* interrupted() const { return interrupted_; }

  /// The worst angle computed within [low, high] (the first of equals).
  double worstWithin(double low, double high) {
    double worst = std::numeric_limits<double>::quiet_NaN();
    for (const auto& [angle, row] : rows_)
      if (angle >= low && angle <= high && (std::isnan(worst) || badness(angle) > badness(worst))) worst = angle;
    return worst;
  }

  /// The row at `angle` with the search's columns and the steps of every evaluation.
  CaseRow result(double angle, double grid_angle) {
    CaseRow row = at(angle);
    row.least_stable_angle = angle;
    row.worst_grid_angle = grid_angle;
    row.least_stable_value = row.status == kCaseComplete ? row.figures[spec_.figure] : std::numeric_limits<double>::quiet_NaN();
    row.steps = steps_;
    return row;
  }

 private:
  const LeastStableAngleSpec& spec_;
  const AngledCase& evaluate_;
  std::map<double, CaseRow> rows_;
  double steps_ = 0.0;
  const CaseRow* interrupted_ = nullptr;
};

}  // namespace

CaseRow searchLeastStableAngle(const Study& study, const AngledCase& evaluate) {
  const LeastStableAngleSpec& spec = *study.least_stable;
  AngleEvaluations rows(study, evaluate);
  std::size_t worst = 0;
  for (std::size_t k = 0; k < spec.grid.size(); ++k) {
    rows.at(spec.grid[k]);
    if (const CaseRow* stopped = rows.interrupted()) return *stopped;
    if (rows.badness(spec.grid[k]) > rows.badness(spec.grid[worst])) worst = k;
  }
  const double grid_angle = spec.grid[worst];
  if (rows.at(grid_angle).status != kCaseComplete) return rows.result(grid_angle, grid_angle);

  // Golden-section search for the largest badness on [x0, x3] around the worst grid angle, with
  // inner points x1 < x2: the bracket shrinks to the side of the worse of them, which stays
  // inside, and a new point goes into the larger part, at 1 − 1/φ of it. Inside the grid the
  // worst angle is an inner point from the start.
  constexpr double kInto = 0.3819660112501051;  // 1 − 1/φ
  const double low = spec.grid[worst == 0 ? 0 : worst - 1], high = spec.grid[std::min(worst + 1, spec.grid.size() - 1)];
  double x0 = low, x3 = high, x1 = 0.0, x2 = 0.0;
  if (worst == 0 || worst + 1 == spec.grid.size()) x1 = x0 + kInto * (x3 - x0), x2 = x1 + kInto * (x3 - x1);
  else if (x3 - grid_angle > grid_angle - x0) x1 = grid_angle, x2 = grid_angle + kInto * (x3 - grid_angle);
  else x2 = grid_angle, x1 = grid_angle - kInto * (grid_angle - x0);
  while (x3 - x0 > spec.tolerance) {
    const bool right = rows.badness(x2) > rows.badness(x1);
    if (const CaseRow* stopped = rows.interrupted()) return *stopped;
    if (right) x0 = x1, x1 = x2, x2 = x1 + kInto * (x3 - x1);
    else x3 = x2, x2 = x1, x1 = x2 - kInto * (x2 - x0);
  }
  return rows.result(rows.worstWithin(low, high), grid_angle);
}

}  // namespace cranesim
