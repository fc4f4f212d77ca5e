#include "cranesim/study/study_execution.hpp"

#include <fmt/format.h>

#include <filesystem>

namespace cranesim {

std::optional<long> CaseQueue::next() {
  const std::lock_guard<std::mutex> guard(lock_);
  if (abandoned_ || (stop_ && *stop_) || next_ == pending_.size()) return std::nullopt;
  return pending_[next_++];
}

CaseRow computeCase(const Study& study, long index, const StudyExecution& execution) {
  CaseOptions options;
  options.stop = execution.stop;
  if (!execution.cases_dir.empty())
    options.results_path = (std::filesystem::path(execution.cases_dir) / fmt::format("case_{:05d}.h5", index)).string();
  return runCase(study, index, options);
}

LocalWorkers::LocalWorkers(const Study& study, CaseQueue& queue, int jobs, const StudyExecution& execution,
                           const RowSink& sink, const std::string& label) {
  for (int k = 0; k < jobs; ++k)
    threads_.emplace_back([&study, &queue, execution, sink, worker = fmt::format("{}thread {}", label, k)] {
      while (const std::optional<long> index = queue.next()) {
        CaseRow row = computeCase(study, *index, execution);
        row.worker = worker;
        sink(std::move(row));
      }
    });
}

void LocalWorkers::join() {
  for (std::thread& t : threads_)
    if (t.joinable()) t.join();
}

}  // namespace cranesim
