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
  // Each value's places in listing order (a stable counting sort: value s has the places
  // place[first[s]] … place[first[s + 1] − 1]); a value with one place is that place's alone,
  // the others are grouped by how many places they have.
  const int n = pattern.nonZeros();
  std::vector<int> first(n + 1, 0);
  for (const Listed& l : listed_)
    for (int s : pattern.slots(l.block)) ++first[s + 1];
  for (int s = 0; s < n; ++s) first[s + 1] += first[s];
  std::vector<int> place(buffer_size_), next(first.begin(), first.end() - 1);
  for (const Listed& l : listed_) {
    const std::vector<int>& slots = pattern.slots(l.block);
    for (std::size_t k = 0; k < slots.size(); ++k) place[next[slots[k]]++] = static_cast<int>(l.offset + k);
  }
  exclusive_value_.assign(buffer_size_, -1);
  shared_.clear();
  for (int s = 0; s < n; ++s) {
    const int count = first[s + 1] - first[s];
    if (count == 1) {
      exclusive_value_[place[first[s]]] = s;
      continue;
    }
    auto group = std::find_if(shared_.begin(), shared_.end(), [&](const Group& g) { return g.count == count; });
    if (group == shared_.end()) group = shared_.insert(shared_.end(), Group{count, {}, {}});
    group->value.push_back(s);
    group->source.insert(group->source.end(), place.begin() + first[s], place.begin() + first[s + 1]);
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
