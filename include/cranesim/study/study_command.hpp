#pragma once
// `crane-sim study STUDY [-o RESULTS.h5] [--jobs N] [--resume]`: reads and checks the study,
// computes its cases on N threads (and across MPI ranks when started by mpirun or srun), keeps
// finished rows in a checkpoint as they arrive, and writes the case table.

#include <atomic>
#include <string>

namespace cranesim {

struct StudyCommand {
  std::string study_path;
  std::string out;  // default: <study stem>.h5 in the working directory
  int jobs = 1;     // threads computing cases in this process
  bool resume = false;
  bool quiet = false;
  const std::atomic<bool>* stop = nullptr;  // set by a signal
  const std::atomic<int>* signal = nullptr;  // which one
};

/// The exit code: 0 when every case was computed (some may have failed: their rows say so), 2
/// for a bad study file or options (nothing written), 1 when the results cannot be written, 128 +
/// the signal's number when a signal stopped the study (the rows so far are written, the
/// checkpoint kept for --resume).
int runStudyCommand(const StudyCommand& command);

}  // namespace cranesim
