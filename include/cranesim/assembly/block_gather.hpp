#pragma once
// A pattern's value array as sums of dense blocks kept side by side in one buffer. The blocks
// are computed in parallel, each into its own places in the buffer, with no zeroing and no
// sums shared between threads; each value is then gathered from its blocks' entries, summed in
// the order the blocks were listed, so the values do not depend on the threads. (Gathering in
// parallel too was measured slower on 2 cores: a second parallel loop costs more than the
// ~0.2 M instructions of the crane's gather.)

#include <cstddef>
#include <vector>

#include "cranesim/assembly/sparsity.hpp"

namespace cranesim {

class BlockGather {
 public:
  /// Lists `block` of `pattern` next; its entries (pattern.slots(block) order) take the buffer
  /// places from the returned offset on.
  std::size_t add(const SparsityPattern& pattern, int block);
  /// After every block is listed: which buffer places make up each of pattern's values.
  void finalize(const SparsityPattern& pattern);

  std::size_t bufferSize() const { return buffer_size_; }
  /// values[s] = Σ buffer[k] over the places listed for s.
  void gather(const double* buffer, double* values) const;

 private:
  struct Listed {
    int block;
    std::size_t offset;
  };
  std::vector<Listed> listed_;
  std::size_t buffer_size_ = 0;
  std::vector<int> source_pointer_;  // value s gathers source_[source_pointer_[s] .. source_pointer_[s + 1])
  std::vector<int> source_;
};

}  // namespace cranesim
