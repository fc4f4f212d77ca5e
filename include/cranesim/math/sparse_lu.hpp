#pragma once
// LU factorisation of a square sparse matrix in compressed-sparse-column form by KLU
// (SuiteSparse), for matrices factorised again and again on one pattern: the ordering and
// symbolic analysis are kept while the pattern stays the same, and the previous pivot sequence
// is reused (klu_refactor) while KLU's cheap condition estimate min|u_ii| / max|u_ii| stays
// above ε^(2/3), SUNDIALS' own test for its KLU solver; otherwise it pivots anew.

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
  /// Entries of the latest factors L and U (KLU's lnz + unz, diagonals included): the fill.
  long factorNonZeros() const;

 private:
  struct Klu;
  std::unique_ptr<Klu> klu_;
};

}  // namespace cranesim
