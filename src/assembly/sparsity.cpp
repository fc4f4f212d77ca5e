#include "cranesim/assembly/sparsity.hpp"

#include <algorithm>

namespace cranesim {

int SparsityPattern::addBlock(const std::vector<int>& rows, const std::vector<int>& cols,
                              bool diagonal) {
  const int block = static_cast<int>(slots_.size());
  int index = 0;
  if (diagonal) {
    for (std::size_t k = 0; k < rows.size(); ++k) entries_.push_back({rows[k], cols[k], block, index++});
  } else {
    for (int c : cols)
      for (int r : rows) entries_.push_back({r, c, block, index++});
  }
  slots_.emplace_back(index, -1);
  return block;
}

void SparsityPattern::finalize(int n) {
  n_ = n;
  std::sort(entries_.begin(), entries_.end(), [](const Entry& a, const Entry& b) {
    return a.col != b.col ? a.col < b.col : a.row < b.row;
  });
  column_pointer_.assign(n + 1, 0);
  row_index_.clear();
  for (std::size_t k = 0; k < entries_.size(); ++k) {
    const Entry& e = entries_[k];
    const bool repeated = k > 0 && entries_[k - 1].col == e.col && entries_[k - 1].row == e.row;
    if (!repeated) {
      row_index_.push_back(e.row);
      ++column_pointer_[e.col + 1];
    }
    slots_[e.block][e.index] = static_cast<int>(row_index_.size()) - 1;
  }
  for (int c = 0; c < n; ++c) column_pointer_[c + 1] += column_pointer_[c];
  entries_.clear();
  entries_.shrink_to_fit();
}

}  // namespace cranesim
