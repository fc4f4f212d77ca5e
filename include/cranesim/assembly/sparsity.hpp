#pragma once
// A compressed-sparse-column pattern built once from dense blocks. Each block remembers where
// its entries live in the value array, so assembly is a scatter without searching.

#include <vector>

namespace cranesim {

class SparsityPattern {
 public:
  /// Registers a dense block rows × cols (entries stored column-major) and returns its id.
  /// With `diagonal`, only entries (rows[k], cols[k]) are registered.
  int addBlock(const std::vector<int>& rows, const std::vector<int>& cols, bool diagonal = false);
  /// Builds the CSC arrays of n columns; afterwards blocks can be scattered into value arrays.
  void finalize(int n);

  int size() const { return n_; }  // columns (rows too, for a square pattern)
  int nonZeros() const { return static_cast<int>(row_index_.size()); }
  const std::vector<int>& columnPointers() const { return column_pointer_; }
  const std::vector<int>& rowIndices() const { return row_index_; }
  /// Value-array positions of a block's entries (column-major, or the diagonal).
  const std::vector<int>& slots(int block) const { return slots_[block]; }

 private:
  struct Entry {
    int row, col, block, index;
  };
  std::vector<Entry> entries_;
  std::vector<std::vector<int>> slots_;
  std::vector<int> column_pointer_, row_index_;
  int n_ = 0;
};

}  // namespace cranesim
