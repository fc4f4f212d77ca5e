#pragma once
// What the rest of the program asks of a reeved rope, whichever its fidelity: the massless one
// (model/reeved_rope_element.hpp) or the massive one (model/massive_reeved_rope_element.hpp).

#include <string>
#include <vector>

#include "cranesim/model/element.hpp"

namespace cranesim {

struct Model;

class ReevedRope : public Element {
 public:
  /// Parts one rope may have: a path of 34 points.
  static constexpr int kMaxParts = 33;

  /// The rope member's name.
  virtual const std::string& name() const = 0;
  /// Its parts, winch to dead end.
  virtual int parts() const = 0;
  /// Each part's tension, winch to dead end (parts() values), N: a massless part's one tension,
  /// a massive part's largest (at its upper end where it hangs).
  virtual void partTensions(const ElementInput& in, double* tension) const = 0;
  /// The winch's pull hoisting steadily what the falls carry at `tension` (elements/reeved_rope.hpp).
  virtual double hoistingLinePull(const double* tension) const = 0;
  /// The positions of the path points (winch, sheaves' centres, dead end).
  virtual std::vector<Vec3> pathPositions(const ElementInput& in) const = 0;
};

/// The index in Model::reeved_ropes of the reeved rope named `rope`, −1 for none.
int findReevedRope(const Model& model, const std::string& rope);
/// Model::reeved_ropes[index]'s element.
const ReevedRope& reevedRope(const Model& model, int index);

}  // namespace cranesim
