#include "cranesim/elements/condensed_truss.hpp"
#include "cranesim/model/kernel_elements.hpp"

namespace cranesim {

std::unique_ptr<Element> makeElement(CondensedTrussKernel kernel, std::vector<int> nodes, std::vector<int> q_indices, std::vector<int> v_indices) {
  return std::make_unique<KernelElement<CondensedTrussKernel>>(std::move(kernel), std::move(nodes), std::move(q_indices), std::move(v_indices));
}

}  // namespace cranesim
