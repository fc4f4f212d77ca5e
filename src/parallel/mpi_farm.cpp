#include "cranesim/parallel/mpi_farm.hpp"

#include <fmt/format.h>
#include <mpi.h>

#include <chrono>
#include <cstdlib>
#include <stdexcept>
#include <thread>

#include "cranesim/io/command_line.hpp"

namespace cranesim {
namespace {

constexpr int kTagResult = 1;  // worker → rank 0: the result of its last task (empty: the first request)
constexpr int kTagTask = 2;    // rank 0 → worker: a task number
constexpr int kTagStop = 3;    // rank 0 → worker: no more tasks

/// Rank 0 polls rather than blocks, so that its own workers' threads keep the cores: Open MPI's
/// blocking receive spins.
constexpr auto kPollInterval = std::chrono::milliseconds(2);

}  // namespace

MpiSession::MpiSession() {
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  if (provided < MPI_THREAD_FUNNELED) throw std::runtime_error("the MPI library does not support threads (MPI_THREAD_FUNNELED)");
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

void MpiSession::finish() {
  if (finished_) return;
  finished_ = true;
  MPI_Finalize();
}

int MpiSession::broadcast(int value) const {
  MPI_Bcast(&value, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return value;
}

void MpiSession::broadcast(std::string& bytes) const {
  long length = static_cast<long>(bytes.size());
  MPI_Bcast(&length, 1, MPI_LONG, 0, MPI_COMM_WORLD);
  bytes.resize(static_cast<std::size_t>(length));
  // In pieces below INT_MAX bytes: a map of large equilibria can exceed MPI's int count.
  constexpr long kPiece = 1L << 30;
  for (long offset = 0; offset < length; offset += kPiece)
    MPI_Bcast(bytes.data() + offset, static_cast<int>(std::min(kPiece, length - offset)), MPI_CHAR, 0, MPI_COMM_WORLD);
}

void MpiSession::abort(int code) const {
  MPI_Abort(MPI_COMM_WORLD, code);
  std::abort();
}

int agreeOnVerdict(const MpiSession* mpi, int verdict) {
  if (!mpi) return verdict;
  const int agreed = mpi->broadcast(verdict);
  if (agreed == 0 && verdict != 0) mpi->abort(kExitBadInput);
  return agreed;
}

void serveTasksToRanks(const MpiSession& session, TaskQueue& queue,
                       const std::function<void(std::string result, int rank)>& receive) {
  int working = session.size() - 1;
  while (working > 0) {
    int arrived = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, kTagResult, MPI_COMM_WORLD, &arrived, &status);
    if (!arrived) {
      std::this_thread::sleep_for(kPollInterval);
      continue;
    }
    int length = 0;
    MPI_Get_count(&status, MPI_CHAR, &length);
    std::string result(static_cast<std::size_t>(length), '\0');
    MPI_Recv(result.data(), length, MPI_CHAR, status.MPI_SOURCE, kTagResult, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (!result.empty()) receive(std::move(result), status.MPI_SOURCE);
    if (const std::optional<long> task = queue.next()) {
      long next = *task;
      MPI_Send(&next, 1, MPI_LONG, status.MPI_SOURCE, kTagTask, MPI_COMM_WORLD);
    } else {
      MPI_Send(nullptr, 0, MPI_LONG, status.MPI_SOURCE, kTagStop, MPI_COMM_WORLD);
      --working;
    }
  }
}

void computeTasksForRank0(const MpiSession& session, const std::function<std::string(long, const std::string&)>& compute) {
  const std::string worker = fmt::format("rank {}", session.rank());
  std::string result;
  for (;;) {
    MPI_Send(result.data(), static_cast<int>(result.size()), MPI_CHAR, 0, kTagResult, MPI_COMM_WORLD);
    long task = 0;
    MPI_Status status;
    MPI_Recv(&task, 1, MPI_LONG, 0, MPI_ANY_TAG, MPI_COMM_WORLD, &status);
    if (status.MPI_TAG == kTagStop) return;
    result = compute(task, worker);
  }
}

}  // namespace cranesim
