#include "ground_reader.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "cranesim/model/closest_name.hpp"

namespace cranesim {
namespace {

/// A number ≥ 0 and at most `high`.
double upTo(const YamlField& f, double high, const char* unit) {
  const double x = f.nonNegative();
  if (x > high) f.fail(fmt::format("{:g} {} lies outside [0, {:g}] {}", x, unit, high, unit));
  return x;
}

GroundContactSpec readContact(const YamlField& f, const Scene& scene) {
  f.allowKeys({"body", "member", "radius"});
  if (f.has("body") == f.has("member")) f.fail("name the part that rests on the ground as exactly one of: body, member");
  GroundContactSpec c;
  c.where = f.where();
  if (const auto bf = f.find("body")) {
    c.body = bf->text();
    if (std::none_of(scene.bodies.begin(), scene.bodies.end(), [&](const RigidBodySpec& b) { return b.name == c.body; }))
      bf->fail(unknownName("body", c.body, namesOf(scene.bodies)));
  } else {
    const YamlField mf = f.at("member");
    c.member = mf.text();
    const auto m = std::find_if(scene.members.begin(), scene.members.end(), [&](const MemberSpec& s) { return s.name == c.member; });
    if (m == scene.members.end()) mf.fail(unknownName("member", c.member, namesOf(scene.members)));
    if (m->reeving) mf.fail(fmt::format("member '{}' is a reeved rope: it has no nodes of its own to rest on the ground", c.member));
  }
  c.radius = upTo(f.at("radius"), 100.0, "m");
  return c;
}

}  // namespace

GroundSurfaceSpec readGroundSurface(const YamlField& f, const Scene& scene) {
  f.allowKeys({"height", "stiffness", "damping", "smoothing", "friction", "friction_speed", "contacts"});
  GroundSurfaceSpec g;
  g.where = f.where();
  g.height = f.number("height", 0.0);
  const auto contacts = f.find("contacts");
  if (!contacts) {
    for (const char* key : {"stiffness", "damping", "smoothing", "friction", "friction_speed"})
      if (f.has(key)) f.at(key).fail("the ground's contact law needs parts that rest on it: list them under contacts");
    return g;
  }
  g.stiffness = f.at("stiffness").within(1.0, 1e13, "N/m");
  g.damping = upTo(f.at("damping"), 1e12, "N·s/m");
  if (const auto sf = f.find("smoothing")) g.smoothing = sf->within(1e-6, 1.0, "m");
  if (const auto mf = f.find("friction")) g.friction = upTo(*mf, 2.0, "");
  if (const auto vf = f.find("friction_speed")) g.friction_speed = vf->within(1e-4, 10.0, "m/s");
  for (const YamlField& item : contacts->items()) {
    g.contacts.push_back(readContact(item, scene));
    const GroundContactSpec& c = g.contacts.back();
    const auto same = [&](const GroundContactSpec& o) { return o.body == c.body && o.member == c.member; };
    if (std::count_if(g.contacts.begin(), g.contacts.end(), same) > 1)
      item.fail(fmt::format("'{}' is listed twice", c.body.empty() ? c.member : c.body));
  }
  if (g.contacts.empty()) contacts->fail("list the parts that rest on the ground, or leave out contacts");
  return g;
}

}  // namespace cranesim
