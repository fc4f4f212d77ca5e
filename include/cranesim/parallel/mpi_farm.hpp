#pragma once
// The task farm across MPI ranks (docs/architecture.md#task-farm), built when CMake finds MPI:
// rank 0 is the master. It keeps the queue and its own LocalWorkers, and hands the queue's tasks
// to ranks 1 … N−1 one at a time as each sends back the result of its last task, as bytes; rank 0
// alone decodes and records them (and writes files: Debian's HDF5 is the serial library). Only
// rank 0's main thread calls MPI (MPI_THREAD_FUNNELED).

#include <functional>
#include <string>

#include "cranesim/parallel/task_farm.hpp"

namespace cranesim {

/// MPI_Init_thread on construction, MPI_Finalize on finish() or destruction.
class MpiSession {
 public:
  MpiSession();
  ~MpiSession() { finish(); }
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }
  /// Rank 0's `value` on every rank.
  int broadcast(int value) const;
  /// Rank 0's `bytes` on every rank.
  void broadcast(std::string& bytes) const;
  /// Ends MPI on this rank (collective: every rank calls it), e.g. when the farmed part of a
  /// command is over and rank 0 goes on alone.
  void finish();
  /// Ends every rank of the job with `code` (a rank that cannot take part).
  [[noreturn]] void abort(int code) const;

 private:
  int rank_ = 0, size_ = 1;
  bool finished_ = false;
};

/// Rank 0: serves the queue's tasks to ranks 1 … size−1 until it runs dry and each rank has been
/// told to stop; each result goes to `receive` with the rank that computed it (on this thread).
/// Returns when every rank has stopped.
void serveTasksToRanks(const MpiSession& session, TaskQueue& queue,
                       const std::function<void(std::string result, int rank)>& receive);

/// Ranks 1 …: asks rank 0 for tasks, computes each (`compute(task, worker)` with worker
/// `rank <r>`; never empty) and sends back the result, until told to stop.
void computeTasksForRank0(const MpiSession& session, const std::function<std::string(long, const std::string&)>& compute);

}  // namespace cranesim
