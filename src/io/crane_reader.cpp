#include "crane_reader.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "cranesim/model/closest_name.hpp"

namespace cranesim {
namespace {

/// The revolute constraint named at `f`.
std::string revoluteConstraint(const YamlField& f, const Scene& scene) {
  const std::string name = f.text();
  const auto c = std::find_if(scene.constraints.begin(), scene.constraints.end(),
                              [&](const ConstraintSpec& k) { return k.name == name; });
  if (c == scene.constraints.end()) f.fail(unknownName("constraint", name, namesOf(scene.constraints)));
  if (c->type != ConstraintType::Revolute) f.fail(fmt::format("constraint '{}' is not a revolute joint", name));
  return name;
}

BackstopSpec readBackstop(const YamlField& f) {
  f.allowKeys({"angle", "stiffness", "damping", "smoothing", "joint"});
  BackstopSpec b;
  b.where = b.where_joint = f.where();
  if (const auto jf = f.find("joint")) b.joint = jf->text(), b.where_joint = jf->where();
  b.angle_deg = f.at("angle").within(1.0, 179.0, "deg");
  b.stiffness = f.at("stiffness").within(1.0, 1e15, "N·m/rad");
  b.damping = f.at("damping").nonNegative();
  if (const auto sf = f.find("smoothing")) b.smoothing_deg = sf->within(1e-4, 10.0, "deg");
  return b;
}

}  // namespace

CraneSpec readCrane(const YamlField& f, const Scene& scene) {
  f.allowKeys({"slewing", "boom_foot", "boom_head", "hook", "load", "ropes", "backstop", "boom_angle_limit"});
  CraneSpec c;
  c.slewing = revoluteConstraint(f.at("slewing"), scene);
  c.where_slewing = f.at("slewing").where();
  c.boom_foot = revoluteConstraint(f.at("boom_foot"), scene);
  c.where_boom_foot = f.at("boom_foot").where();
  c.boom_head = f.at("boom_head").text();
  c.where_boom_head = f.at("boom_head").where();
  c.hook = f.at("hook").text();
  c.where_hook = f.at("hook").where();
  if (const auto load = f.find("load")) {
    c.load = load->text();
    if (std::none_of(scene.bodies.begin(), scene.bodies.end(), [&](const RigidBodySpec& b) { return b.name == c.load; }))
      load->fail(unknownName("body", c.load, namesOf(scene.bodies)));
  }
  std::vector<std::string> ropes;
  for (const MemberSpec& m : scene.members)
    if (m.type == MemberType::Rope) ropes.push_back(m.name);
  if (const auto list = f.find("ropes"))
    for (const YamlField& item : list->items()) {
      const std::string name = item.text();
      if (std::find(ropes.begin(), ropes.end(), name) == ropes.end()) item.fail(unknownName("rope", name, ropes));
      if (std::find(c.ropes.begin(), c.ropes.end(), name) != c.ropes.end()) item.fail(fmt::format("'{}' is listed twice", name));
      c.ropes.push_back(name);
    }
  if (const auto bf = f.find("backstop")) c.backstop = readBackstop(*bf);
  if (const auto lf = f.find("boom_angle_limit")) c.boom_angle_limit_deg = lf->within(1.0, 180.0, "deg");
  if (c.backstop && c.backstop->angle_deg > c.boom_angle_limit_deg)
    f.at("backstop").at("angle").fail(fmt::format("the backstop engages at {:g}°, beyond the boom angle limit {:g}°: the boom "
                                                  "would leave its envelope before touching it", c.backstop->angle_deg,
                                                  c.boom_angle_limit_deg));
  return c;
}

}  // namespace cranesim
