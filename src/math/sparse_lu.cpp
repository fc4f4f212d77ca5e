#include "cranesim/math/sparse_lu.hpp"

#include <klu.h>

#include <algorithm>
#include <vector>

namespace cranesim {

struct SparseLU::Klu {
  static constexpr double kRefactorConditionLimit = 3.7e-11;  // ε^(2/3)
  static constexpr double kGrowthTolerance = 1e-2;  // refactored pivot growth / pivoted pivot growth

  klu_common common;
  klu_symbolic* symbolic = nullptr;
  klu_numeric* numeric = nullptr;
  int n = 0;
  std::vector<int> outer, inner;  // the pattern `symbolic` was analysed for
  double pivoted_growth = 0.0;     // reciprocal pivot growth of the last factorisation with pivoting
  int pivotings = 0;               // factorisations with pivoting so far

  Klu() { klu_defaults(&common); }
  ~Klu() { release(); }
  void release() {
    if (numeric) klu_free_numeric(&numeric, &common);
    if (symbolic) klu_free_symbolic(&symbolic, &common);
  }
  bool analysed(int size, const int* Ap, const int* Ai) const {
    return symbolic && size == n && std::equal(outer.begin(), outer.end(), Ap) &&
           std::equal(inner.begin(), inner.end(), Ai);
  }
};

SparseLU::SparseLU() : klu_(std::make_unique<Klu>()) {}
SparseLU::~SparseLU() = default;
SparseLU::SparseLU(SparseLU&&) noexcept = default;
SparseLU& SparseLU::operator=(SparseLU&&) noexcept = default;

bool SparseLU::factorise(int n, const int* Ap, const int* Ai, const double* Ax) {
  Klu& k = *klu_;
  // KLU's interface takes non-const arrays but does not write them.
  int* ap = const_cast<int*>(Ap);
  int* ai = const_cast<int*>(Ai);
  double* ax = const_cast<double*>(Ax);
  if (!k.analysed(n, Ap, Ai)) {
    k.release();
    k.n = n;
    k.outer.assign(Ap, Ap + n + 1);
    k.inner.assign(Ai, Ai + Ap[n]);
    k.symbolic = klu_analyze(n, ap, ai, &k.common);
    if (!k.symbolic) return false;
  }
  if (k.numeric && klu_refactor(ap, ai, ax, k.symbolic, k.numeric, &k.common) && stableRefactor(ap, ai, ax)) return true;
  if (k.numeric) klu_free_numeric(&k.numeric, &k.common);
  k.numeric = klu_factor(ap, ai, ax, k.symbolic, &k.common);
  if (k.numeric == nullptr || k.common.status != KLU_OK) return false;
  ++k.pivotings;
  k.pivoted_growth = klu_rgrowth(ap, ai, ax, k.symbolic, k.numeric, &k.common) ? k.common.rgrowth : 0.0;
  return true;
}

bool SparseLU::stableRefactor(int* Ap, int* Ai, double* Ax) {
  Klu& k = *klu_;
  if (klu_rcond(k.symbolic, k.numeric, &k.common) && k.common.rcond > Klu::kRefactorConditionLimit) return true;
  return k.pivoted_growth > 0.0 && klu_rgrowth(Ap, Ai, Ax, k.symbolic, k.numeric, &k.common) &&
         k.common.rgrowth >= Klu::kGrowthTolerance * k.pivoted_growth;
}

void SparseLU::solve(double* x) {
  Klu& k = *klu_;
  klu_solve(k.symbolic, k.numeric, k.n, 1, x, &k.common);
}

void SparseLU::forgetPivots() {
  Klu& k = *klu_;
  if (k.numeric) klu_free_numeric(&k.numeric, &k.common);
}

int SparseLU::pivotedFactorisations() const { return klu_->pivotings; }

long SparseLU::factorNonZeros() const {
  const Klu& k = *klu_;
  return k.numeric ? static_cast<long>(k.numeric->lnz) + k.numeric->unz : 0;
}

}  // namespace cranesim
