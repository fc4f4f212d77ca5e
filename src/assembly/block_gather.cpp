#include "cranesim/assembly/block_gather.hpp"

#include <algorithm>

namespace cranesim {

std::size_t BlockGather::add(const SparsityPattern& pattern, int block) {
  const std::size_t offset = buffer_size_;
  listed_.push_back({block, offset});
  buffer_size_ += pattern.slots(block).size();
  return offset;
}

void BlockGather::finalize(const SparsityPattern& pattern) {
  // Each value's places in listing order; a value with one place is that place's alone, the
  // others are grouped by how many places they have.
  std::vector<std::vector<int>> sources(pattern.nonZeros());
  for (const Listed& l : listed_) {
    const std::vector<int>& slots = pattern.slots(l.block);
    for (std::size_t k = 0; k < slots.size(); ++k) sources[slots[k]].push_back(static_cast<int>(l.offset + k));
  }
  exclusive_value_.assign(buffer_size_, -1);
  shared_.clear();
  for (int s = 0; s < pattern.nonZeros(); ++s) {
    const int count = static_cast<int>(sources[s].size());
    if (count == 1) {
      exclusive_value_[sources[s][0]] = s;
      continue;
    }
    auto group = std::find_if(shared_.begin(), shared_.end(), [&](const Group& g) { return g.count == count; });
    if (group == shared_.end()) group = shared_.insert(shared_.end(), Group{count, {}, {}});
    group->value.push_back(s);
    group->source.insert(group->source.end(), sources[s].begin(), sources[s].end());
  }
}

void BlockGather::writeExclusive(std::size_t begin, std::size_t end, const double* buffer, double* values) const {
  for (std::size_t k = begin; k < end; ++k)
    if (const int v = exclusive_value_[k]; v >= 0) values[v] = 0.0 + buffer[k];  // 0 + x: the scatter's −0 → +0
}

void BlockGather::gatherShared(const double* buffer, double* values) const {
  for (const Group& g : shared_) {
    const int* source = g.source.data();
    for (int v : g.value) {
      double sum = 0.0;
      for (int i = 0; i < g.count; ++i) sum += buffer[source[i]];
      values[v] = sum;
      source += g.count;
    }
  }
}

}  // namespace cranesim
