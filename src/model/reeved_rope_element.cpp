#include "cranesim/model/reeved_rope_element.hpp"

#include "cranesim/math/rotation.hpp"
#include "cranesim/model/model.hpp"

namespace cranesim {

ReevedRopeElement::ReevedRopeElement(std::string name, ReevedRopeKernel kernel, RopePath path, std::vector<int> nodes,
                                     std::vector<int> q_indices, std::vector<int> v_indices)
    : name_(std::move(name)), kernel_(std::move(kernel)), path_(std::move(path)), nodes_(std::move(nodes)),
      q_(std::move(q_indices)), v_(std::move(v_indices)) {}

ReevedRopeElement::Local<double> ReevedRopeElement::gather(const double* x, const std::vector<int>& at) const {
  Local<double> out(static_cast<Eigen::Index>(at.size()));
  for (std::size_t k = 0; k < at.size(); ++k) out(static_cast<Eigen::Index>(k)) = x[at[k]];
  return out;
}

template <class S> ReevedRopeElement::Path<S> ReevedRopeElement::path(const Local<S>& q, const Local<S>& v) const {
  Path<S> out;
  path_.place<S>(q, v, out.x, out.xd, out.R);
  return out;
}

/// The rope's point forces f gathered on the nodes as [f, p × Rᵀ f].
template <class S>
ReevedRopeElement::Local<S> ReevedRopeElement::force(const Local<S>& q, const Local<S>& v, double t, ParameterRates rates) const {
  const Path<S> p = path(q, v);
  ReevedRopeKernel::Points<S> f;
  kernel_.pointForces(p.x, p.xd, t, rates, f);
  Local<S> r = Local<S>::Zero(size());
  path_.gather(p.R, f, r);
  return r;
}

void ReevedRopeElement::residual(const ElementInput& in, double* r) const {
  Eigen::Map<Eigen::VectorXd>(r, size()) = force<double>(gather(in.q, q_), gather(in.v, v_), in.t, in.rates);
}

void ReevedRopeElement::tangent(const ElementInput& in, bool velocities, double* J) const {
  const Local<double> q = gather(in.q, q_), v = gather(in.v, v_);
  Local<RopePath::SlotDual> qd = q.cast<RopePath::SlotDual>(), vd = v.cast<RopePath::SlotDual>();
  Local<RopePath::SlotDual>& seeded_values = velocities ? vd : qd;
  const Local<double>& values = velocities ? v : q;
  const int n = size();
  Eigen::Map<Eigen::MatrixXd> out(J, n, n);
  for (const RopePath::Slot& slot : path_.slots) {
    for (int k = 0; k < slot.size; ++k) seeded_values(slot.at + k) = seeded<double, RopePath::kMaxSlotValues>(values(slot.at + k), k);
    const Local<RopePath::SlotDual> r = force<RopePath::SlotDual>(qd, vd, in.t, in.rates);
    for (int i = 0; i < n; ++i) out.row(i).segment(slot.at, slot.size) = r(i).derivatives().head(slot.size).transpose();
    for (int k = 0; k < slot.size; ++k) seeded_values(slot.at + k) = RopePath::SlotDual(values(slot.at + k));
  }
}

void ReevedRopeElement::jacobian(const ElementInput& in, double, double* J) const {
  tangent(in, false, J);
  tangent(in, true, J + size() * size());
}

void ReevedRopeElement::coordinateJacobian(const ElementInput& in, double* J) const { tangent(in, false, J); }

void ReevedRopeElement::mass(const ElementInput&, double* M) const { std::fill(M, M + size() * size(), 0.0); }

double ReevedRopeElement::potentialEnergy(const ElementInput& in) const {
  const Local<double> q = gather(in.q, q_);
  return kernel_.potentialEnergy(path<double>(q, Local<double>::Zero(size())).x, in.t);
}

double ReevedRopeElement::explicitTimePower(const ElementInput& in) const {
  const Path<double> p = path<double>(gather(in.q, q_), gather(in.v, v_));
  return kernel_.explicitTimePower(p.x, p.xd, in.t);
}

double ReevedRopeElement::dissipatedPower(const ElementInput& in) const {
  const Path<double> p = path<double>(gather(in.q, q_), gather(in.v, v_));
  return kernel_.dissipatedPower(p.x, p.xd, in.t);
}

void ReevedRopeElement::hold(const ElementInput& in) const {
  const Path<double> p = path<double>(gather(in.q, q_), gather(in.v, v_));
  kernel_.hold(p.x, p.xd, in.t);
}

std::vector<double> ReevedRopeElement::memory() const {
  std::vector<double> out;
  for (int i = 0; i + 2 < kernel_.points; ++i)
    for (const double value : {kernel_.grip[i].travel, kernel_.grip[i].state, kernel_.grip[i].distance}) out.push_back(value);
  return out;
}

void ReevedRopeElement::setMemory(const double* memory) const {
  for (int i = 0; i + 2 < kernel_.points; ++i, memory += 3) kernel_.grip[i] = {memory[0], memory[1], memory[2]};
}

void ReevedRopeElement::partTensions(const ElementInput& in, double* tension) const {
  const Path<double> p = path<double>(gather(in.q, q_), gather(in.v, v_));
  kernel_.partTensions(p.x, p.xd, in.t, in.rates, tension);
}

std::vector<Vec3> ReevedRopeElement::pathPositions(const ElementInput& in) const {
  const Local<double> q = gather(in.q, q_);
  const Path<double> p = path<double>(q, Local<double>::Zero(size()));
  return {p.x.begin(), p.x.begin() + kernel_.points};
}

int findReevedRope(const Model& model, const std::string& rope) {
  for (std::size_t r = 0; r < model.reeved_ropes.size(); ++r)
    if (reevedRope(model, static_cast<int>(r)).name() == rope) return static_cast<int>(r);
  return -1;
}

const ReevedRope& reevedRope(const Model& model, int index) {
  return dynamic_cast<const ReevedRope&>(*model.elements[model.reeved_ropes[static_cast<std::size_t>(index)]]);
}

}  // namespace cranesim
