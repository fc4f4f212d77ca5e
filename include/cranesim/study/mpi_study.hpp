#pragma once
// A study across MPI ranks (DESIGN §15), built when CMake finds MPI: rank 0 is the master. It
// runs the study's bookkeeping and its own LocalWorkers, and hands the same queue's cases to
// ranks 1 … N−1 one at a time as each sends back the row of its last case; the rows go to the
// one sink on rank 0, which alone writes files (the serial HDF5 library is used by one process
// for the study's results). Only rank 0's main thread calls MPI (MPI_THREAD_FUNNELED).

#include <atomic>

#include "cranesim/study/study_execution.hpp"

namespace cranesim {

/// MPI_Init_thread on construction, MPI_Finalize on destruction.
class MpiSession {
 public:
  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }
  /// Rank 0's `value` on every rank.
  int broadcast(int value) const;
  /// Ends every rank of the job with `code` (a rank that cannot take part).
  [[noreturn]] void abort(int code) const;

 private:
  int rank_ = 0, size_ = 1;
};

/// Rank 0: serves the queue's cases to ranks 1 … size−1 until it runs dry and each rank has been
/// told to stop; their rows go to `sink`. Returns when every rank has stopped.
void serveCasesToRanks(const MpiSession& session, CaseQueue& queue, std::size_t figures, const RowSink& sink);

/// Ranks 1 …: asks rank 0 for cases, computes them and sends their rows, until told to stop.
void computeCasesForRank0(const Study& study, const StudyExecution& execution);

}  // namespace cranesim
