#include "cranesim/assembly/block_gather.hpp"

namespace cranesim {

std::size_t BlockGather::add(const SparsityPattern& pattern, int block) {
  const std::size_t offset = buffer_size_;
  listed_.push_back({block, offset});
  buffer_size_ += pattern.slots(block).size();
  return offset;
}

void BlockGather::finalize(const SparsityPattern& pattern) {
  // A counting sort of the listed entries by value, stable: each value's places in listing order.
  source_pointer_.assign(pattern.nonZeros() + 1, 0);
  for (const Listed& l : listed_)
    for (int s : pattern.slots(l.block)) ++source_pointer_[s + 1];
  for (int s = 0; s < pattern.nonZeros(); ++s) source_pointer_[s + 1] += source_pointer_[s];
  source_.resize(buffer_size_);
  std::vector<int> next(source_pointer_.begin(), source_pointer_.end() - 1);
  for (const Listed& l : listed_) {
    const std::vector<int>& slots = pattern.slots(l.block);
    for (std::size_t k = 0; k < slots.size(); ++k) source_[next[slots[k]]++] = static_cast<int>(l.offset + k);
  }
}

void BlockGather::gather(const double* buffer, double* values) const {
  const int n = static_cast<int>(source_pointer_.size()) - 1;
  for (int s = 0; s < n; ++s) {
    double sum = 0.0;
    for (int k = source_pointer_[s]; k < source_pointer_[s + 1]; ++k) sum += buffer[source_[k]];
    values[s] = sum;
  }
}

}  // namespace cranesim
