#pragma once
// Elements from the kernels the scene compiler builds. The factories are compiled in
// src/elements/ (the two truss sections apart, as the largest), where KernelElement<Kernel> and
// its forward-AD Jacobians are instantiated once: they are the costliest code of the project to
// compile, and no other translation unit (scene compiler, tests) instantiates them again.

#include <memory>
#include <vector>

#include "cranesim/model/element.hpp"

namespace cranesim {

struct RigidBodyKernel;
struct StrutTieKernel;
struct SplineRopeKernel;
struct CableKernel;
struct TimoshenkoBeamKernel;
struct RotatedEndsBeamKernel;
struct SplineBeamKernel;
struct SuperTrussKernel;
struct CondensedTrussKernel;

/// KernelElement<Kernel> on `nodes`, reading q at `q_indices` and dq at `v_indices`.
std::unique_ptr<Element> makeElement(RigidBodyKernel kernel, std::vector<int> nodes, std::vector<int> q_indices, std::vector<int> v_indices);
std::unique_ptr<Element> makeElement(StrutTieKernel kernel, std::vector<int> nodes, std::vector<int> q_indices, std::vector<int> v_indices);
std::unique_ptr<Element> makeElement(SplineRopeKernel kernel, std::vector<int> nodes, std::vector<int> q_indices, std::vector<int> v_indices);
std::unique_ptr<Element> makeElement(CableKernel kernel, std::vector<int> nodes, std::vector<int> q_indices, std::vector<int> v_indices);
std::unique_ptr<Element> makeElement(TimoshenkoBeamKernel kernel, std::vector<int> nodes, std::vector<int> q_indices, std::vector<int> v_indices);
std::unique_ptr<Element> makeElement(RotatedEndsBeamKernel kernel, std::vector<int> nodes, std::vector<int> q_indices, std::vector<int> v_indices);
std::unique_ptr<Element> makeElement(SplineBeamKernel kernel, std::vector<int> nodes, std::vector<int> q_indices, std::vector<int> v_indices);
std::unique_ptr<Element> makeElement(SuperTrussKernel kernel, std::vector<int> nodes, std::vector<int> q_indices, std::vector<int> v_indices);
std::unique_ptr<Element> makeElement(CondensedTrussKernel kernel, std::vector<int> nodes, std::vector<int> q_indices, std::vector<int> v_indices);

}  // namespace cranesim
