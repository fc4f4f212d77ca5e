#pragma once
// One case of a study: its scene built, its analysis run by the solvers crane-sim's verbs use
// (solvers/scene_equilibrium.hpp, simulate, computeModes), its figures taken; with a study's
// `capacity`, once per load of the bisection (study/capacity_search.hpp); with a
// `least_stable_angle`, once per angle of the search (study/least_stable_angle.hpp). Every
// failure is the row's status and message, never an exception: the study goes on.

#include <atomic>
#include <string>

#include "cranesim/study/case_row.hpp"
#include "cranesim/study/study.hpp"

namespace cranesim {

struct CaseOptions {
  /// Set by a signal: a run stops at its next step and its row is `interrupted`.
  const std::atomic<bool>* stop = nullptr;
  /// Where the case's full results go (study: keep_results); empty: nowhere.
  std::string results_path;
};

CaseRow runCase(const Study& study, long index, const CaseOptions& options);

}  // namespace cranesim
