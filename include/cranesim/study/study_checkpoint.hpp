#pragma once
// The finished rows of a study, kept beside its results as `<out>.checkpoint`: one line per row
// (case_row.hpp), appended and synced to disk as rows arrive, so that a study stopped by a
// signal, a batch system's time limit or a crash resumes (`--resume`) without computing them
// again. The first line identifies the study (a hash of its text, its scene's text and the
// engine version): the checkpoint of another study is refused, not mixed in.

#include <string>
#include <vector>

#include "cranesim/study/case_row.hpp"
#include "cranesim/study/study.hpp"

namespace cranesim {

class StudyCheckpoint {
 public:
  /// The checkpoint of `study` at `path`; nothing is read or written yet.
  StudyCheckpoint(std::string path, const Study& study);
  ~StudyCheckpoint();
  StudyCheckpoint(const StudyCheckpoint&) = delete;
  StudyCheckpoint& operator=(const StudyCheckpoint&) = delete;

  const std::string& path() const { return path_; }
  bool exists() const;
  /// The rows recorded so far (the last of a file cut short by a crash is dropped). Throws
  /// SceneError at "--resume" when the file is another study's.
  std::vector<CaseRow> load() const;
  /// Opens the file for appending; `fresh` starts it anew. Throws when it cannot be written.
  void open(bool fresh);
  /// Appends a row and syncs it to disk; throws when that fails.
  void append(const CaseRow& row);
  /// Closes and deletes the file (the study's results are written).
  void remove();

 private:
  std::string path_, header_;
  std::size_t figures_ = 0;
  int fd_ = -1;
};

}  // namespace cranesim
