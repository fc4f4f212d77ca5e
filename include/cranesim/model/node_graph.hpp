#pragma once
// Which nodes of a model hang together: joined by elements and by constraints (all, or all but
// one that is cut), the ground counted as one more node. Drive posing asks which part a cut
// joint moves; the constraint rank check asks whether a constraint closes a loop.

#include <numeric>
#include <vector>

#include "cranesim/model/model.hpp"

namespace cranesim {

class NodeGraph {
 public:
  /// `cut`: the index of a constraint left out, or −1.
  NodeGraph(const Model& model, int cut = -1) : ground_(static_cast<int>(model.nodes.size())), parent_(ground_ + 1) {
    std::iota(parent_.begin(), parent_.end(), 0);
    for (const auto& e : model.elements)
      for (int n : e->nodes()) join(e->nodes().front(), n);
    for (std::size_t c = 0; c < model.constraints.size(); ++c)
      if (static_cast<int>(c) != cut) join(nodeOf(model, model.constraints[c].joint1), nodeOf(model, model.constraints[c].joint2));
  }

  /// The node a joint is on, the ground's for a ground joint.
  int nodeOf(const Model& model, int joint) const { return model.joints[joint].node < 0 ? ground_ : model.joints[joint].node; }
  int root(int n) {
    while (parent_[n] != n) n = parent_[n] = parent_[parent_[n]];
    return n;
  }
  bool connected(int a, int b) { return root(a) == root(b); }
  /// Whether node n's part is held by the ground.
  bool grounded(int n) { return connected(n, ground_); }

 private:
  void join(int a, int b) { parent_[root(a)] = root(b); }
  int ground_;
  std::vector<int> parent_;
};

}  // namespace cranesim
