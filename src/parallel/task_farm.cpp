#include "cranesim/parallel/task_farm.hpp"

#include <fmt/format.h>

#include <cstdlib>

namespace cranesim {

std::optional<long> TaskQueue::next() {
  const std::lock_guard<std::mutex> guard(lock_);
  if (abandoned_ || (stop_ && *stop_) || next_ == pending_.size()) return std::nullopt;
  return pending_[next_++];
}

LocalWorkers::LocalWorkers(TaskQueue& queue, int jobs, const TaskWork& work, const std::string& label) {
  for (int k = 0; k < jobs; ++k)
    threads_.emplace_back([&queue, work, worker = fmt::format("{}thread {}", label, k)] {
      while (const std::optional<long> task = queue.next()) work(*task, worker);
    });
}

void LocalWorkers::join() {
  for (std::thread& t : threads_)
    if (t.joinable()) t.join();
}

bool startedByMpiLauncher() {
  for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "PMI_RANK", "MPI_LOCALNRANKS"})
    if (std::getenv(variable)) return true;
  return false;
}

#ifndef CRANESIM_WITH_MPI
int agreeOnVerdict(const MpiSession*, int verdict) { return verdict; }
#endif

}  // namespace cranesim
