#include "cranesim/model/massive_reeved_rope_element.hpp"

#include <algorithm>
#include <stdexcept>

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
  listCables();
}

void MassiveReevedRopeElement::listCables() {
  const int n = kernel_.elements_per_part, m = kernel_.parts();
  if (n < 2) throw std::invalid_argument("a massive part is a chain of at least 2 cables: one path point per cable");
  for (int k = 0; k < m; ++k)
    for (int e = 0; e < n; ++e) {
      CableBlock b;
      b.k = k, b.e = e;
      for (int end = 0; end < 2; ++end) {
        b.end_at[end] = static_cast<int>(b.locals.size());
        const int c = e + end;  // the end's place in the part's chain
        if (c == 0 || c == n) {
          b.point[end] = k + c / n;
          const int slot = path_.points[static_cast<std::size_t>(b.point[end])].slot;
          if (slot < 0) continue;
          const RopePath::Slot& values = path_.slots[static_cast<std::size_t>(slot)];
          for (int i = 0; i < values.size; ++i) b.locals.push_back(values.at + i);
        } else {
          for (int i = 0; i < 3; ++i) b.locals.push_back(innerAt() + 3 * (k * (n - 1) + c - 1) + i);
        }
      }
      for (int end = 0; end < 2; ++end)
        if (const int i = k + end; i > 0 && i < m) {
          b.sigma_at[end] = static_cast<int>(b.locals.size());
          b.locals.push_back(sheaveAt() + i - 1);
        }
      cables_.push_back(std::move(b));
    }
}

MassiveReevedRopeElement::CableValues<double> MassiveReevedRopeElement::gather(const Local& x, const std::vector<int>& at) {
  CableValues<double> out(static_cast<Eigen::Index>(at.size()));
  for (std::size_t k = 0; k < at.size(); ++k) out(static_cast<Eigen::Index>(k)) = x(at[k]);
  return out;
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
MassiveReevedRopeElement::CableValues<S> MassiveReevedRopeElement::cableForce(const CableBlock& b, const CableValues<S>& q,
                                                                              const CableValues<S>& v, const CableValues<double>& a,
                                                                              const ElementInput& in) const {
  MassiveReevingKernel::Cable<S> c;
  std::array<Mat3T<S>, 2> R;
  for (int end = 0; end < 2; ++end) {
    if (b.point[end] >= 0) {
      path_.placePoint<S>(static_cast<std::size_t>(b.point[end]), q, v, b.end_at[end], c.x[end], c.v[end], R[end]);
    } else {
      c.x[end] = q.template segment<3>(b.end_at[end]);
      c.v[end] = v.template segment<3>(b.end_at[end]);
    }
    const int i = b.k + end;
    if (b.sigma_at[end] >= 0) {
      c.sigma[end] = q(b.sigma_at[end]);
      c.sigma_rate[end] = v(b.sigma_at[end]);
    } else {
      c.sigma[end] = S(i == 0 ? kernel_.segmentLength(in.t) : 0.0);
      c.sigma_rate[end] = S(i == 0 ? kernel_.segmentRate(in.t, in.rates) : 0.0);
    }
  }
  if (b.point[0] < 0) c.a = a.segment<3>(b.end_at[0]);
  if (b.sigma_at[1] >= 0) c.sigma_acceleration = a(b.sigma_at[1]);
  const MassiveReevingKernel::CableResidual<S> r = kernel_.cableResidual(c, b.k, b.e, in.gravity, in.mass_damping);
  CableValues<S> out = CableValues<S>::Zero(static_cast<Eigen::Index>(b.locals.size()));
  for (int end = 0; end < 2; ++end) {
    if (b.point[end] >= 0) path_.gatherPoint<S>(static_cast<std::size_t>(b.point[end]), R[end], r.node[end], out, b.end_at[end]);
    else out.template segment<3>(b.end_at[end]) = r.node[end];
    if (b.sigma_at[end] >= 0) out(b.sigma_at[end]) = r.sigma[end];
  }
  return out;
}

void MassiveReevedRopeElement::residual(const ElementInput& in, double* r) const {
  const Local q = gather(in.q, q_), v = gather(in.v, v_), a = accelerations(in);
  Eigen::Map<Eigen::VectorXd> out(r, size());
  out.setZero();
  for (const CableBlock& b : cables_) {
    const CableValues<double> share = cableForce<double>(b, gather(q, b.locals), gather(v, b.locals), gather(a, b.locals), in);
    for (std::size_t i = 0; i < b.locals.size(); ++i) out(b.locals[i]) += share(static_cast<Eigen::Index>(i));
  }
}

std::vector<std::vector<int>> MassiveReevedRopeElement::jacobianBlocks() const {
  std::vector<std::vector<int>> out;
  for (const CableBlock& b : cables_) out.push_back(b.locals);
  return out;
}

void MassiveReevedRopeElement::blockJacobian(const ElementInput& in, double cj, bool coordinates_only, double* values) const {
  const Local q = gather(in.q, q_), v = gather(in.v, v_), a = accelerations(in);
  const std::vector<double> sigma = materialCoordinates(in);
  const int n = kernel_.elements_per_part;
  for (const CableBlock& b : cables_) {
    const int size = static_cast<int>(b.locals.size());
    const CableValues<double> qb = gather(q, b.locals), vb = gather(v, b.locals), ab = gather(a, b.locals);
    Eigen::Map<Eigen::MatrixXd> J(values, size, 2 * size);
    values += 2 * size * size;
    const auto differentiate = [&](bool velocities) {
      CableValues<CableDual> qd = qb.cast<CableDual>(), vd = vb.cast<CableDual>();
      CableValues<CableDual>& seeded_values = velocities ? vd : qd;
      for (int k = 0; k < size; ++k) seeded_values(k) = seeded<double, kMaxCableValues>(velocities ? vb(k) : qb(k), k);
      const CableValues<CableDual> r = cableForce<CableDual>(b, qd, vd, ab, in);
      for (int i = 0; i < size; ++i) J.row(i).segment(velocities ? size : 0, size) = r(i).derivatives().head(size).transpose();
    };
    differentiate(false);
    if (coordinates_only) {
      J.rightCols(size).setZero();
      continue;
    }
    differentiate(true);
    if (b.e > 0) {  // the start node's lumped mass
      const double node_mass = kernel_.lineDensity() * (sigma[b.k] - sigma[b.k + 1]) / n;
      for (int i = 0; i < 3; ++i) J(b.end_at[0] + i, size + b.end_at[0] + i) += cj * node_mass;
    }
    if (b.e == n - 1 && b.sigma_at[1] >= 0) J(b.sigma_at[1], size + b.sigma_at[1]) += cj * kernel_.sheave_mass[b.k];
  }
}

void MassiveReevedRopeElement::denseJacobian(const ElementInput& in, double cj, bool coordinates_only, double* J) const {
  const int n = size();
  std::size_t values = 0;
  for (const CableBlock& b : cables_) values += 2 * b.locals.size() * b.locals.size();
  std::vector<double> blocks(values);
  blockJacobian(in, cj, coordinates_only, blocks.data());
  const int columns = coordinates_only ? n : 2 * n;
  Eigen::Map<Eigen::MatrixXd> out(J, n, columns);
  out.setZero();
  const double* at = blocks.data();
  for (const CableBlock& b : cables_) {
    const int size = static_cast<int>(b.locals.size());
    const Eigen::Map<const Eigen::MatrixXd> block(at, size, 2 * size);
    at += 2 * size * size;
    for (int j = 0; j < size; ++j)
      for (int i = 0; i < size; ++i) {
        out(b.locals[i], b.locals[j]) += block(i, j);
        if (!coordinates_only) out(b.locals[i], n + b.locals[j]) += block(i, size + j);
      }
  }
}

void MassiveReevedRopeElement::jacobian(const ElementInput& in, double cj, double* J) const { denseJacobian(in, cj, false, J); }

void MassiveReevedRopeElement::coordinateJacobian(const ElementInput& in, double* J) const { denseJacobian(in, 0.0, true, J); }

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
