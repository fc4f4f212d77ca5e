#pragma once
// Steps shared by the scene compilers (compile.cpp, compile_truss.cpp): adding a kernel element
// on nodes, and adding a constraint with its rows.

#include <memory>
#include <string>
#include <vector>

#include "cranesim/math/rotation.hpp"
#include "cranesim/model/kernel_elements.hpp"
#include "cranesim/model/model.hpp"

namespace cranesim {

template <class Kernel>
void addElement(Model& model, Kernel kernel, const std::vector<int>& nodes) {
  std::vector<int> q, v;
  for (int n : nodes) {
    const Node& node = model.nodes[n];
    for (int k = 0; k < node.size(); ++k) q.push_back(node.q + k), v.push_back(node.v + k);
  }
  model.elements.push_back(makeElement(std::move(kernel), nodes, std::move(q), std::move(v)));
}

inline std::vector<std::string> constraintRowLabels(const Constraint& c) {
  static const char* const axis_names[] = {"x", "y", "z"};
  const std::vector<std::string> position = {"x", "y", "z"};
  const std::vector<std::string> lock = {"rot_yz", "rot_zx", "rot_xy"};
  const std::string i = axis_names[c.axis], p = axis_names[(c.axis + 1) % 3], q = axis_names[(c.axis + 2) % 3];
  std::vector<std::string> out;
  switch (c.type) {
    case ConstraintType::Spherical: out = position; break;
    case ConstraintType::Fixed:
      out = position;
      out.insert(out.end(), lock.begin(), lock.end());
      break;
    case ConstraintType::Revolute:
      out = position;
      out.push_back("rot_" + i + p);
      out.push_back("rot_" + i + q);
      if (c.drive) out.push_back("angle");
      break;
    case ConstraintType::Prismatic:
      out = {"slide_" + p, "slide_" + q};
      out.insert(out.end(), lock.begin(), lock.end());
      if (c.drive) out.push_back("displacement");
      break;
    case ConstraintType::Distance: out = {"length"}; break;
  }
  for (auto& label : out) label = c.name + "/" + label;
  return out;
}

/// Appends the constraint at the next rows of Φ and labels its rows ("<name>/x", …).
inline void addConstraint(Model& model, Constraint c) {
  c.rows = constraintRows(c.type, c.drive.has_value());
  c.row = model.m;
  c.row_labels = constraintRowLabels(c);
  model.m += c.rows;
  model.constraints.push_back(std::move(c));
}

}  // namespace cranesim
