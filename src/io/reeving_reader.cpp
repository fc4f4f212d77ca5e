#include "reeving_reader.hpp"

#include <fmt/format.h>

#include <numbers>
#include <string>

namespace cranesim {
namespace {

/// A sheave's efficiency: a tension ratio in (0, 1].
double readEfficiency(const YamlField& f) {
  const double eta = f.number();
  if (!(eta > 0.0 && eta <= 1.0))
    f.fail(fmt::format("a sheave's efficiency is the tension ratio across it, in (0, 1]; found {:g}", eta));
  return eta;
}

/// A capstan's friction coefficient μ of rope on steel: in [0, 1].
double readFriction(const YamlField& f) {
  const double mu = f.number();
  if (!(mu >= 0.0 && mu <= 1.0))
    f.fail(fmt::format("a capstan's friction coefficient μ (rope on a drum or saddle, about 0.1) lies in [0, 1]; "
                       "found {:g}", mu));
  return mu;
}

/// A capstan's wrap angle, degrees in (0, 3600] (up to ten turns on a drum), as radians.
double readWrap(const YamlField& f) {
  const double degrees = f.number();
  if (!(degrees > 0.0 && degrees <= 3600.0))
    f.fail(fmt::format("a capstan's wrap angle lies in (0, 3600] degrees (up to ten turns); found {:g}", degrees));
  return degrees * std::numbers::pi / 180.0;
}

/// A turning sheave's rotary inertia J about its axle, kg·m², on a massive rope only: the
/// massless rope has no coordinate of the material running over its sheaves to carry it.
double readSheaveInertia(const YamlField& f, bool massive) {
  if (!massive)
    f.fail("a sheave's inertia needs fidelity: massive (the rope's speed over the sheave is a coordinate there; "
           "massless parts have none to carry it)");
  return f.nonNegative();
}

/// `{joint: <body>.<joint>, radius: r, efficiency: η, inertia: J}`, η defaulting to the rope's,
/// J to 0, or a capstan `{joint, radius, friction: μ, wrap_deg: θ}`, θ defaulting to the drawn
/// path's turn.
SheaveSpec readSheave(const YamlField& f, double efficiency, bool massive) {
  if (!f.isMap())
    f.fail("a sheave is {joint: <body>.<joint>, radius: r} (and optionally efficiency: η and inertia: J, or friction: μ "
           "and wrap_deg: θ for a capstan); only the path's first point (the winch) and last (the dead end) are bare joints");
  f.allowKeys({"joint", "radius", "efficiency", "inertia", "friction", "wrap_deg"});
  SheaveSpec s;
  s.joint = f.at("joint").text();
  s.where = f.at("joint").where();
  const YamlField radius = f.at("radius");
  s.radius = radius.number();
  if (!(s.radius > 0.0)) radius.fail(fmt::format("a sheave's radius must be positive, found {:g}", s.radius));
  if (s.radius > YamlField::kMaxCoordinate) radius.fail(fmt::format("a radius of {:g} m is beyond any crane's sheave", s.radius));
  if (const auto mu = f.find("friction")) {
    for (const char* turning : {"efficiency", "inertia"})
      if (f.has(turning))
        f.at(turning).fail(fmt::format("a capstan (a sheave with friction) does not turn: it has no {}",
                                       turning == std::string("efficiency") ? "bearing efficiency" : "rotary inertia"));
    s.friction = readFriction(*mu);
    if (const auto wrap = f.find("wrap_deg")) s.wrap = readWrap(*wrap);
    return s;
  }
  if (f.has("wrap_deg"))
    f.at("wrap_deg").fail("wrap_deg belongs to a capstan: give the rope's friction on it as friction: μ");
  s.efficiency = f.has("efficiency") ? readEfficiency(f.at("efficiency")) : efficiency;
  if (const auto inertia = f.find("inertia")) s.inertia = readSheaveInertia(*inertia, massive);
  return s;
}

std::string jointName(const YamlField& f) {
  if (!f.isScalar()) f.fail("the path's first point (the winch) and last (the dead end) are joints '<part>.<joint>'");
  return f.text();
}

/// `fidelity: massless` (the default) or `massive` with `elements_per_part: n` (default 8).
int readElementsPerPart(const YamlField& f) {
  constexpr int kDefault = 8, kMost = 64;
  const bool massive = f.has("fidelity") && f.at("fidelity").choice({"massless", "massive"}) == "massive";
  if (!f.has("elements_per_part")) return massive ? kDefault : 0;
  const YamlField n = f.at("elements_per_part");
  if (!massive) n.fail("elements_per_part belongs to fidelity: massive (parts that carry the rope's mass)");
  const int elements = n.integer();
  if (elements < 2 || elements > kMost)
    n.fail(fmt::format("a massive part is a chain of 2…{} cable elements (2 to sag at all); found {}", kMost, elements));
  return elements;
}

}  // namespace

ReevingSpec readReeving(const YamlField& f) {
  ReevingSpec r;
  r.elements_per_part = readElementsPerPart(f);
  const double efficiency = f.has("efficiency") ? readEfficiency(f.at("efficiency")) : 1.0;
  if (const auto b = f.find("speed_band")) {
    if (r.elements_per_part == 0)
      b->fail("speed_band belongs to fidelity: massive; a massless rope's sheaves grip it (pre-sliding) instead");
    r.speed_band = b->positive();
  }
  if (const auto d = f.find("pre_sliding")) {
    if (r.elements_per_part > 0)
      d->fail("pre_sliding belongs to a massless rope, whose sheaves grip it; a massive rope's take speed_band");
    r.pre_sliding = d->positive();
  }
  if (f.has("path") == f.has("falls"))
    f.fail("a reeved rope has either a path (winch, sheaves, dead end) or falls between a head and a hook block");
  if (const auto path = f.find("path")) {
    for (const char* key : {"winch", "head", "hook"})
      if (f.has(key)) f.at(key).fail(fmt::format("'{}' belongs to falls: n; a path names its points itself", key));
    const std::vector<YamlField> points = path->items();
    if (points.size() < 3)
      path->fail(fmt::format("a path runs from the winch over at least one sheave to the dead end; found {} point(s)",
                             points.size()));
    if (points.size() > static_cast<std::size_t>(ReevedRopeKernel::kMaxPoints))
      path->fail(fmt::format("a path has at most {} points, found {}", ReevedRopeKernel::kMaxPoints, points.size()));
    r.winch = jointName(points.front());
    r.where_winch = points.front().where();
    for (std::size_t i = 1; i + 1 < points.size(); ++i) r.sheaves.push_back(readSheave(points[i], efficiency, r.elements_per_part > 0));
    r.dead_end = jointName(points.back());
    r.where_dead_end = points.back().where();
  } else {
    const YamlField n = f.at("falls");
    const int falls = n.integer();
    constexpr int kMaxFalls = ReevedRopeKernel::kMaxPoints - 2;
    if (falls < 1 || falls > kMaxFalls)
      n.fail(fmt::format("the falls (parts of line) between the blocks must be 1…{}, found {}", kMaxFalls, falls));
    r.winch = f.at("winch").text();
    r.where_winch = f.at("winch").where();
    const bool massive = r.elements_per_part > 0;
    const SheaveSpec head = readSheave(f.at("head"), efficiency, massive), hook = readSheave(f.at("hook"), efficiency, massive);
    // winch → head → hook → head … : n falls over n sheaves, the dead end on the block the last
    // fall reaches.
    for (int i = 0; i < falls; ++i) r.sheaves.push_back(i % 2 == 0 ? head : hook);
    const SheaveSpec& end = falls % 2 == 0 ? head : hook;
    r.dead_end = end.joint;
    r.where_dead_end = end.where;
  }
  return r;
}

}  // namespace cranesim
