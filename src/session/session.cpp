#include "cranesim/session/session.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "cranesim/crane/stated_equilibrium_search.hpp"
#include "cranesim/io/scene_reader.hpp"
#include "cranesim/io/state_file.hpp"
#include "cranesim/model/closest_name.hpp"
#include "cranesim/model/compile.hpp"
#include "cranesim/model/member_force_elements.hpp"
#include "cranesim/model/reeved_rope.hpp"
#include "cranesim/solvers/scene_equilibrium.hpp"

namespace cranesim {

Session::Session(const std::string& scene_path, bool record)
    : Session(sceneAtStatedEquilibrium(readScene(scene_path), true), record) {}

Session::Session(const Scene& scene, bool record)
    : scene_(scene), recording_(record), model_(std::make_unique<Model>(compileModel(scene_))),
      assembler_(std::make_unique<Assembler>(*model_)) {
  if (recording_) requireResultsFit(scene_, *model_);
  initial_ = runInitialState(scene_, *model_, *assembler_, true);
  start();
}

Session::~Session() = default;

void Session::start() {
  simulation_.reset();
  for (const ModelInput& input : model_->inputs) *input.signal = InputSignal(input.signal->spec(), initial_.t);
  if (recording_) sink_.recorder = std::make_unique<ResultsRecorder>(*assembler_);
  simulation_ = std::make_unique<Simulation>(*assembler_, initial_, sink_);
  observed(initial_.t);
}

void Session::observed(double t) {
  observed_t_ = t;
  interpolated_ = false;
  motion_known_ = false;
}

void Session::reset() { start(); }

int Session::input(const std::string& name) const {
  const int k = model_->findInput(name);
  if (k >= 0) return k;
  throw std::invalid_argument(unknownName("input", name, namesOf(model_->inputs)));
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

bool Session::advanceTo(double t, const std::atomic<bool>* stop) {
  SimulationControl control;
  control.stop_requested = stop;
  const bool going = simulation_->advanceTo(t, control);
  // At t, or where the run stopped before it; never back before an earlier advance's t.
  observed(std::max(observed_t_, std::min(std::min(t, model_->solver.t_end), simulation_->time())));
  interpolated_ = simulation_->time() > observed_t_;
  if (interpolated_) {
    observed_.resize(static_cast<std::size_t>(assembler_->size()));
    simulation_->stateAt(observed_t_, observed_.data());
  }
  return going;
}

SimulationState Session::save() {
  SimulationState saved = simulation_->save();
  observed(saved.t);
  return saved;
}

void Session::restore(const SimulationState& state) {
  simulation_->restore(state);
  if (sink_.recorder) {
    sink_.recorder->keepBefore(initial_.t + static_cast<double>(state.next_sample) * model_->output.interval);
  }
  observed(state.t);
}

void Session::saveFile(const std::string& path) { writeStateFile(path, *model_, save()); }

void Session::restoreFile(const std::string& path) { restore(readStateFile(path, *model_)); }

void Session::writeResults(const std::string& path) const {
  if (!sink_.recorder) throw std::logic_error("this run is not recorded: open it with recording on to write its results");
  // Complete: the run went where it was asked to (to time(), or on to t_end) without failing.
  SimulationOutcome outcome = simulation_->outcome();
  const double asked = outcome.complete ? model_->solver.t_end : observed_t_;
  outcome.complete = outcome.message.empty();
  const ResultsRecorder::Metadata meta{scene_.path, scene_.text,
                                       model_->solver.formulation == Formulation::GGL ? "ggl" : "baumgarte", asked};
  sink_.recorder->write(path, meta, outcome);
}

int Session::joint(const std::string& name) const {
  const int j = model_->findJoint(name);
  if (j >= 0) return j;
  const std::string closest = closestName(name, namesOf(model_->joints));
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

Session::Sway Session::sway(int hanging, int pivot) const {
  const Vec3 down = model_->gravity.normalized();
  const Vec3 head = jointPosition(pivot), head_rate = jointVelocity(pivot);
  const Vec3 line = jointPosition(hanging) - head, line_rate = jointVelocity(hanging) - head_rate;
  // The plane turns with the pivot: the axes' rates enter the angles' rates.
  const Vec3 out = head - head.dot(down) * down, out_rate = head_rate - head_rate.dot(down) * down;
  Vec3 radial = down.unitOrthogonal(), radial_rate = Vec3::Zero();
  if (out.norm() > 0.0) {
    radial = out.normalized();
    radial_rate = (out_rate - radial * radial.dot(out_rate)) / out.norm();
  }
  const Vec3 across = radial.cross(down), across_rate = radial_rate.cross(down);
  const double d = line.dot(down), d_rate = line_rate.dot(down);
  Sway s;
  const auto angle = [&](const Vec3& axis, const Vec3& axis_rate, double& value, double& rate) {
    const double a = line.dot(axis), a_rate = line_rate.dot(axis) + line.dot(axis_rate);
    value = std::atan2(a, d);
    rate = (a_rate * d - a * d_rate) / (a * a + d * d);
  };
  angle(radial, radial_rate, s.radial, s.radial_rate);
  angle(across, across_rate, s.across, s.across_rate);
  return s;
}

int Session::constraint(const std::string& name) const {
  const int c = model_->findConstraint(name);
  if (c >= 0) return c;
  throw std::invalid_argument(unknownName("constraint", name, namesOf(model_->constraints)));
}

const DynamicState& Session::motion() const {
  if (motion_known_) return motion_;
  const int nq = model_->nq, nv = model_->nv;
  const double* y = state();
  motion_.t = observed_t_;
  motion_.q = Eigen::Map<const VecX>(y, nq);
  motion_.v = Eigen::Map<const VecX>(y + assembler_->vOffset(), nv);
  motion_constraints_ = assembler_->constraints(motion_.t, y, y + assembler_->vOffset());
  accelerations_.solve(*assembler_, motion_, motion_constraints_, Limit::Left);
  motion_known_ = true;
  return motion_;
}

ConstraintReaction Session::constraintLoad(int constraint) const {
  const Constraint& c = model_->constraints.at(static_cast<std::size_t>(constraint));
  const DynamicState& s = motion();
  return constraintReaction(*model_, c, motion_constraints_.G, s.q.data(), s.lambda.data());
}

const MemberSpec& Session::rope(const std::string& name) const {
  const auto spec = std::find_if(scene_.members.begin(), scene_.members.end(), [&](const MemberSpec& m) { return m.name == name; });
  if (spec == scene_.members.end() || spec->type != MemberType::Rope) {
    std::vector<std::string> ropes;
    for (const MemberSpec& m : scene_.members)
      if (m.type == MemberType::Rope) ropes.push_back(m.name);
    throw std::invalid_argument(unknownName("rope", name, ropes));
  }
  return *spec;
}

std::vector<double> Session::ropeTensions(const std::string& name) const {
  rope(name);
  if (const int reeved = findReevedRope(*model_, name); reeved >= 0) {
    const ReevedRope& element = reevedRope(*model_, reeved);
    const double* y = state();
    double parts[ReevedRope::kMaxParts];
    element.partTensions(ElementInput{y, y + assembler_->vOffset(), nullptr, observed_t_, model_->gravity}, parts);
    std::vector<double> tensions;
    for (int k = 0; k < element.parts(); ++k) tensions.insert(tensions.end(), kTensionPoints, parts[k]);
    return tensions;
  }
  const VecX zero = VecX::Zero(model_->nv);
  const ElementInput in{state(), zero.data(), zero.data(), observed_t_, model_->gravity};
  std::vector<double> tensions;
  for (const int e : memberForceElements(*model_, name, true)) {
    double forces[kTensionPoints];
    model_->elements[static_cast<std::size_t>(e)]->tensions(in, forces);
    tensions.insert(tensions.end(), forces, forces + kTensionPoints);
  }
  return tensions;
}

double Session::drivePower(int constraint) const {
  const Constraint& c = model_->constraints.at(static_cast<std::size_t>(constraint));
  const double* y = state();
  return assembler_->drivePower(c, observed_t_, y, y + assembler_->lambdaOffset());
}

double Session::winchPower(const std::string& name) const {
  rope(name);
  const double* y = state();
  const ElementInput in{y, y + assembler_->vOffset(), nullptr, observed_t_, model_->gravity};
  if (const int reeved = findReevedRope(*model_, name); reeved >= 0) return reevedRope(*model_, reeved).explicitTimePower(in);
  double power = 0.0;
  for (const int e : memberForceElements(*model_, name, true))
    power += model_->elements[static_cast<std::size_t>(e)]->explicitTimePower(in);
  return power;
}

double Session::kineticEnergy() const {
  const double* y = state();
  const Eigen::Map<const VecX> dq(y + assembler_->vOffset(), model_->nv);
  return 0.5 * dq.dot(assembler_->massMatrix(observed_t_, y) * dq);
}

double Session::potentialEnergy() const { return assembler_->potentialEnergy(observed_t_, state()); }

}  // namespace cranesim
