#pragma once
// Thin RAII helpers over the HDF5 C API for writing numeric datasets and string attributes.

#include <hdf5.h>

#include <string>
#include <vector>

namespace cranesim {

class Hdf5File {
 public:
  explicit Hdf5File(const std::string& path);  // creates (truncates)
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

 private:
  hid_t file_ = -1;
};

}  // namespace cranesim
