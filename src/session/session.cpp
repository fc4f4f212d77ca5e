#include "cranesim/session/session.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "cranesim/io/scene_reader.hpp"
#include "cranesim/io/state_file.hpp"
#include "cranesim/model/closest_name.hpp"
#include "cranesim/model/compile.hpp"
#include "cranesim/solvers/scene_equilibrium.hpp"

namespace cranesim {
namespace {

struct DiscardedSamples final : SampleSink {
  void sample(double, const double*, const WorkTerms&) override {}
};

/// "no <what> named 'x' (did you mean 'y'?); the scene's <what>s: a, b, …"
std::string unknownName(const std::string& what, const std::string& name, const std::vector<std::string>& names) {
  const std::string closest = closestName(name, names);
  std::string message = fmt::format("no {} named '{}'", what, name);
  if (!closest.empty()) message += fmt::format(" (did you mean '{}'?)", closest);
  if (names.empty()) return message + fmt::format("; the scene has no {}s", what);
  return message + fmt::format("; the scene's {}s: {}", what, fmt::join(names, ", "));
}

}  // namespace

Session::Session(const std::string& scene_path) : Session(readScene(scene_path)) {}

Session::Session(const Scene& scene)
    : scene_(scene), model_(std::make_unique<Model>(compileModel(scene_))), assembler_(std::make_unique<Assembler>(*model_)),
      sink_(std::make_unique<DiscardedSamples>()) {
  initial_ = runInitialState(scene_, *model_, *assembler_, true);
  start();
}

Session::~Session() = default;

void Session::start() {
  simulation_.reset();
  for (const ModelInput& input : model_->inputs) *input.signal = InputSignal(input.signal->spec(), initial_.t);
  simulation_ = std::make_unique<Simulation>(*assembler_, initial_, *sink_);
  observed_t_ = initial_.t;
  interpolated_ = false;
}

void Session::reset() { start(); }

int Session::input(const std::string& name) const {
  const int k = model_->findInput(name);
  if (k >= 0) return k;
  std::vector<std::string> names;
  for (const ModelInput& input : model_->inputs) names.push_back(input.name);
  throw std::invalid_argument(unknownName("input", name, names));
}

double Session::setInput(int index, double command) {
  const ModelInput& input = model_->inputs.at(static_cast<std::size_t>(index));
  try {
    return input.signal->command(time(), command);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(fmt::format("input '{}' ({}): {}", input.name, input.what, e.what()));
  }
}

double Session::inputValue(int index) const {
  return model_->inputs.at(static_cast<std::size_t>(index)).signal->derivatives(time())[0];
}

double Session::inputRate(int index) const {
  return model_->inputs.at(static_cast<std::size_t>(index)).signal->derivatives(time())[1];
}

bool Session::advanceTo(double t) {
  const bool going = simulation_->advanceTo(t);
  // At t, or where the run stopped before it; never back before an earlier advance's t.
  observed_t_ = std::max(observed_t_, std::min(std::min(t, model_->solver.t_end), simulation_->time()));
  interpolated_ = simulation_->time() > observed_t_;
  if (interpolated_) {
    observed_.resize(static_cast<std::size_t>(assembler_->size()));
    simulation_->stateAt(observed_t_, observed_.data());
  }
  return going;
}

SimulationState Session::save() {
  SimulationState saved = simulation_->save();
  observed_t_ = saved.t;
  interpolated_ = false;
  return saved;
}

void Session::restore(const SimulationState& state) {
  simulation_->restore(state);
  observed_t_ = state.t;
  interpolated_ = false;
}

void Session::saveFile(const std::string& path) { writeStateFile(path, *model_, save()); }

void Session::restoreFile(const std::string& path) { restore(readStateFile(path, *model_)); }

int Session::joint(const std::string& name) const {
  const int j = model_->findJoint(name);
  if (j >= 0) return j;
  std::vector<std::string> names;
  for (const Joint& joint : model_->joints) names.push_back(joint.name);
  const std::string closest = closestName(name, names);
  throw std::invalid_argument(fmt::format("no joint named '{}'{}", name, closest.empty() ? "" : fmt::format(" (did you mean '{}'?)", closest)));
}

Vec3 Session::jointPosition(int joint) const {
  model_->joints.at(static_cast<std::size_t>(joint));  // std::out_of_range for a joint that is not there
  return model_->jointFrame(state(), joint).r;
}

Vec3 Session::jointVelocity(int joint) const {
  const Joint& j = model_->joints.at(static_cast<std::size_t>(joint));
  if (j.node < 0) return Vec3::Zero();
  const Node& n = model_->nodes[static_cast<std::size_t>(j.node)];
  const double* v = state() + assembler_->vOffset() + n.v;
  const Vec3 velocity(v[0], v[1], v[2]);
  if (!n.hasRotation()) return velocity;
  const Vec3 omega(v[3], v[4], v[5]);  // body frame (2-10)
  return velocity + model_->nodeFrame(state(), j.node).R * omega.cross(j.offset);
}

}  // namespace cranesim
