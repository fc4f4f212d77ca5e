#include "cranesim/study/study_command.hpp"

#include <fmt/format.h>
#include <tbb/global_control.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <limits>
#include <map>
#include <mutex>
#include <optional>

#include "cranesim/io/command_line.hpp"
#include "cranesim/io/study_writer.hpp"
#include "cranesim/study/study_checkpoint.hpp"
#include "cranesim/parallel/task_farm.hpp"
#include "cranesim/study/study_execution.hpp"
#ifdef CRANESIM_WITH_MPI
#include "cranesim/parallel/mpi_farm.hpp"
#endif

namespace cranesim {
namespace {

/// Rank 0's part (or the whole study without MPI): the checkpoint, the rows, the results file.
class StudyBook {
 public:
  StudyBook(const Study& study, const StudyCommand& command, std::string out)
      : study_(study), command_(command), out_(std::move(out)), checkpoint_(out_ + ".checkpoint", study) {
    rows_.resize(static_cast<std::size_t>(study.cases));
    for (long i = 0; i < study.cases; ++i) {
      rows_[i].index = i;
      rows_[i].figures.assign(study.figures.size(), std::numeric_limits<double>::quiet_NaN());
    }
    if (!command.resume && checkpoint_.exists())
      throw SceneError({"-o", 0, 0}, fmt::format("'{}' holds the finished cases of a stopped study: continue it with "
                                                 "--resume, or remove it to start anew", checkpoint_.path()));
    if (command.resume && checkpoint_.exists())
      for (CaseRow& row : checkpoint_.load())
        if (row.index < study.cases && !done(row.index)) rows_[row.index] = std::move(row), ++finished_;
    checkpoint_.open(!(command.resume && checkpoint_.exists()));
    if (finished_ > 0 && !command.quiet)
      fmt::print(stderr, "resuming: {} of {} cases finished before\n", finished_, study.cases);
    resumed_ = finished_;
  }

  std::vector<long> pending() const {
    std::vector<long> out;
    for (long i = 0; i < study_.cases; ++i)
      if (!done(i)) out.push_back(i);
    return out;
  }

  /// A row from any worker: recorded in the checkpoint, then in the table.
  void record(CaseRow row, TaskQueue& queue) {
    const std::lock_guard<std::mutex> guard(lock_);
    if (row.status == kCaseInterrupted || done(row.index)) return;
    try {
      checkpoint_.append(row);
    } catch (const std::exception& e) {
      if (error_.empty()) error_ = e.what();
      queue.abandon();
      return;
    }
    if (row.status != kCaseComplete && !command_.quiet)
      fmt::print(stderr, "{}case {}: {}: {}\n", isatty(STDERR_FILENO) ? "\r" : "", row.index, row.status, row.message);
    rows_[row.index] = std::move(row);
    ++finished_;
    if (!command_.quiet && isatty(STDERR_FILENO))
      fmt::print(stderr, "\r  {} of {} cases finished   ", finished_, study_.cases);
  }

  /// Writes the results; the exit code. `execution` says who computed the cases.
  int finish(double wall_time_s, const std::string& execution) {
    const bool stopped = finished_ < study_.cases;
    std::string message;
    if (!error_.empty()) message = error_;
    else if (stopped) message = fmt::format("interrupted with {} of {} cases finished; continue with --resume", finished_, study_.cases);
    writeStudyResults(out_, study_, rows_, message, execution);
    if (message.empty()) checkpoint_.remove();
    if (!command_.quiet) {
      std::map<std::string, long> by_status;
      for (const CaseRow& row : rows_) ++by_status[row.status];
      std::string counts;
      for (const auto& [status, count] : by_status) counts += fmt::format("{}{} {}", counts.empty() ? "" : ", ", count, status);
      const long computed = finished_ - resumed_;
      fmt::print(stderr, "{}study: {} cases ({}); {} computed by {} in {:.3g} s wall, {:.4g} cases/hour\n",
                 isatty(STDERR_FILENO) ? "\r" : "", study_.cases, counts, computed, execution, wall_time_s,
                 computed / std::max(wall_time_s, 1e-9) * 3600.0);
      fmt::print(stderr, "  results: {}{}\n", out_, message.empty() ? "" : " (incomplete; checkpoint " + checkpoint_.path() + ")");
    }
    if (!error_.empty()) {
      fmt::print(stderr, "error: {}\n", error_);
      return kExitSolverFailure;
    }
    if (stopped) return 128 + (command_.signal ? command_.signal->load() : 0);
    return 0;
  }

 private:
  bool done(long index) const { return rows_[index].status != kCaseNotRun; }

  const Study& study_;
  const StudyCommand& command_;
  std::string out_;
  StudyCheckpoint checkpoint_;
  std::vector<CaseRow> rows_;
  long finished_ = 0, resumed_ = 0;
  std::mutex lock_;
  std::string error_;
};

/// The case table's path: -o, or <study stem>.h5 in the working directory.
std::string tablePath(const StudyCommand& command) {
  return command.out.empty() ? std::filesystem::path(command.study_path).stem().string() + ".h5" : command.out;
}

/// The directory each case's full results go to: `<out stem>_cases` beside the results.
std::string casesDirectory(const std::string& out) {
  const std::filesystem::path path(out);
  return (path.parent_path() / (path.stem().string() + "_cases")).string();
}

void createCasesDirectory(const std::string& dir) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) throw SceneError({"-o", 0, 0}, fmt::format("cannot create '{}' for the cases' results: {}", dir, error.message()));
}

}  // namespace

int runStudyCommand(const StudyCommand& command) {
  const auto start = std::chrono::steady_clock::now();
  // One case per core: the cases are the parallelism, the element loops of each run serially.
  const tbb::global_control one_thread_per_case(tbb::global_control::max_allowed_parallelism, 1);
  if (command.jobs < 1) throw SceneError({"--jobs", 0, 0}, fmt::format("expected at least 1, found {}", command.jobs));
#ifdef CRANESIM_WITH_MPI
  std::optional<MpiSession> mpi;
  if (startedByMpiLauncher()) mpi.emplace();
  const MpiSession* ranks = mpi ? &*mpi : nullptr;
  const bool master = !mpi || mpi->rank() == 0;
#else
  if (startedByMpiLauncher())
    throw SceneError({"mpirun", 0, 0}, "this crane-sim was built without MPI (install libopenmpi-dev and rebuild), "
                                       "so its ranks would each run the whole study: run it without mpirun, with --jobs");
  const MpiSession* ranks = nullptr;
  const bool master = true;
#endif
  std::optional<Study> study;
  std::optional<StudyBook> book;
  std::string cases_dir;
  const int verdict = agreeOnVerdict(ranks, inputVerdict(command.study_path, master, [&] {
    study = readStudy(command.study_path);
    if (master) {
      const std::string out = outputPath(command.study_path, tablePath(command), ".h5");
      book.emplace(*study, command, out);
      if (study->keep_results) createCasesDirectory(cases_dir = casesDirectory(out));
    }
  }));
  if (verdict != 0) return verdict;

  StudyExecution execution{command.stop, cases_dir};
#ifdef CRANESIM_WITH_MPI
  if (mpi && !master) {
    if (study->keep_results) execution.cases_dir = casesDirectory(tablePath(command));
    computeTasksForRank0(*mpi, [&](long index, const std::string& worker) {
      CaseRow row = computeCase(*study, index, execution);
      row.worker = worker;
      return encodeRow(row);
    });
    return 0;
  }
#endif
  TaskQueue queue(book->pending(), command.stop);
  const RowSink sink = [&](CaseRow row) { book->record(std::move(row), queue); };
  std::string workers = fmt::format("{} thread{}", command.jobs, command.jobs == 1 ? "" : "s"), label;
#ifdef CRANESIM_WITH_MPI
  if (mpi) {
    workers = fmt::format("{} MPI rank{} ({} on rank 0, one on each other rank)", mpi->size(), mpi->size() == 1 ? "" : "s", workers);
    label = "rank 0 ";
  }
#endif
  LocalWorkers local(queue, command.jobs, [&](long index, const std::string& worker) {
    CaseRow row = computeCase(*study, index, execution);
    row.worker = worker;
    sink(std::move(row));
  }, label);
#ifdef CRANESIM_WITH_MPI
  if (mpi)
    serveTasksToRanks(*mpi, queue, [&](std::string line, int) {
      if (auto row = decodeRow(line, study->figures.size())) sink(std::move(*row));
    });
#endif
  local.join();
  return book->finish(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), workers);
}

}  // namespace cranesim
