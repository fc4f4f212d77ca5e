#include "rotation_reader.hpp"

#include "cranesim/math/rotation.hpp"
#include "cranesim/math/units.hpp"
#include "yaml_field.hpp"

namespace cranesim {
Mat3 readRotation(const YamlField& f) {
  f.allowKeys({"axis", "angle", "angle_deg", "rotation_vector", "matrix"});
  const int forms = f.has("rotation_vector") + f.has("matrix") + f.has("axis");
  if (forms != 1) f.fail("give exactly one of: axis with angle or angle_deg, rotation_vector, matrix");
  if (const auto rv = f.find("rotation_vector")) return rotationMatrix<double>(rv->vec3());
  if (const auto mf = f.find("matrix")) {
    const auto rows = mf->items();
    if (rows.size() != 3) mf->fail("expected 3 rows of 3 numbers");
    Mat3 R;
    for (int r = 0; r < 3; ++r) R.row(r) = rows[r].vec3().transpose();
    if ((R.transpose() * R - Mat3::Identity()).norm() > 1e-9 || R.determinant() < 0.0)
      mf->fail("is not a rotation matrix (orthonormal, determinant +1) to 1e-9");
    return R;
  }
  const YamlField axis_field = f.at("axis");
  const Vec3 axis = axis_field.vec3();
  if (axis.norm() < 1e-12) axis_field.fail("axis must not be the zero vector");
  if (f.has("angle") && f.has("angle_deg")) f.at("angle_deg").fail("give either angle (rad) or angle_deg, not both");
  if (!f.has("angle") && !f.has("angle_deg")) f.fail("an axis needs an angle (rad) or angle_deg");
  const double angle = f.has("angle") ? f.at("angle").number() : f.at("angle_deg").number() * kRadiansPerDegree;
  return axisAngle(axis, angle);
}

}  // namespace cranesim
