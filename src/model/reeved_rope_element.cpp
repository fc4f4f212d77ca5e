#include "cranesim/model/reeved_rope_element.hpp"

#include "cranesim/math/rotation.hpp"
#include "cranesim/model/model.hpp"

namespace cranesim {

namespace {
constexpr int kMaxNodeDirections = 7;
using NodeDual = Dual<double, kMaxNodeDirections>;
}  // namespace

ReevedRopeElement::ReevedRopeElement(std::string name, ReevedRopeKernel kernel, std::vector<PathPoint> path,
                                     std::vector<Slot> slots, std::vector<int> nodes, std::vector<int> q_indices,
                                     std::vector<int> v_indices)
    : name_(std::move(name)), kernel_(std::move(kernel)), path_(std::move(path)), slots_(std::move(slots)), nodes_(std::move(nodes)),
      q_(std::move(q_indices)), v_(std::move(v_indices)) {}

ReevedRopeElement::Local<double> ReevedRopeElement::gather(const double* x, const std::vector<int>& at) const {
  Local<double> out(static_cast<Eigen::Index>(at.size()));
  for (std::size_t k = 0; k < at.size(); ++k) out(static_cast<Eigen::Index>(k)) = x[at[k]];
  return out;
}

/// x = r + R p, ẋ = ṙ + R (ω × p) (4-5), ω in body axes.
template <class S> ReevedRopeElement::Path<S> ReevedRopeElement::path(const Local<S>& q, const Local<S>& v) const {
  Path<S> out;
  for (std::size_t s = 0; s < slots_.size(); ++s)
    if (slots_[s].rotates) out.R[s] = rotationMatrix<S>(Vec3T<S>(q.template segment<3>(slots_[s].at + 3)));
  for (std::size_t p = 0; p < path_.size(); ++p) {
    const PathPoint& point = path_[p];
    if (point.slot < 0) {
      out.x[p] = point.offset.cast<S>();
      out.xd[p].setZero();
      continue;
    }
    const Slot& slot = slots_[point.slot];
    out.x[p] = q.template segment<3>(slot.at);
    out.xd[p] = v.template segment<3>(slot.at);
    if (slot.rotates) {
      const Vec3T<S> offset = point.offset.cast<S>();
      out.x[p] += out.R[point.slot] * offset;
      out.xd[p] += out.R[point.slot] * Vec3T<S>(Vec3T<S>(v.template segment<3>(slot.at + 3)).cross(offset));
    }
  }
  return out;
}

/// The rope's point forces f gathered on the nodes as [f, p × Rᵀ f].
template <class S>
ReevedRopeElement::Local<S> ReevedRopeElement::force(const Local<S>& q, const Local<S>& v, double t, ParameterRates rates) const {
  const Path<S> p = path(q, v);
  ReevedRopeKernel::Points<S> f;
  kernel_.pointForces(p.x, p.xd, t, rates, f);
  Local<S> r = Local<S>::Zero(size());
  for (std::size_t k = 0; k < path_.size(); ++k) {
    const PathPoint& point = path_[k];
    if (point.slot < 0) continue;
    const Slot& slot = slots_[point.slot];
    r.template segment<3>(slot.at) += f[k];
    if (slot.rotates)
      r.template segment<3>(slot.at + 3) += point.offset.cast<S>().cross(Vec3T<S>(p.R[point.slot].transpose() * f[k]));
  }
  return r;
}

void ReevedRopeElement::residual(const ElementInput& in, double* r) const {
  Eigen::Map<Eigen::VectorXd>(r, size()) = force<double>(gather(in.q, q_), gather(in.v, v_), in.t, in.rates);
}

void ReevedRopeElement::tangent(const ElementInput& in, bool velocities, double* J) const {
  const Local<double> q = gather(in.q, q_), v = gather(in.v, v_);
  Local<NodeDual> qd = q.cast<NodeDual>(), vd = v.cast<NodeDual>();
  Local<NodeDual>& seeded_values = velocities ? vd : qd;
  const Local<double>& values = velocities ? v : q;
  const int n = size();
  Eigen::Map<Eigen::MatrixXd> out(J, n, n);
  for (const Slot& slot : slots_) {
    for (int k = 0; k < slot.size; ++k) seeded_values(slot.at + k) = seeded<double, kMaxNodeDirections>(values(slot.at + k), k);
    const Local<NodeDual> r = force<NodeDual>(qd, vd, in.t, in.rates);
    for (int i = 0; i < n; ++i) out.row(i).segment(slot.at, slot.size) = r(i).derivatives().head(slot.size).transpose();
    for (int k = 0; k < slot.size; ++k) seeded_values(slot.at + k) = NodeDual(values(slot.at + k));
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

const ReevedRopeElement& reevedRope(const Model& model, int index) {
  return dynamic_cast<const ReevedRopeElement&>(*model.elements[model.reeved_ropes[static_cast<std::size_t>(index)]]);
}

}  // namespace cranesim
