#pragma once
// IDAS' vector arithmetic compiled here. Debian's SUNDIALS 6.4 (6.4.1+dfsg1-3) is built without
// optimisation: its serial N_Vector operations spill every loop variable to the stack, and a
// weighted RMS norm of 144 entries takes ~760 ns instead of ~70 ns. IDAS calls them many times
// per step (error test and order selection, Newton's convergence test, prediction), which made
// them ~20 % of a small beam's step (docs/numerics.md).
//
// SUNDIALS dispatches every vector operation through the vector's table of operations, which
// the N_Vector interface lets a user fill, and which every clone copies (IDAS makes its work
// vectors by cloning the state vector). useCompiledSerialOps replaces the operations IDAS uses by
// the same arithmetic in the same order, special cases included (N_VLinearSum's a = ±1, a = ±b,
// in-place axpy; N_VScale in place, by ±1): the results are SUNDIALS' own, bit for bit
// (tests/math/test_serial_vector_ops.cpp compares every one against the library's function).

#include <nvector/nvector_serial.h>

namespace cranesim {

/// Replaces the hot operations of a serial vector `v` (and of every clone made of it afterwards)
/// by optimised, bit-identical implementations. Call before IDAInit / IDAQuadInit clone it.
void useCompiledSerialOps(N_Vector v);

}  // namespace cranesim
