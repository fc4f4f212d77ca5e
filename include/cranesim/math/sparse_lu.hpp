#pragma once
// LU factorisation of a square sparse matrix in compressed-sparse-column form by KLU
// (SuiteSparse), for matrices factorised again and again on one pattern: the ordering and
// symbolic analysis are kept while the pattern stays the same, and the previous pivot sequence
// is reused (klu_refactor) while it stays stable; otherwise it pivots anew.
//
// Stable means: KLU's cheap condition estimate min|u_ii| / max|u_ii| above ε^(2/3) (SUNDIALS'
// own test for its KLU solver), or else the reciprocal pivot growth of the refactored factors
// (klu_rgrowth: per column, max|A| / max|U| of the scaled matrix) at least 1/100 of that of the
// last factorisation with pivoting. The first test alone refuses nearly every refactorisation
// of a DAE Jacobian [∂r/∂y + c_j ∂r/∂ẏ] of a crane: masses of 10²…10⁵ kg, rotary inertias up to
// 10⁷ kg m² and the constraint rows make min|u_ii| / max|u_ii| small for any pivots at all,
// while the pivots' quality shows in their growth.

#include <memory>

namespace cranesim {

class SparseLU {
 public:
  SparseLU();
  ~SparseLU();
  SparseLU(SparseLU&&) noexcept;
  SparseLU& operator=(SparseLU&&) noexcept;

  /// Factorises the n × n matrix (column pointers Ap, row indices Ai, values Ax); false when it
  /// is singular.
  bool factorise(int n, const int* Ap, const int* Ai, const double* Ax);
  /// Solves A x = b in place (x holds b on entry) with the latest factorisation.
  void solve(double* x);
  /// The next factorisation pivots anew, as a new SparseLU's first does; solve needs it first.
  void forgetPivots();
  /// Factorisations with pivoting so far (the others reused the pivots before them).
  int pivotedFactorisations() const;
  /// Entries of the latest factors L and U (KLU's lnz + unz, diagonals included): the fill.
  long factorNonZeros() const;

 private:
  /// Whether the factors klu_refactor just computed on the old pivots are stable (file comment).
  bool stableRefactor(int* Ap, int* Ai, double* Ax);

  struct Klu;
  std::unique_ptr<Klu> klu_;
};

}  // namespace cranesim
