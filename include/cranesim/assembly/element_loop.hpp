#pragma once
// The loop over the elements, serial or in parallel (TBB). Many cheap elements pay for the
// threads, and so do a few expensive ones (a crane of eight super truss elements): the first
// call runs serially and times itself, and later calls run in parallel when the model has many
// elements or that first call took long enough to be worth TBB's overhead. Each element writes
// to its own scratch, so the results do not depend on the choice.

#include <tbb/parallel_for.h>

#include <chrono>
#include <cstddef>

namespace cranesim {

class ElementLoop {
 public:
  template <class Body> void run(std::size_t n, const Body& body) {
    if (mode_ == Mode::Parallel) {
      tbb::parallel_for(std::size_t{0}, n, body);
      return;
    }
    const auto start = std::chrono::steady_clock::now();
    for (std::size_t e = 0; e < n; ++e) body(e);
    if (mode_ == Mode::Undecided) {
      const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
      mode_ = (n >= kManyElements || (n > 1 && took.count() > kWorthThreads)) ? Mode::Parallel : Mode::Serial;
    }
  }

 private:
  static constexpr std::size_t kManyElements = 32;
  static constexpr double kWorthThreads = 2e-4;  // s: ~10× the cost of a parallel_for on 2 cores
  enum class Mode { Undecided, Serial, Parallel };
  Mode mode_ = Mode::Undecided;
};

}  // namespace cranesim
