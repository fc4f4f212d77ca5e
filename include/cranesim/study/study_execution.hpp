#pragma once
// How a study's cases are computed: a queue hands out case numbers one at a time to whichever
// worker asks next (threads here, MPI ranks in mpi_study.hpp), so that cases of very different
// length balance themselves; each case is computed exactly once, and its row goes to one sink.

#include <atomic>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "cranesim/study/case_runner.hpp"

namespace cranesim {

/// The cases still to compute. Thread-safe. Runs dry when every case has been handed out, when
/// `stop` is set (a signal) or when the study is abandoned.
class CaseQueue {
 public:
  CaseQueue(std::vector<long> pending, const std::atomic<bool>* stop) : pending_(std::move(pending)), stop_(stop) {}
  std::optional<long> next();
  /// Hands out no more cases (a row that cannot be recorded ends the study).
  void abandon() { abandoned_ = true; }

 private:
  std::mutex lock_;
  std::vector<long> pending_;
  std::size_t next_ = 0;
  const std::atomic<bool>* stop_;
  std::atomic<bool> abandoned_{false};
};

/// What every worker needs besides the study and the case number.
struct StudyExecution {
  const std::atomic<bool>* stop = nullptr;
  std::string cases_dir;  // where each case's full results go (keep_results); empty: nowhere
};

/// Computes case `index` (case_runner.hpp) with its results file in `execution.cases_dir`:
/// case_00017.h5, numbered with at least five digits.
CaseRow computeCase(const Study& study, long index, const StudyExecution& execution);

/// Receives each finished row; must be thread-safe.
using RowSink = std::function<void(CaseRow)>;

/// `jobs` threads, each taking the queue's next case until it runs dry; their rows name them
/// `<label> thread <k>`.
class LocalWorkers {
 public:
  LocalWorkers(const Study& study, CaseQueue& queue, int jobs, const StudyExecution& execution, const RowSink& sink,
               const std::string& label);
  /// Waits for every thread to finish.
  void join();
  ~LocalWorkers() { join(); }

 private:
  std::vector<std::thread> threads_;
};

}  // namespace cranesim
