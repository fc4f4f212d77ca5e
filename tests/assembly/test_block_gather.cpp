// BlockGather (assembly/block_gather.hpp): the values written by each block's task (those it alone
// reaches) and gathered after them (those several reach) equal, bit for bit, the blocks scattered
// and added in the order they were listed, for overlapping blocks, diagonal blocks and a value
// that only one block reaches.

#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "cranesim/assembly/block_gather.hpp"
#include "cranesim/assembly/sparsity.hpp"

using namespace cranesim;

TEST_CASE("Block sums written and gathered equal the blocks scattered in listing order", "[assembly]") {
  SparsityPattern pattern;
  std::vector<int> blocks = {
      pattern.addBlock({0, 1, 2}, {0, 1, 2}),                    // overlaps the next two
      pattern.addBlock({1, 2, 3, 4}, {2, 3}),                    //
      pattern.addBlock({0, 1, 2, 3, 4}, {0, 1, 2, 3, 4}, true),  // diagonal
      pattern.addBlock({4}, {0}),                                // a value no other block reaches
      pattern.addBlock({2, 3}, {2, 3}),                          // inside the first two
  };
  pattern.finalize(5);
  // Listed in an order other than the registration, as the Assembler lists a constraint's blocks.
  const std::vector<int> order = {blocks[2], blocks[0], blocks[4], blocks[3], blocks[1]};
  BlockGather gather;
  std::vector<std::size_t> offset;
  for (int b : order) offset.push_back(gather.add(pattern, b));
  gather.finalize(pattern);

  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> buffer(gather.bufferSize());
  for (double& x : buffer) x = u(rng) * std::pow(10.0, 8.0 * u(rng));  // magnitudes 1e-8…1e8: order matters
  std::vector<double> scattered(pattern.nonZeros(), 0.0);
  for (std::size_t i = 0; i < order.size(); ++i) {
    const std::vector<int>& slots = pattern.slots(order[i]);
    for (std::size_t k = 0; k < slots.size(); ++k) scattered[slots[k]] += buffer[offset[i] + k];
  }
  std::vector<double> gathered(pattern.nonZeros(), -1.0);
  for (std::size_t i = order.size(); i-- > 0;)  // the tasks in any order
    gather.writeExclusive(offset[i], offset[i] + pattern.slots(order[i]).size(), buffer.data(), gathered.data());
  gather.gatherShared(buffer.data(), gathered.data());
  REQUIRE(gathered == scattered);
  CHECK(gather.bufferSize() == 9 + 8 + 5 + 1 + 4);
  CHECK(pattern.nonZeros() == 9 + 6 + 1 + 1);  // the second block adds 6 values, the diagonal (4, 4), then (4, 0)
}
