#pragma once
// A pattern's value array as sums of dense blocks kept side by side in one buffer. The blocks
// are computed in parallel, each into its own places in the buffer, with no zeroing and no sums
// shared between threads. A value that one block alone reaches (86 % of the crane's) is written
// by the task that computed that block, right after it (writeExclusive); the values that several
// blocks reach are gathered after the parallel loop (gatherShared), their entries summed in the
// order the blocks were listed. Either way the values are the serial scatter's, bit for bit,
// whatever the threads.

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
  /// The values reached only by the buffer places [begin, end).
  void writeExclusive(std::size_t begin, std::size_t end, const double* buffer, double* values) const;
  /// The values reached by several blocks: Σ buffer[k] over their places in listing order.
  void gatherShared(const double* buffer, double* values) const;

 private:
  struct Listed {
    int block;
    std::size_t offset;
  };
  /// The shared values made of `count` entries each: value[j] = Σ buffer[source[count j + i]],
  /// i < count. Grouped by count, the inner loop's length is fixed (a loop of varying length
  /// mispredicts its exit once per value).
  struct Group {
    int count;
    std::vector<int> value, source;
  };
  std::vector<Listed> listed_;
  std::size_t buffer_size_ = 0;
  std::vector<int> exclusive_value_;  // by buffer place: the value it alone reaches, or −1
  std::vector<Group> shared_;
};

}  // namespace cranesim
