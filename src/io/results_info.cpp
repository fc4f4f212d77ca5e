#include "cranesim/io/results_info.hpp"

#include <fmt/format.h>
#include <hdf5.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>

namespace cranesim {
namespace {

std::string attributeText(hid_t attr) {
  const hid_t type = H5Aget_type(attr);
  std::string out;
  switch (H5Tget_class(type)) {
    case H5T_STRING: {
      char* value = nullptr;
      const hid_t mem = H5Tcopy(H5T_C_S1);
      H5Tset_size(mem, H5T_VARIABLE);
      H5Tset_cset(mem, H5Tget_cset(type));
      if (H5Aread(attr, mem, &value) >= 0 && value) {
        out = value;
        H5free_memory(value);
      }
      H5Tclose(mem);
      break;
    }
    case H5T_INTEGER: {
      long v = 0;
      H5Aread(attr, H5T_NATIVE_LONG, &v);
      out = fmt::format("{}", v);
      break;
    }
    case H5T_FLOAT: {
      double v = 0;
      H5Aread(attr, H5T_NATIVE_DOUBLE, &v);
      out = fmt::format("{:g}", v);
      break;
    }
    default: out.assign(1, '?');  // not = "?": g++ 12 warns falsely (-Wrestrict, GCC bug 105329)
  }
  H5Tclose(type);
  return out;
}

herr_t listAttribute(hid_t object, const char* name, const H5A_info_t*, void* data) {
  auto* out = static_cast<std::string*>(data);
  const hid_t attr = H5Aopen(object, name, H5P_DEFAULT);
  std::string value = attributeText(attr);
  H5Aclose(attr);
  if (const std::string_view key(name); key == "scene_text" || key == "study_text") value = fmt::format("<{} lines of YAML>", std::count(value.begin(), value.end(), '\n'));
  *out += fmt::format("    {:<22} {}\n", name, value);
  return 0;
}

herr_t listObject(hid_t root, const char* name, const H5O_info_t* info, void* data) {
  auto* out = static_cast<std::string*>(data);
  if (std::string(name) == ".") return 0;
  if (info->type == H5O_TYPE_DATASET) {
    const hid_t set = H5Dopen2(root, name, H5P_DEFAULT);
    const hid_t space = H5Dget_space(set);
    hsize_t dims[8];
    const int rank = H5Sget_simple_extent_dims(space, dims, nullptr);
    std::string shape;
    for (int k = 0; k < rank; ++k) shape += (k ? " × " : "") + std::to_string(dims[k]);
    *out += fmt::format("  /{:<44} {}\n", name, shape);
    H5Sclose(space);
    H5Dclose(set);
  } else if (info->type == H5O_TYPE_GROUP && info->num_attrs > 0) {
    *out += fmt::format("  /{} attributes:\n", name);
    const hid_t g = H5Gopen2(root, name, H5P_DEFAULT);
    H5Aiterate2(g, H5_INDEX_NAME, H5_ITER_INC, nullptr, listAttribute, out);
    H5Gclose(g);
  }
  return 0;
}

}  // namespace

std::string describeResults(const std::string& path) {
  if (!std::filesystem::exists(path)) throw std::runtime_error(fmt::format("'{}' does not exist", path));
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  if (H5Fis_hdf5(path.c_str()) <= 0) throw std::runtime_error(fmt::format("'{}' is not an HDF5 file", path));
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) throw std::runtime_error(fmt::format("cannot open '{}'", path));
  if (H5Aexists(file, "engine_version") <= 0) {  // every file the tools write carries it
    H5Fclose(file);
    throw std::runtime_error(fmt::format("'{}' is an HDF5 file but not one cranesim wrote (no engine_version attribute)", path));
  }
  std::string out = fmt::format("{}\n  attributes:\n", path);
  H5Aiterate2(file, H5_INDEX_NAME, H5_ITER_INC, nullptr, listAttribute, &out);
  out += "  contents:\n";
  H5Ovisit2(file, H5_INDEX_NAME, H5_ITER_INC, listObject, &out, H5O_INFO_BASIC | H5O_INFO_NUM_ATTRS);
  H5Fclose(file);
  return out;
}

}  // namespace cranesim
