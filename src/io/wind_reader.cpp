#include "wind_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "cranesim/math/gauss_legendre.hpp"
#include "cranesim/model/closest_name.hpp"

namespace cranesim {
namespace {

/// The crane industry's rule for a load's wind area when it is not known (manufacturers' load
/// charts: Liebherr's training material, FEM 5.016): 1.2 m² per tonne of mass, with c = 1.2.
constexpr double kLoadWindAreaPerKilogram = 1.2e-3;

/// EN 1991-1-4, Table 4.1: roughness length z₀ and minimum height z_min of terrain categories
/// 0, I, II, III and IV.
struct TerrainCategory {
  const char* name;
  double roughness_length, minimum_height;
};
constexpr TerrainCategory kTerrainCategories[] = {
    {"0", 0.003, 1.0}, {"I", 0.01, 1.0}, {"II", 0.05, 2.0}, {"III", 0.3, 5.0}, {"IV", 1.0, 10.0}};

Vec3 upOf(const Vec3& gravity) { return gravity.norm() > 0.0 ? Vec3(-gravity.normalized()) : Vec3::UnitZ(); }

/// `direction: [x, y, z]` (horizontal) or `azimuth: deg` (from +x towards +y), as a unit vector.
Vec3 readDirection(const YamlField& f, const Vec3& up) {
  if (f.has("direction") == f.has("azimuth")) f.fail("give the wind's direction as exactly one of: direction, azimuth");
  if (const auto a = f.find("azimuth")) {
    const double angle = a->number() * std::numbers::pi / 180.0;
    const Vec3 d(std::cos(angle), std::sin(angle), 0.0);
    const Vec3 horizontal = d - up * up.dot(d);
    if (horizontal.norm() < 1e-6) a->fail("this azimuth points along gravity: give a horizontal direction instead");
    return horizontal.normalized();
  }
  const YamlField df = f.at("direction");
  const Vec3 d = df.vec3();
  if (!(d.norm() > 0.0)) df.fail("the wind's direction must not be zero");
  if (std::abs(up.dot(d)) > 1e-6 * d.norm())
    df.fail(fmt::format("the wind's direction must be horizontal (normal to gravity); its vertical part is {:g}", up.dot(d)));
  return d.normalized();
}

WindProfileSpec readWindProfile(const YamlField& f) {
  WindProfileSpec p;
  const std::string law = f.at("law").choice({"uniform", "power", "logarithmic"});
  if (law == "uniform") {
    f.allowKeys({"law"});
    p.law = WindProfileLaw::Uniform;
  } else if (law == "power") {
    f.allowKeys({"law", "exponent", "minimum_height"});
    p.law = WindProfileLaw::Power;
    p.exponent = f.at("exponent").within(1e-3, 1.0, "");
    p.minimum_height = f.positive("minimum_height", 1.0);
  } else {
    f.allowKeys({"law", "terrain_category", "minimum_height"});
    p.law = WindProfileLaw::Logarithmic;
    const YamlField cf = f.at("terrain_category");
    const std::string name = cf.choice({"0", "I", "II", "III", "IV"});
    const auto c = std::find_if(std::begin(kTerrainCategories), std::end(kTerrainCategories),
                                [&](const TerrainCategory& t) { return name == t.name; });
    p.roughness_length = c->roughness_length;
    p.minimum_height = f.positive("minimum_height", c->minimum_height);
    if (!(p.minimum_height > p.roughness_length))
      f.at("minimum_height").fail(fmt::format("must exceed the roughness length {:g} m of category {}", p.roughness_length, name));
  }
  return p;
}

GustSpec readGust(const YamlField& f, double speed) {
  f.allowKeys({"t_start", "rise_time", "duration", "factor", "peak_speed"});
  GustSpec g;
  g.t_start = f.at("t_start").number();
  g.rise_time = f.at("rise_time").positive();
  const YamlField df = f.at("duration");
  g.duration = df.positive();
  if (g.duration < 2.0 * g.rise_time)
    df.fail(fmt::format("a gust rises and falls in rise_time each, so its duration must be at least 2 · {:g} s", g.rise_time));
  if (f.has("factor") == f.has("peak_speed")) f.fail("give the gust's strength as exactly one of: factor, peak_speed");
  if (const auto pf = f.find("peak_speed")) {
    if (!(speed > 0.0)) pf->fail("a peak speed scales the mean speed, which is 0: give the wind a speed");
    g.factor = pf->nonNegative() / speed;
  } else {
    g.factor = f.at("factor").nonNegative();
  }
  return g;
}

TurbulenceSpec readTurbulence(const YamlField& f, double speed) {
  f.allowKeys({"spectrum", "intensity", "length_scale", "seed", "period", "frequency_max"});
  f.at("spectrum").choice({"kaimal"});
  if (!(speed > 0.0)) f.fail("turbulence is relative to the mean speed, which is 0: give the wind a speed");
  TurbulenceSpec t;
  t.intensity = f.at("intensity").within(1e-6, 1.0, "");
  t.length_scale = f.at("length_scale").within(1e-2, 1e5, "m");
  t.seed = f.at("seed").seed();
  if (const auto ff = f.find("frequency_max")) t.frequency_max = ff->within(1e-2, 50.0, "Hz");
  if (const auto pf = f.find("period")) t.period = pf->within(1.0, 1e5, "s");
  if (t.period * t.frequency_max < 10.0 || t.period * t.frequency_max > 1e6)
    f.fail(fmt::format("period · frequency_max is the number of harmonics, {:g}: keep it within 10 … 10⁶",
                       t.period * t.frequency_max));
  return t;
}

WindBodySpec readExposedBody(const YamlField& f, const Scene& scene) {
  f.allowKeys({"body", "area", "drag_coefficient", "joint"});
  WindBodySpec b;
  b.where = f.where();
  const YamlField bf = f.at("body");
  b.body = bf.text();
  b.where_body = bf.where();
  const auto body = std::find_if(scene.bodies.begin(), scene.bodies.end(), [&](const RigidBodySpec& s) { return s.name == b.body; });
  if (body == scene.bodies.end()) bf.fail(fmt::format("no body '{}' (here: {})", b.body, listedNames(namesOf(scene.bodies))));
  b.drag_coefficient = f.positive("drag_coefficient", 1.2);
  b.area = f.has("area") ? f.at("area").within(1e-6, 1e5, "m²") : kLoadWindAreaPerKilogram * body->mass;
  if (const auto jf = f.find("joint")) {
    b.joint = jf->text();
    b.where_joint = jf->where();
    const std::string own = b.joint.rfind(b.body + ".", 0) == 0 ? b.joint.substr(b.body.size() + 1) : "";
    const bool known = own == "origin" || std::any_of(body->joints.begin(), body->joints.end(), [&](const JointSpec& j) { return j.name == own; });
    if (!known) {
      std::string joints = b.body + ".origin";
      for (const JointSpec& j : body->joints) joints += ", " + b.body + "." + j.name;
      jf->fail(fmt::format("no joint '{}' on body '{}' (its joints: {})", b.joint, b.body, joints));
    }
  }
  return b;
}

WindMemberSpec readExposedMember(const YamlField& f, const Scene& scene) {
  WindMemberSpec m;
  m.where = f.where();
  const YamlField mf = f.at("member");
  m.member = mf.text();
  m.where_member = mf.where();
  const auto member = std::find_if(scene.members.begin(), scene.members.end(), [&](const MemberSpec& s) { return s.name == m.member; });
  if (member == scene.members.end())
    mf.fail(fmt::format("no member '{}' (here: {})", m.member, listedNames(namesOf(scene.members))));
  m.drag_coefficient = f.positive("drag_coefficient", 1.2);
  if (member->reeving && member->reeving->elements_per_part == 0)
    mf.fail(fmt::format("member '{}' is a massless reeved rope: the wind acts on the parts of fidelity: massive only", m.member));
  if (member->type == MemberType::Truss) {
    f.allowKeys({"member", "drag_coefficient", "shielding"});
    if (const auto sf = f.find("shielding")) {
      m.shielding = sf->number();
      if (!(m.shielding > 0.0 && m.shielding <= 1.0)) sf->fail(fmt::format("a shielding factor lies in (0, 1], found {:g}", m.shielding));
    }
    return m;
  }
  f.allowKeys({"member", "diameter", "drag_coefficient"});
  if (const auto df = f.find("diameter")) {
    m.diameter = df->within(1e-4, 1e2, "m");
  } else {
    m.diameter = 2.0 * member->section.outer_radius;
    if (!(m.diameter > 0.0)) f.fail(fmt::format("member '{}' has no round section: give its diameter", m.member));
  }
  return m;
}

}  // namespace

WindSpec readWind(const YamlField& f, const Scene& scene) {
  f.allowKeys({"speed", "reference_height", "direction", "azimuth", "air_density", "ground_height", "profile", "gust",
               "turbulence", "quadrature", "bodies", "members"});
  WindSpec w;
  w.where = f.where();
  WindFieldSpec& field = w.field;
  const Vec3 up = upOf(scene.gravity);
  field.speed = f.at("speed").nonNegative();
  if (field.speed > 200.0) f.at("speed").fail(fmt::format("{:g} m/s is beyond any wind: give the speed in m/s", field.speed));
  field.reference_height = f.positive("reference_height", field.reference_height);
  field.direction = readDirection(f, up);
  if (const auto rf = f.find("air_density")) field.air_density = rf->within(1e-3, 1e2, "kg/m³");
  field.ground_height = f.number("ground_height", 0.0);
  if (const auto pf = f.find("profile")) field.profile = readWindProfile(*pf);
  if (field.profile.law != WindProfileLaw::Uniform && !(field.reference_height > field.profile.roughness_length))
    f.at("reference_height").fail("the reference height must exceed the roughness length");
  if (const auto gf = f.find("gust")) field.gust = readGust(*gf, field.speed);
  if (const auto tf = f.find("turbulence")) field.turbulence = readTurbulence(*tf, field.speed);
  if (const auto qf = f.find("quadrature")) {
    w.quadrature = qf->integer();
    if (w.quadrature < 1 || w.quadrature > kMaxGaussPoints) qf->fail(fmt::format("expected 1 … {} Gauss points", kMaxGaussPoints));
  }
  const auto listedTwice = [](const auto& list, const std::string& name, auto key) {
    return std::count_if(list.begin(), list.end(), [&](const auto& item) { return item.*key == name; }) > 1;
  };
  if (const auto bs = f.find("bodies"))
    for (const YamlField& item : bs->items()) {
      w.bodies.push_back(readExposedBody(item, scene));
      if (listedTwice(w.bodies, w.bodies.back().body, &WindBodySpec::body))
        item.at("body").fail(fmt::format("body '{}' is listed twice", w.bodies.back().body));
    }
  if (const auto ms = f.find("members"))
    for (const YamlField& item : ms->items()) {
      w.members.push_back(readExposedMember(item, scene));
      if (listedTwice(w.members, w.members.back().member, &WindMemberSpec::member))
        item.at("member").fail(fmt::format("member '{}' is listed twice", w.members.back().member));
    }
  if (w.bodies.empty() && w.members.empty()) f.fail("name the parts the wind acts on: bodies, members or both");
  return w;
}

}  // namespace cranesim
