#pragma once
// Whether a crane's carriage on its supports (support_elements.hpp) has tipped. On a Winkler bed
// a carriage at rest stands only while the points of its supports that carry span an area seen
// from above: carrying points in one line — two pads of four, the front stretches of two
// tracks, one track — leave it on an edge, a single pad on a corner. The bed then has no
// stiffness about that edge, so the supports' resultant lies on it: the crane is at its tipping
// point, a balance on an edge that the least disturbance ends (a run shows the carriage falling
// over it: its lifted supports carry nothing). Such an equilibrium is not one a crane stands in,
// nor a point of its load chart.

#include <string>

#include "cranesim/model/model.hpp"

namespace cranesim {

/// Why the carriage at rest in q at time t counts as tipped — which supports carry (more than a
/// millionth of what all carry), standing in one line or at one point seen from above, or none
/// carrying — or empty when it stands (or the model has no supports).
std::string carriageTipped(const Model& model, const VecX& q, double t);

}  // namespace cranesim
