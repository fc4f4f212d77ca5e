#include "hdf5_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace cranesim {
namespace {

void require(herr_t status, const std::string& what) {
  if (status < 0) throw std::runtime_error("HDF5: cannot " + what);
}

hid_t linkCreationProperties() {
  const hid_t p = H5Pcreate(H5P_LINK_CREATE);
  H5Pset_create_intermediate_group(p, 1);
  return p;
}

}  // namespace

Hdf5File::Hdf5File() {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // failures are reported by the statuses checked here
  const hid_t access = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_fapl_core(access, 1 << 20, /*backing_store=*/0);
  file_ = H5Fcreate("results", H5F_ACC_TRUNC, H5P_DEFAULT, access);
  H5Pclose(access);
  if (file_ < 0) throw std::runtime_error("HDF5: cannot create a file in memory");
}

Hdf5File::~Hdf5File() {
  if (file_ >= 0) H5Fclose(file_);
}

void Hdf5File::save(const std::string& path) {
  require(H5Fflush(file_, H5F_SCOPE_GLOBAL), "flush the file");
  const ssize_t size = H5Fget_file_image(file_, nullptr, 0);
  require(size < 0 ? -1 : 0, "take the file's image");
  std::vector<char> image(static_cast<std::size_t>(size));
  require(H5Fget_file_image(file_, image.data(), image.size()) < 0 ? -1 : 0, "take the file's image");
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  const auto fail = [&](const char* what) {
    const std::string why = std::strerror(errno);
    if (fd >= 0) ::close(fd);
    throw std::runtime_error(fmt::format("{}: {}", what, why));
  };
  if (fd < 0) fail("cannot create it");
  for (std::size_t done = 0; done < image.size();) {
    const ssize_t n = ::write(fd, image.data() + done, image.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail("cannot write it");
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) fail("cannot sync it to disk");
  if (::close(fd) != 0) fail("cannot close it");
}

namespace hdf5_detail {

std::mutex& libraryLock() {
  static std::mutex lock;
  return lock;
}

void abandon(const std::string& partial, const std::string& path, const std::string& why) {
  std::error_code ignored;
  std::filesystem::remove(partial, ignored);
  const bool older = std::filesystem::exists(path, ignored);
  throw std::runtime_error(fmt::format("cannot write '{}': {}{}", path, why,
                                       older ? " (the older file there is kept)" : ""));
}

}  // namespace hdf5_detail

void Hdf5File::ensureGroup(const std::string& path) {
  if (H5Lexists(file_, path.c_str(), H5P_DEFAULT) > 0) return;
  const hid_t lcpl = linkCreationProperties();
  const hid_t g = H5Gcreate2(file_, path.c_str(), lcpl, H5P_DEFAULT, H5P_DEFAULT);
  H5Pclose(lcpl);
  require(g < 0 ? -1 : 0, "create group " + path);
  H5Gclose(g);
}

void Hdf5File::writeDoubles(const std::string& path, const std::vector<hsize_t>& dims, const double* data) {
  const hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  const hid_t lcpl = linkCreationProperties();
  const hid_t set = H5Dcreate2(file_, path.c_str(), H5T_IEEE_F64LE, space, lcpl, H5P_DEFAULT, H5P_DEFAULT);
  H5Pclose(lcpl);
  require(set < 0 ? -1 : 0, "create dataset " + path);
  hsize_t count = 1;
  for (hsize_t d : dims) count *= d;
  if (count > 0) require(H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "write " + path);
  H5Dclose(set);
  H5Sclose(space);
}

void Hdf5File::writeStrings(const std::string& path, const std::vector<hsize_t>& dims,
                            const std::vector<std::string>& values) {
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  const hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  const hid_t lcpl = linkCreationProperties();
  const hid_t set = H5Dcreate2(file_, path.c_str(), type, space, lcpl, H5P_DEFAULT, H5P_DEFAULT);
  H5Pclose(lcpl);
  require(set < 0 ? -1 : 0, "create dataset " + path);
  std::vector<const char*> pointers;
  for (const auto& v : values) pointers.push_back(v.c_str());
  if (!pointers.empty()) require(H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, pointers.data()), "write " + path);
  H5Dclose(set);
  H5Sclose(space);
  H5Tclose(type);
}

void Hdf5File::attribute(const std::string& object, const std::string& name, const std::string& value) {
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t attr = H5Acreate_by_name(file_, object.c_str(), name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  require(attr < 0 ? -1 : 0, "create attribute " + name);
  const char* p = value.c_str();
  require(H5Awrite(attr, type, &p), "write attribute " + name);
  H5Aclose(attr);
  H5Sclose(space);
  H5Tclose(type);
}

void Hdf5File::attribute(const std::string& object, const std::string& name, double value) {
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t attr = H5Acreate_by_name(file_, object.c_str(), name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  require(attr < 0 ? -1 : 0, "create attribute " + name);
  require(H5Awrite(attr, H5T_NATIVE_DOUBLE, &value), "write attribute " + name);
  H5Aclose(attr);
  H5Sclose(space);
}

void Hdf5File::attribute(const std::string& object, const std::string& name, long value) {
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t attr = H5Acreate_by_name(file_, object.c_str(), name.c_str(), H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  require(attr < 0 ? -1 : 0, "create attribute " + name);
  require(H5Awrite(attr, H5T_NATIVE_LONG, &value), "write attribute " + name);
  H5Aclose(attr);
  H5Sclose(space);
}

}  // namespace cranesim
