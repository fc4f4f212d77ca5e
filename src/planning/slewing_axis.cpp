#include "cranesim/planning/slewing_axis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "cranesim/model/compile.hpp"

namespace cranesim {

double SlewingAxis::radiusAt(double x) const { return std::hypot(x - point.x(), plane_y - point.y()); }

double SlewingAxis::xAtRadius(double radius) const {
  const double offset = std::abs(plane_y - point.y());
  if (!(radius >= offset))
    throw std::domain_error(fmt::format("a radius of {:g} m lies inside the crane's plane, {:.4g} m from the slewing axis", radius, offset));
  return point.x() + side * std::sqrt(radius * radius - offset * offset);
}

SlewingAxis slewingAxisOf(const Scene& scene, const std::string& constraint, const std::string& end_point) {
  const Model model = compileModel(scene);
  const auto c = std::find_if(model.constraints.begin(), model.constraints.end(), [&](const Constraint& k) { return k.name == constraint; });
  if (c == model.constraints.end()) throw std::invalid_argument(fmt::format("the scene has no constraint '{}'", constraint));
  if (c->type != ConstraintType::Revolute) throw std::invalid_argument(fmt::format("'{}' is not a revolute constraint", constraint));
  const Frame frame = model.jointFrame(model.q0.data(), c->joint1);
  const Vec3 axis = frame.R.col(c->axis);
  if (axis.cross(scene.gravity.normalized()).norm() > 1e-6)
    throw std::invalid_argument(fmt::format("'{}' turns about ({:.3g}, {:.3g}, {:.3g}) in the drawing, which is not vertical",
                                            constraint, axis.x(), axis.y(), axis.z()));
  const int joint = model.findJoint(end_point);
  if (joint < 0) throw std::invalid_argument(fmt::format("the scene has no joint '{}'", end_point));
  const Vec3 end = model.jointFrame(model.q0.data(), joint).r;
  SlewingAxis a;
  a.constraint = constraint;
  a.point = frame.r.head<2>();
  a.plane_y = end.y();
  a.side = end.x() < frame.r.x() ? -1.0 : 1.0;
  return a;
}

}  // namespace cranesim
