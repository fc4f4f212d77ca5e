#pragma once

#include <Eigen/Dense>

namespace cranesim {

template <class S> using Vec3T = Eigen::Matrix<S, 3, 1>;
template <class S> using Mat3T = Eigen::Matrix<S, 3, 3>;
using Vec3 = Vec3T<double>;
using Mat3 = Mat3T<double>;
using VecX = Eigen::VectorXd;
using MatX = Eigen::MatrixXd;

/// A frame: origin position and rotation matrix (frame axes → inertial), both in the inertial frame.
template <class S> struct FrameT {
  Vec3T<S> r;
  Mat3T<S> R;
};
using Frame = FrameT<double>;

}  // namespace cranesim
