#include "reeving_reader.hpp"

#include <fmt/format.h>

namespace cranesim {
namespace {

/// A sheave's efficiency: a tension ratio in (0, 1].
double readEfficiency(const YamlField& f) {
  const double eta = f.number();
  if (!(eta > 0.0 && eta <= 1.0))
    f.fail(fmt::format("a sheave's efficiency is the tension ratio across it, in (0, 1]; found {:g}", eta));
  return eta;
}

/// `{joint: <body>.<joint>, radius: r, efficiency: η}`, η defaulting to the rope's.
SheaveSpec readSheave(const YamlField& f, double efficiency) {
  if (!f.isMap())
    f.fail("a sheave is {joint: <body>.<joint>, radius: r} (and optionally efficiency: η); only the path's first "
           "point (the winch) and last (the dead end) are bare joints");
  f.allowKeys({"joint", "radius", "efficiency"});
  SheaveSpec s;
  s.joint = f.at("joint").text();
  s.where = f.at("joint").where();
  const YamlField radius = f.at("radius");
  s.radius = radius.number();
  if (!(s.radius > 0.0)) radius.fail(fmt::format("a sheave's radius must be positive, found {:g}", s.radius));
  if (s.radius > YamlField::kMaxCoordinate) radius.fail(fmt::format("a radius of {:g} m is beyond any crane's sheave", s.radius));
  s.efficiency = f.has("efficiency") ? readEfficiency(f.at("efficiency")) : efficiency;
  return s;
}

std::string jointName(const YamlField& f) {
  if (!f.isScalar()) f.fail("the path's first point (the winch) and last (the dead end) are joints '<part>.<joint>'");
  return f.text();
}

}  // namespace

ReevingSpec readReeving(const YamlField& f) {
  ReevingSpec r;
  const double efficiency = f.has("efficiency") ? readEfficiency(f.at("efficiency")) : 1.0;
  if (const auto b = f.find("speed_band")) r.speed_band = b->positive();
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
    for (std::size_t i = 1; i + 1 < points.size(); ++i) r.sheaves.push_back(readSheave(points[i], efficiency));
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
    const SheaveSpec head = readSheave(f.at("head"), efficiency), hook = readSheave(f.at("hook"), efficiency);
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
