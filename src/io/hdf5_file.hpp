#pragma once
// Thin RAII helpers over the HDF5 C API for writing numeric datasets and string attributes, and
// the one way results files are written. A file is assembled in memory (HDF5's core driver) and
// then written to disk by plain, checked POSIX calls under a temporary name, synced and renamed:
// HDF5 itself never meets a failing disk (a full disk used to crash it at exit), and a failed
// write never replaces an older good file.

#include <hdf5.h>

#include <filesystem>
#include <mutex>
#include <string>
#include <vector>

namespace cranesim {

class Hdf5File {
 public:
  Hdf5File();  // an empty file in memory
  ~Hdf5File();
  Hdf5File(const Hdf5File&) = delete;
  Hdf5File& operator=(const Hdf5File&) = delete;

  /// Creates intermediate groups as needed.
  void writeDoubles(const std::string& path, const std::vector<hsize_t>& dims, const double* data);
  void writeStrings(const std::string& path, const std::vector<hsize_t>& dims, const std::vector<std::string>& values);
  void attribute(const std::string& object, const std::string& name, const std::string& value);
  void attribute(const std::string& object, const std::string& name, double value);
  void attribute(const std::string& object, const std::string& name, long value);
  void ensureGroup(const std::string& path);
  /// Writes the file's image to `path` (created or truncated) and syncs it to disk; throws when
  /// any step fails.
  void save(const std::string& path);

 private:
  hid_t file_ = -1;
};

/// The temporary name a results file at `path` is written under before it is renamed.
inline std::string partialPath(const std::string& path) { return path + ".partial"; }

/// Writes `path` by `write(Hdf5File&)`: the image saved to `path`.partial, then renamed over
/// `path`. On any failure the partial file is removed and the error rethrown naming `path`: an
/// older file at `path` stays as it was. Debian's serial HDF5 library is not thread-safe, so
/// files written from several threads (a study's cases) are written one at a time.
template <class Write> void writeResultsFile(const std::string& path, const Write& write);

namespace hdf5_detail {
/// The lock every use of the HDF5 library in this process holds.
std::mutex& libraryLock();
/// Removes `partial` and throws a runtime_error "cannot write `path`: why (…kept)".
[[noreturn]] void abandon(const std::string& partial, const std::string& path, const std::string& why);
}  // namespace hdf5_detail

template <class Write> void writeResultsFile(const std::string& path, const Write& write) {
  const std::string partial = partialPath(path);
  const std::lock_guard<std::mutex> lock(hdf5_detail::libraryLock());
  try {
    Hdf5File file;
    write(file);
    file.save(partial);
    std::filesystem::rename(partial, path);
  } catch (const std::exception& e) {
    hdf5_detail::abandon(partial, path, e.what());
  }
}

}  // namespace cranesim
