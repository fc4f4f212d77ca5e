#include "hdf5_file.hpp"

#include <fmt/format.h>

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

Hdf5File::Hdf5File(const std::string& path) {
  file_ = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (file_ < 0) throw std::runtime_error(fmt::format("cannot create the results file '{}'", path));
}

Hdf5File::~Hdf5File() {
  if (file_ >= 0) H5Fclose(file_);
}

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
