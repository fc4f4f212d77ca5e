#include "cranesim/model/massive_reeved_rope_element.hpp"

#include <algorithm>

#include "cranesim/model/model.hpp"

namespace cranesim {

namespace {
template <class S> using LocalT = Eigen::Matrix<S, Eigen::Dynamic, 1>;
}  // namespace

MassiveReevedRopeElement::MassiveReevedRopeElement(std::string name, MassiveReevingKernel kernel, RopePath path,
                                                   std::vector<int> nodes, std::vector<int> q_indices,
                                                   std::vector<int> v_indices)
    : name_(std::move(name)), kernel_(std::move(kernel)), path_(std::move(path)), nodes_(std::move(nodes)),
      q_(std::move(q_indices)), v_(std::move(v_indices)) {
  inner_at_ = path_.slots.empty() ? 0 : path_.slots.back().at + path_.slots.back().size;
}

MassiveReevedRopeElement::Local MassiveReevedRopeElement::gather(const double* x, const std::vector<int>& at) const {
  Local out(static_cast<Eigen::Index>(at.size()));
  for (std::size_t k = 0; k < at.size(); ++k) out(static_cast<Eigen::Index>(k)) = x[at[k]];
  return out;
}

MassiveReevedRopeElement::Local MassiveReevedRopeElement::accelerations(const ElementInput& in) const {
  return in.a ? gather(in.a, v_) : Local(Local::Zero(size()));
}

template <class S>
MassiveReevingKernel::State<S> MassiveReevedRopeElement::state(const LocalT<S>& q, const LocalT<S>& v, const Local& a,
                                                               const ElementInput& in) const {
  const int n = kernel_.elements_per_part, m = kernel_.parts();
  std::vector<Vec3T<S>> x(static_cast<std::size_t>(m + 1)), xd(x.size());
  RopePath::Rotations<S> R;
  path_.place<S>(q, v, x, xd, R);
  MassiveReevingKernel::State<S> s;
  s.x.resize(static_cast<std::size_t>(kernel_.chainNodes()));
  s.v.resize(s.x.size());
  s.a.assign(s.x.size(), Vec3::Zero());
  for (int k = 0; k <= m; ++k) s.x[k * n] = x[k], s.v[k * n] = xd[k];
  for (int k = 0; k < m; ++k)
    for (int e = 1; e < n; ++e) {
      const int at = innerAt() + 3 * (k * (n - 1) + e - 1);
      s.x[k * n + e] = q.template segment<3>(at);
      s.v[k * n + e] = v.template segment<3>(at);
      if (a.size() > 0) s.a[k * n + e] = a.segment<3>(at);
    }
  s.sigma.assign(static_cast<std::size_t>(m + 1), S(0.0));
  s.sigma_rate.assign(s.sigma.size(), S(0.0));
  s.sigma_acceleration.assign(s.sigma.size(), 0.0);
  s.sigma[0] = S(kernel_.segmentLength(in.t));
  s.sigma_rate[0] = S(kernel_.segmentRate(in.t, in.rates));
  for (int i = 1; i < m; ++i) {
    s.sigma[i] = q(sheaveAt() + i - 1);
    s.sigma_rate[i] = v(sheaveAt() + i - 1);
    if (a.size() > 0) s.sigma_acceleration[i] = a(sheaveAt() + i - 1);
  }
  return s;
}

template <class S>
LocalT<S> MassiveReevedRopeElement::force(const LocalT<S>& q, const LocalT<S>& v, const Local& a, const ElementInput& in) const {
  const int n = kernel_.elements_per_part, m = kernel_.parts();
  std::vector<Vec3T<S>> x(static_cast<std::size_t>(m + 1)), xd(x.size());
  RopePath::Rotations<S> R;
  path_.place<S>(q, v, x, xd, R);
  const MassiveReevingKernel::Residual<S> r = kernel_.residual(state<S>(q, v, a, in), in.gravity, in.mass_damping);
  LocalT<S> out = LocalT<S>::Zero(size());
  std::vector<Vec3T<S>> on_path(x.size());
  for (int k = 0; k <= m; ++k) on_path[k] = r.chain[k * n];
  path_.gather(R, on_path, out);
  for (int k = 0; k < m; ++k)
    for (int e = 1; e < n; ++e) out.template segment<3>(innerAt() + 3 * (k * (n - 1) + e - 1)) = r.chain[k * n + e];
  for (int i = 1; i < m; ++i) out(sheaveAt() + i - 1) = r.sigma[i];
  return out;
}

void MassiveReevedRopeElement::residual(const ElementInput& in, double* r) const {
  Eigen::Map<Eigen::VectorXd>(r, size()) = force<double>(gather(in.q, q_), gather(in.v, v_), accelerations(in), in);
}

void MassiveReevedRopeElement::tangent(const ElementInput& in, bool velocities, double* J) const {
  const Local q = gather(in.q, q_), v = gather(in.v, v_), a = accelerations(in);
  LocalT<RopePath::SlotDual> qd = q.cast<RopePath::SlotDual>(), vd = v.cast<RopePath::SlotDual>();
  LocalT<RopePath::SlotDual>& seeded_values = velocities ? vd : qd;
  const Local& values = velocities ? v : q;
  const int n = size();
  Eigen::Map<Eigen::MatrixXd> out(J, n, n);
  std::vector<RopePath::Slot> blocks = path_.slots;  // the path's nodes, then the rope's own
  for (int j = 0; j < innerNodes(); ++j) blocks.push_back({innerAt() + 3 * j, 3, false});
  for (int i = 1; i < kernel_.parts(); ++i) blocks.push_back({sheaveAt() + i - 1, 1, false});
  for (const RopePath::Slot& block : blocks) {
    for (int k = 0; k < block.size; ++k) seeded_values(block.at + k) = seeded<double, RopePath::kMaxSlotValues>(values(block.at + k), k);
    const LocalT<RopePath::SlotDual> r = force<RopePath::SlotDual>(qd, vd, a, in);
    for (int i = 0; i < n; ++i) out.row(i).segment(block.at, block.size) = r(i).derivatives().head(block.size).transpose();
    for (int k = 0; k < block.size; ++k) seeded_values(block.at + k) = RopePath::SlotDual(values(block.at + k));
  }
}

void MassiveReevedRopeElement::jacobian(const ElementInput& in, double cj, double* J) const {
  const int n = size();
  tangent(in, false, J);
  tangent(in, true, J + n * n);
  Eigen::MatrixXd M(n, n);
  mass(in, M.data());
  Eigen::Map<Eigen::MatrixXd>(J + n * n, n, n) += cj * M;
}

void MassiveReevedRopeElement::coordinateJacobian(const ElementInput& in, double* J) const { tangent(in, false, J); }

void MassiveReevedRopeElement::mass(const ElementInput& in, double* M) const {
  const int n = size(), per_part = kernel_.elements_per_part - 1;
  Eigen::Map<Eigen::MatrixXd> out(M, n, n);
  out.setZero();
  const std::vector<double> sigma = materialCoordinates(in);
  for (int k = 0; k < kernel_.parts(); ++k) {
    const double node_mass = kernel_.lineDensity() * (sigma[k] - sigma[k + 1]) / kernel_.elements_per_part;
    for (int j = 0; j < 3 * per_part; ++j) out(innerAt() + 3 * k * per_part + j, innerAt() + 3 * k * per_part + j) = node_mass;
  }
  for (int i = 1; i < kernel_.parts(); ++i) out(sheaveAt() + i - 1, sheaveAt() + i - 1) = kernel_.sheave_mass[i - 1];
}

double MassiveReevedRopeElement::kineticEnergy(const ElementInput& in) const {
  return kernel_.kineticEnergy(state<double>(gather(in.q, q_), gather(in.v, v_), Local(), in));
}

double MassiveReevedRopeElement::potentialEnergy(const ElementInput& in) const {
  return kernel_.potentialEnergy(state<double>(gather(in.q, q_), Local::Zero(size()), Local(), in), in.gravity);
}

double MassiveReevedRopeElement::explicitTimePower(const ElementInput& in) const {
  return kernel_.explicitTimePower(state<double>(gather(in.q, q_), gather(in.v, v_), Local(), in), in.gravity);
}

double MassiveReevedRopeElement::dissipatedPower(const ElementInput& in) const {
  return kernel_.dissipatedPower(state<double>(gather(in.q, q_), gather(in.v, v_), Local(), in));
}

std::vector<double> MassiveReevedRopeElement::elementTensions(const ElementInput& in) const {
  const MassiveReevingKernel::State<double> s = state<double>(gather(in.q, q_), gather(in.v, v_), Local(), in);
  std::vector<double> out;
  for (int k = 0; k < kernel_.parts(); ++k)
    for (int e = 0; e < kernel_.elements_per_part; ++e) out.push_back(kernel_.axial(s, k, e).tension);
  return out;
}

void MassiveReevedRopeElement::partTensions(const ElementInput& in, double* tension) const {
  const std::vector<double> T = elementTensions(in);
  const int n = kernel_.elements_per_part;
  for (int k = 0; k < parts(); ++k) tension[k] = *std::max_element(T.begin() + k * n, T.begin() + (k + 1) * n);
}

std::vector<Vec3> MassiveReevedRopeElement::pathPositions(const ElementInput& in) const {
  const std::vector<Vec3> chain = chainPositions(in);
  std::vector<Vec3> out;
  for (int k = 0; k <= parts(); ++k) out.push_back(chain[static_cast<std::size_t>(k * kernel_.elements_per_part)]);
  return out;
}

std::vector<Vec3> MassiveReevedRopeElement::chainPositions(const ElementInput& in) const {
  return state<double>(gather(in.q, q_), Local::Zero(size()), Local(), in).x;
}

MassiveReevedRopeElement::ChainPoint MassiveReevedRopeElement::chainPoint(int c) const {
  const int n = kernel_.elements_per_part, k = c / n, e = c % n;
  if (e == 0) {
    const RopePath::Point& p = path_.points[static_cast<std::size_t>(k)];
    return {p.slot < 0 ? -1 : nodes_[static_cast<std::size_t>(p.slot)], p.offset};
  }
  return {nodes_[path_.slots.size() + static_cast<std::size_t>(k * (n - 1) + e - 1)], Vec3::Zero()};
}

std::vector<double> MassiveReevedRopeElement::materialCoordinates(const ElementInput& in) const {
  const Local q = gather(in.q, q_);
  std::vector<double> sigma(static_cast<std::size_t>(kernel_.parts() + 1), 0.0);
  sigma[0] = kernel_.segmentLength(in.t);
  for (int i = 1; i < kernel_.parts(); ++i) sigma[i] = q(sheaveAt() + i - 1);
  return sigma;
}

}  // namespace cranesim
