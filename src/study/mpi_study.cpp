#include "cranesim/study/mpi_study.hpp"

#include <fmt/format.h>
#include <mpi.h>

#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>

namespace cranesim {
namespace {

constexpr int kTagRow = 1;   // worker → rank 0: the row of its last case (empty: the first request)
constexpr int kTagCase = 2;  // rank 0 → worker: a case number
constexpr int kTagStop = 3;  // rank 0 → worker: no more cases

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

MpiSession::~MpiSession() { MPI_Finalize(); }

int MpiSession::broadcast(int value) const {
  MPI_Bcast(&value, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return value;
}

void MpiSession::abort(int code) const {
  MPI_Abort(MPI_COMM_WORLD, code);
  std::abort();
}

void serveCasesToRanks(const MpiSession& session, CaseQueue& queue, std::size_t figures, const RowSink& sink) {
  int working = session.size() - 1;
  while (working > 0) {
    int arrived = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, kTagRow, MPI_COMM_WORLD, &arrived, &status);
    if (!arrived) {
      std::this_thread::sleep_for(kPollInterval);
      continue;
    }
    int length = 0;
    MPI_Get_count(&status, MPI_CHAR, &length);
    std::string line(static_cast<std::size_t>(length), '\0');
    MPI_Recv(line.data(), length, MPI_CHAR, status.MPI_SOURCE, kTagRow, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (!line.empty())
      if (auto row = decodeRow(line, figures)) sink(std::move(*row));
    if (const std::optional<long> index = queue.next()) {
      long next = *index;
      MPI_Send(&next, 1, MPI_LONG, status.MPI_SOURCE, kTagCase, MPI_COMM_WORLD);
    } else {
      MPI_Send(nullptr, 0, MPI_LONG, status.MPI_SOURCE, kTagStop, MPI_COMM_WORLD);
      --working;
    }
  }
}

void computeCasesForRank0(const Study& study, const StudyExecution& execution) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  std::string line;
  for (;;) {
    MPI_Send(line.data(), static_cast<int>(line.size()), MPI_CHAR, 0, kTagRow, MPI_COMM_WORLD);
    long index = 0;
    MPI_Status status;
    MPI_Recv(&index, 1, MPI_LONG, 0, MPI_ANY_TAG, MPI_COMM_WORLD, &status);
    if (status.MPI_TAG == kTagStop) return;
    CaseRow row = computeCase(study, index, execution);
    row.worker = fmt::format("rank {}", rank);
    line = encodeRow(row);
  }
}

}  // namespace cranesim
