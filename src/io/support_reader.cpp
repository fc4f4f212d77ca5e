#include "support_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <set>

#include "cranesim/model/closest_name.hpp"

namespace cranesim {
namespace {

/// Soil classes: a modulus of subgrade reaction for a pad about 1 m wide (Bowles, Foundation
/// Analysis and Design, 5th ed., Table 9-1, the middle of its ranges) and the presumed allowable
/// bearing pressure (BS 8004:1986 Table 1). Both quoted from memory: check against the sources
/// and the site's ground investigation before relying on them.
struct SoilClass {
  const char* name;
  double subgrade_modulus;    // N/m³
  double allowable_pressure;  // Pa
};
constexpr SoilClass kSoilClasses[] = {
    {"loose_sand", 10.0e6, 100.0e3},   {"medium_dense_sand", 40.0e6, 200.0e3}, {"dense_sand", 100.0e6, 400.0e3},
    {"dense_gravel", 150.0e6, 600.0e3}, {"firm_clay", 20.0e6, 100.0e3},        {"stiff_clay", 40.0e6, 200.0e3},
};

SoilSpec readSoil(const YamlField& f) {
  SoilSpec soil;
  if (const auto cf = f.find("class")) {
    f.allowKeys({"class"});
    soil.soil_class = cf->text();
    const auto c = std::find_if(std::begin(kSoilClasses), std::end(kSoilClasses), [&](const SoilClass& s) { return soil.soil_class == s.name; });
    if (c == std::end(kSoilClasses)) {
      std::vector<std::string> names;
      for (const SoilClass& s : kSoilClasses) names.emplace_back(s.name);
      cf->fail(unknownName("soil class", soil.soil_class, names));
    }
    soil.subgrade_modulus = c->subgrade_modulus;
    soil.allowable_pressure = c->allowable_pressure;
    return soil;
  }
  f.allowKeys({"subgrade_modulus", "allowable_pressure"});
  if (!f.has("subgrade_modulus") || !f.has("allowable_pressure"))
    f.fail("give the soil as {class: …} or as {subgrade_modulus: N/m³, allowable_pressure: Pa}");
  soil.subgrade_modulus = f.at("subgrade_modulus").within(1e5, 1e13, "N/m³");
  soil.allowable_pressure = f.at("allowable_pressure").within(1e3, 1e9, "Pa");
  return soil;
}

/// A joint `<body>.<name>` of the supported body, checked against its joints.
std::string supportJoint(const YamlField& f, const RigidBodySpec& body) {
  const std::string joint = f.text();
  const std::string prefix = body.name + ".";
  if (joint.rfind(prefix, 0) != 0)
    f.fail(fmt::format("'{}' is not a joint of the supported body '{}': supports stand under it, named '{}<joint>'", joint, body.name, prefix));
  const std::string name = joint.substr(prefix.size());
  std::vector<std::string> names{"origin"};
  for (const JointSpec& j : body.joints) names.push_back(j.name);
  if (std::find(names.begin(), names.end(), name) == names.end()) f.fail(unknownName(fmt::format("joint of body '{}'", body.name), name, names));
  return joint;
}

SupportPadSpec readPad(const YamlField& f, const RigidBodySpec& body) {
  f.allowKeys({"name", "joint", "area"});
  SupportPadSpec pad;
  pad.where = f.where();
  pad.name = f.at("name").identifier();
  pad.where_joint = f.at("joint").where();
  pad.joint = supportJoint(f.at("joint"), body);
  pad.area = f.at("area").within(1e-3, 100.0, "m²");
  return pad;
}

SupportTrackSpec readTrack(const YamlField& f, const RigidBodySpec& body) {
  f.allowKeys({"name", "from", "to", "width", "segments"});
  SupportTrackSpec track;
  track.where = f.where();
  track.name = f.at("name").identifier();
  track.where_from = f.at("from").where();
  track.from = supportJoint(f.at("from"), body);
  track.where_to = f.at("to").where();
  track.to = supportJoint(f.at("to"), body);
  if (track.from == track.to) f.at("to").fail("a track runs between two different joints");
  track.width = f.at("width").within(0.05, 10.0, "m");
  if (const auto sf = f.find("segments")) {
    track.segments = sf->integer();
    if (track.segments < 2 || track.segments > 1000) sf->fail(fmt::format("{} segments: a track needs 2 to 1000", track.segments));
  }
  return track;
}

}  // namespace

GroundSupportsSpec readGroundSupports(const YamlField& f, const Scene& scene) {
  f.allowKeys({"body", "soil", "damping_ratio", "shear_ratio", "friction", "smoothing", "pads", "tracks"});
  GroundSupportsSpec s;
  s.where = f.where();
  const YamlField bf = f.at("body");
  s.where_body = bf.where();
  s.body = bf.text();
  const auto body = std::find_if(scene.bodies.begin(), scene.bodies.end(), [&](const RigidBodySpec& b) { return b.name == s.body; });
  if (body == scene.bodies.end()) bf.fail(unknownName("body", s.body, namesOf(scene.bodies)));
  s.soil = readSoil(f.at("soil"));
  if (const auto df = f.find("damping_ratio")) {
    s.damping_ratio = df->nonNegative();
    if (s.damping_ratio > 2.0) df->fail(fmt::format("{:g} lies outside [0, 2]", s.damping_ratio));
  }
  if (const auto rf = f.find("shear_ratio")) s.shear_ratio = rf->within(0.01, 10.0, "");
  if (const auto ff = f.find("friction")) s.friction = ff->within(0.01, 2.0, "");
  if (const auto sf = f.find("smoothing")) s.smoothing = sf->within(1e-4, 1.0, "of the mean settlement");
  std::set<std::string> names;
  const auto unique = [&](const YamlField& item, const std::string& name) {
    if (!names.insert(name).second) item.at("name").fail(fmt::format("a support named '{}' is listed twice", name));
  };
  if (const auto pf = f.find("pads"))
    for (const YamlField& item : pf->items()) {
      s.pads.push_back(readPad(item, *body));
      unique(item, s.pads.back().name);
    }
  if (const auto tf = f.find("tracks"))
    for (const YamlField& item : tf->items()) {
      s.tracks.push_back(readTrack(item, *body));
      unique(item, s.tracks.back().name);
    }
  if (s.tracks.empty() && s.pads.size() < 3)
    f.fail(fmt::format("{} pad(s) and no track: a carriage stands on at least three pads or on tracks", s.pads.size()));
  if (s.tracks.size() == 1 && s.pads.empty())
    f.fail("one track and no pads: a carriage on a single line of support falls over; give two tracks or add pads");
  return s;
}

}  // namespace cranesim
