#pragma once
// IDAS' linear solver on SparseLU (math/sparse_lu.hpp): the same KLU factorisation as SUNDIALS'
// KLU module, with SparseLU's test of when the old pivots may be reused. SUNDIALS' module
// refactors on the old pivots, and when min|u_ii| / max|u_ii| falls below ε^(2/3) it estimates
// the condition number (klu_condest, several solves) and, that being large too, factorises anew
// with pivoting: on a crane's DAE Jacobian, whose scaling keeps that ratio small whatever the
// pivots, every linear setup paid for a refactorisation, a condition estimate and a full
// factorisation. SparseLU judges the refactored pivots by their growth instead. It orders the
// matrix by KLU's default, AMD on A + Aᵀ, where SUNDIALS' module chose COLAMD.

#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>

namespace cranesim {

/// A direct SUNLinearSolver for compressed-sparse-column SUNSparseMatrix systems; free it with
/// SUNLinSolFree.
SUNLinearSolver sparseLuLinearSolver(SUNContext context);

/// The solver's next setup pivots anew (SparseLU::forgetPivots).
void forgetPivots(SUNLinearSolver solver);

}  // namespace cranesim
