#include "cranesim/elements/cable.hpp"
#include "cranesim/elements/rigid_body.hpp"
#include "cranesim/elements/rotated_ends.hpp"
#include "cranesim/elements/spline_beam.hpp"
#include "cranesim/elements/spline_rope.hpp"
#include "cranesim/elements/strut_tie.hpp"
#include "cranesim/elements/timoshenko_beam.hpp"
#include "cranesim/model/kernel_elements.hpp"

// The bodies and members of a scene in one translation unit: their kernels share most of their
// AD instantiations (rotations, the Timoshenko beam under the rotated-ends beam), which would be
// compiled once per kernel apart.

namespace cranesim {

std::unique_ptr<Element> makeElement(RigidBodyKernel kernel, std::vector<int> nodes, std::vector<int> q_indices, std::vector<int> v_indices) {
  return std::make_unique<KernelElement<RigidBodyKernel>>(std::move(kernel), std::move(nodes), std::move(q_indices), std::move(v_indices));
}

std::unique_ptr<Element> makeElement(StrutTieKernel kernel, std::vector<int> nodes, std::vector<int> q_indices, std::vector<int> v_indices) {
  return std::make_unique<KernelElement<StrutTieKernel>>(std::move(kernel), std::move(nodes), std::move(q_indices), std::move(v_indices));
}

std::unique_ptr<Element> makeElement(SplineRopeKernel kernel, std::vector<int> nodes, std::vector<int> q_indices, std::vector<int> v_indices) {
  return std::make_unique<KernelElement<SplineRopeKernel>>(std::move(kernel), std::move(nodes), std::move(q_indices), std::move(v_indices));
}

std::unique_ptr<Element> makeElement(CableKernel kernel, std::vector<int> nodes, std::vector<int> q_indices, std::vector<int> v_indices) {
  return std::make_unique<KernelElement<CableKernel>>(std::move(kernel), std::move(nodes), std::move(q_indices), std::move(v_indices));
}

std::unique_ptr<Element> makeElement(TimoshenkoBeamKernel kernel, std::vector<int> nodes, std::vector<int> q_indices, std::vector<int> v_indices) {
  kernel.keepStiffness();
  return std::make_unique<KernelElement<TimoshenkoBeamKernel>>(std::move(kernel), std::move(nodes), std::move(q_indices), std::move(v_indices));
}

std::unique_ptr<Element> makeElement(RotatedEndsBeamKernel kernel, std::vector<int> nodes, std::vector<int> q_indices, std::vector<int> v_indices) {
  return std::make_unique<KernelElement<RotatedEndsBeamKernel>>(std::move(kernel), std::move(nodes), std::move(q_indices), std::move(v_indices));
}

std::unique_ptr<Element> makeElement(SplineBeamKernel kernel, std::vector<int> nodes, std::vector<int> q_indices, std::vector<int> v_indices) {
  return std::make_unique<KernelElement<SplineBeamKernel>>(std::move(kernel), std::move(nodes), std::move(q_indices), std::move(v_indices));
}

}  // namespace cranesim
