#include "cranesim/control/lqr.hpp"

#include <unsupported/Eigen/MatrixFunctions>

#include <stdexcept>

namespace cranesim {

DiscreteSystem zeroOrderHold(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, double h) {
  const Eigen::Index n = A.rows(), m = B.cols();
  Eigen::MatrixXd augmented = Eigen::MatrixXd::Zero(n + m, n + m);
  augmented.topLeftCorner(n, n) = A * h;
  augmented.topRightCorner(n, m) = B * h;
  const Eigen::MatrixXd held = augmented.exp();
  return {held.topLeftCorner(n, n), held.topRightCorner(n, m)};
}

LqrDesign discreteLqr(const DiscreteSystem& system, const Eigen::MatrixXd& Q, const Eigen::MatrixXd& R) {
  const Eigen::MatrixXd& A = system.A;
  const Eigen::MatrixXd& B = system.B;
  const Eigen::Index n = A.rows();
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
  // Doubling: A_k, G_k, H_k with H_k → P (Chu, Fan, Lin's SDA for the DARE).
  Eigen::MatrixXd Ak = A, G = B * R.ldlt().solve(B.transpose()), H = Q;
  LqrDesign design;
  for (design.doublings = 1; design.doublings <= 100; ++design.doublings) {
    const Eigen::PartialPivLU<Eigen::MatrixXd> W(I + G * H);
    const Eigen::MatrixXd WA = W.solve(Ak), WG = W.solve(G);
    const Eigen::MatrixXd H_next = H + Ak.transpose() * H * WA;
    G = G + Ak * WG * Ak.transpose();
    Ak = Ak * WA;
    const double change = (H_next - H).norm();
    H = 0.5 * (H_next + H_next.transpose());
    if (!H.allFinite()) break;
    if (change <= 1e-14 * H.norm()) {
      design.P = H;
      design.K = (R + B.transpose() * H * B).ldlt().solve(B.transpose() * H * A);
      return design;
    }
  }
  throw std::runtime_error("the LQR design does not converge: the model is not stabilisable by its input, or its cost "
                           "does not weigh an unstable mode");
}

}  // namespace cranesim
