#include "cranesim/solvers/sparse_lu_linear_solver.hpp"

#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <new>
#include <vector>

#include "cranesim/math/sparse_lu.hpp"

namespace cranesim {
namespace {

struct Content {
  SparseLU lu;
  std::vector<int> outer, inner;  // the matrix' pattern in KLU's index type
  sunindextype last_flag = SUNLS_SUCCESS;
};

Content& content(SUNLinearSolver S) { return *static_cast<Content*>(S->content); }

SUNLinearSolver_Type type(SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; }
SUNLinearSolver_ID id(SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; }
int initialize(SUNLinearSolver S) { return static_cast<int>(content(S).last_flag = SUNLS_SUCCESS); }

int setup(SUNLinearSolver S, SUNMatrix A) {
  Content& c = content(S);
  if (SUNMatGetID(A) != SUNMATRIX_SPARSE || SUNSparseMatrix_SparseType(A) != CSC_MAT)
    return static_cast<int>(c.last_flag = SUNLS_ILL_INPUT);
  const sunindextype n = SUNSparseMatrix_Columns(A);
  const sunindextype* Ap = SUNSparseMatrix_IndexPointers(A);
  const sunindextype* Ai = SUNSparseMatrix_IndexValues(A);
  c.outer.assign(Ap, Ap + n + 1);
  c.inner.assign(Ai, Ai + Ap[n]);
  const bool factorised = c.lu.factorise(static_cast<int>(n), c.outer.data(), c.inner.data(), SUNSparseMatrix_Data(A));
  return static_cast<int>(c.last_flag = factorised ? SUNLS_SUCCESS : SUNLS_PACKAGE_FAIL_REC);
}

int solve(SUNLinearSolver S, SUNMatrix, N_Vector x, N_Vector b, realtype) {
  N_VScale(1.0, b, x);
  content(S).lu.solve(N_VGetArrayPointer(x));
  return static_cast<int>(content(S).last_flag = SUNLS_SUCCESS);
}

sunindextype lastFlag(SUNLinearSolver S) { return content(S).last_flag; }

int release(SUNLinearSolver S) {
  if (S == nullptr) return SUNLS_SUCCESS;
  delete static_cast<Content*>(S->content);
  S->content = nullptr;
  SUNLinSolFreeEmpty(S);
  return SUNLS_SUCCESS;
}

}  // namespace

void forgetPivots(SUNLinearSolver solver) { content(solver).lu.forgetPivots(); }

SUNLinearSolver sparseLuLinearSolver(SUNContext context) {
  SUNLinearSolver S = SUNLinSolNewEmpty(context);
  if (S == nullptr) throw std::bad_alloc();
  S->ops->gettype = type;
  S->ops->getid = id;
  S->ops->initialize = initialize;
  S->ops->setup = setup;
  S->ops->solve = solve;
  S->ops->lastflag = lastFlag;
  S->ops->free = release;
  S->content = new Content;
  return S;
}

}  // namespace cranesim
