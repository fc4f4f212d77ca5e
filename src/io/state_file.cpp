#include "cranesim/io/state_file.hpp"

#include <fmt/format.h>
#include <hdf5.h>

#include <stdexcept>
#include <vector>

#include "hdf5_file.hpp"

namespace cranesim {
namespace {

constexpr const char* kFormat = "cranesim run state";
constexpr long kStateFileVersion = 2;
constexpr int kInputFields = 6;  // t, u, r, x, z₁, z₂

std::string inputNames(const Model& model) {
  std::string names;
  for (const ModelInput& input : model.inputs) names += (names.empty() ? "" : ",") + input.name;
  return names;
}

/// A state file open for reading; every failure names the file.
class StateReader {
 public:
  explicit StateReader(const std::string& path) : path_(path) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // failures are reported by the statuses checked here
    file_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (file_ < 0) fail("cannot be opened as an HDF5 file");
  }
  ~StateReader() {
    if (file_ >= 0) H5Fclose(file_);
  }
  StateReader(const StateReader&) = delete;
  StateReader& operator=(const StateReader&) = delete;

  [[noreturn]] void fail(const std::string& why) const { throw std::runtime_error(fmt::format("{}: {}", path_, why)); }

  std::string text(const char* name) const {
    if (H5Aexists(file_, name) <= 0) fail(fmt::format("is not a run state file (no '{}' attribute)", name));
    const hid_t attr = H5Aopen(file_, name, H5P_DEFAULT);
    const hid_t mem = H5Tcopy(H5T_C_S1);
    H5Tset_size(mem, H5T_VARIABLE);
    H5Tset_cset(mem, H5T_CSET_UTF8);
    char* value = nullptr;
    std::string out;
    if (H5Aread(attr, mem, &value) >= 0 && value) {
      out = value;
      H5free_memory(value);
    }
    H5Tclose(mem);
    H5Aclose(attr);
    return out;
  }

  long number(const char* name) const {
    if (H5Aexists(file_, name) <= 0) fail(fmt::format("is not a run state file (no '{}' attribute)", name));
    const hid_t attr = H5Aopen(file_, name, H5P_DEFAULT);
    long value = 0;
    const herr_t status = H5Aread(attr, H5T_NATIVE_LONG, &value);
    H5Aclose(attr);
    if (status < 0) fail(fmt::format("its '{}' attribute is not a number", name));
    return value;
  }

  /// The dataset `name`, which must hold `count` numbers.
  std::vector<double> doubles(const char* name, std::size_t count) const {
    if (H5Lexists(file_, name, H5P_DEFAULT) <= 0) fail(fmt::format("has no '{}'", name));
    const hid_t set = H5Dopen(file_, name, H5P_DEFAULT);
    const hid_t space = H5Dget_space(set);
    const auto points = static_cast<std::size_t>(H5Sget_simple_extent_npoints(space));
    std::vector<double> out(points);
    const herr_t status = points == count ? H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) : -1;
    H5Sclose(space);
    H5Dclose(set);
    if (points != count) fail(fmt::format("'{}' holds {} numbers, not the {} this model has", name, points, count));
    if (status < 0) fail(fmt::format("'{}' cannot be read", name));
    return out;
  }

 private:
  std::string path_;
  hid_t file_ = -1;
};

}  // namespace

void writeStateFile(const std::string& path, const Model& model, const SimulationState& state) {
  writeResultsFile(path, [&](Hdf5File& file) {
    file.attribute("/", "format", std::string(kFormat));
    file.attribute("/", "version", kStateFileVersion);
    file.attribute("/", "scene", model.name);
    file.attribute("/", "inputs", inputNames(model));
    file.writeDoubles("/t", {1}, &state.t);
    file.writeDoubles("/q", {static_cast<hsize_t>(state.q.size())}, state.q.data());
    file.writeDoubles("/v", {static_cast<hsize_t>(state.v.size())}, state.v.data());
    file.writeDoubles("/work", {state.work.size()}, state.work.data());
    std::vector<double> inputs;
    for (const InputState& s : state.inputs) inputs.insert(inputs.end(), {s.t, s.u, s.r, s.x, s.z[0], s.z[1]});
    file.writeDoubles("/inputs", {state.inputs.size(), kInputFields}, inputs.data());
    const double bookkeeping[] = {state.drive_impulses, static_cast<double>(state.next_break),
                                  static_cast<double>(state.next_sample), state.sampled_end ? 1.0 : 0.0,
                                  static_cast<double>(state.sharing.steps), static_cast<double>(state.sharing.clean),
                                  static_cast<double>(state.sharing.wait), static_cast<double>(state.sharing.trial),
                                  static_cast<double>(state.sharing.before_trial), static_cast<double>(state.sharing.settling)};
    file.writeDoubles("/bookkeeping", {10}, bookkeeping);
    if (!state.memory.empty()) file.writeDoubles("/memory", {state.memory.size()}, state.memory.data());
  });
}

SimulationState readStateFile(const std::string& path, const Model& model) {
  const std::lock_guard<std::mutex> lock(hdf5_detail::libraryLock());
  const StateReader file(path);
  if (file.text("format") != kFormat) file.fail("is not a run state file");
  if (const long version = file.number("version"); version != kStateFileVersion)
    file.fail(fmt::format("is a run state of version {}; this cranesim reads version {}", version, kStateFileVersion));
  if (const std::string inputs = file.text("inputs"); inputs != inputNames(model))
    file.fail(fmt::format("was saved from a model with the inputs [{}], not [{}]", inputs, inputNames(model)));
  SimulationState state;
  state.t = file.doubles("/t", 1)[0];
  const std::vector<double> q = file.doubles("/q", static_cast<std::size_t>(model.nq));
  const std::vector<double> v = file.doubles("/v", static_cast<std::size_t>(model.nv));
  state.q = Eigen::Map<const VecX>(q.data(), model.nq);
  state.v = Eigen::Map<const VecX>(v.data(), model.nv);
  const std::vector<double> work = file.doubles("/work", state.work.size());
  std::copy(work.begin(), work.end(), state.work.begin());
  const std::vector<double> inputs = file.doubles("/inputs", model.inputs.size() * kInputFields);
  for (std::size_t k = 0; k < model.inputs.size(); ++k) {
    const double* f = inputs.data() + k * kInputFields;
    state.inputs.push_back({f[0], f[1], f[2], f[3], {f[4], f[5]}});
  }
  const std::vector<double> b = file.doubles("/bookkeeping", 10);
  state.drive_impulses = b[0];
  state.next_break = static_cast<std::size_t>(b[1]);
  state.next_sample = static_cast<long>(b[2]);
  state.sampled_end = b[3] != 0.0;
  state.sharing = {static_cast<long>(b[4]), static_cast<long>(b[5]), static_cast<long>(b[6]), static_cast<long>(b[7]),
                   static_cast<long>(b[8]), static_cast<long>(b[9])};
  std::size_t memory = 0;
  for (const auto& e : model.elements) memory += e->memory().size();
  if (memory > 0) state.memory = file.doubles("/memory", memory);
  return state;
}

}  // namespace cranesim
