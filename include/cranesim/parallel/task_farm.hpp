#pragma once
// A farm of numbered tasks (docs/architecture.md#task-farm): a queue hands out task numbers one
// at a time to whichever worker asks next — threads of this process here, MPI ranks in
// mpi_farm.hpp — so that tasks of very different length balance themselves, and each task is
// computed exactly once. crane-sim study farms its cases, crane-opt its static map's rows of
// boom angle.

#include <atomic>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace cranesim {

/// The tasks still to compute. Thread-safe. Runs dry when every task has been handed out, when
/// `stop` is set (a signal) or when the work is abandoned.
class TaskQueue {
 public:
  TaskQueue(std::vector<long> pending, const std::atomic<bool>* stop = nullptr)
      : pending_(std::move(pending)), stop_(stop) {}
  std::optional<long> next();
  /// Hands out no more tasks (e.g. a result that cannot be recorded ends a study).
  void abandon() { abandoned_ = true; }

 private:
  std::mutex lock_;
  std::vector<long> pending_;
  std::size_t next_ = 0;
  const std::atomic<bool>* stop_;
  std::atomic<bool> abandoned_{false};
};

/// Computes task `task` on the worker named `worker`; called from several threads at once.
using TaskWork = std::function<void(long task, const std::string& worker)>;

/// `jobs` threads, each taking the queue's next task until it runs dry; they name themselves
/// `<label>thread <k>`.
class LocalWorkers {
 public:
  LocalWorkers(TaskQueue& queue, int jobs, const TaskWork& work, const std::string& label = "");
  /// Waits for every thread to finish.
  void join();
  ~LocalWorkers() { join(); }

 private:
  std::vector<std::thread> threads_;
};

/// Whether an MPI launcher (mpirun, mpiexec, srun) started this process: it names a rank.
bool startedByMpiLauncher();

class MpiSession;  // mpi_farm.hpp

/// The exit code every rank acts on after each read the command's input: rank 0's (which alone
/// reports errors). A rank that failed where rank 0 did not ends the job: it cannot take part,
/// and rank 0 would wait for it. Without MPI (`mpi` null) `verdict` itself.
int agreeOnVerdict(const MpiSession* mpi, int verdict);

}  // namespace cranesim
