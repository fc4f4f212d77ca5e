#include "cranesim/io/scene_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "boom_assembly.hpp"
#include "bounded_yaml.hpp"
#include "crane_reader.hpp"
#include "cranesim/math/gauss_legendre.hpp"
#include "cranesim/math/rotation.hpp"
#include "cranesim/model/closest_name.hpp"
#include "member_ends.hpp"
#include "profile_reader.hpp"
#include "reeving_reader.hpp"
#include "rotation_reader.hpp"
#include "scene_composition.hpp"
#include "sensor_reader.hpp"
#include "solver_reader.hpp"
#include "ground_reader.hpp"
#include "support_reader.hpp"
#include "wind_reader.hpp"
#include "yaml_field.hpp"

namespace cranesim {
namespace {

Mat3 readInertia(const YamlField& f) {
  const std::vector<double> v = f.isSequence() && !f.items().empty() && f.items()[0].isSequence()
                                    ? std::vector<double>{}
                                    : f.numbers();
  Mat3 I = Mat3::Zero();
  if (v.size() == 3) {
    I.diagonal() << v[0], v[1], v[2];
  } else if (v.size() == 6) {
    I << v[0], v[3], v[4], v[3], v[1], v[5], v[4], v[5], v[2];
  } else if (v.empty()) {
    const auto rows = f.items();
    if (rows.size() != 3) f.fail("expected [Ixx, Iyy, Izz], [Ixx, Iyy, Izz, Ixy, Ixz, Iyz] or a 3×3 matrix");
    for (int r = 0; r < 3; ++r) I.row(r) = rows[r].vec3().transpose();
    if ((I - I.transpose()).norm() > 1e-12 * I.norm()) f.fail("inertia matrix must be symmetric");
  } else {
    f.fail("expected [Ixx, Iyy, Izz], [Ixx, Iyy, Izz, Ixy, Ixz, Iyz] or a 3×3 matrix");
  }
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(I);
  const Vec3 p = eig.eigenvalues();
  if (p.minCoeff() <= 0.0) f.fail(fmt::format("inertia must be positive definite (principal moments {}, {}, {})", p(0), p(1), p(2)));
  if (p(0) + p(1) < p(2) * (1.0 - 1e-9))
    f.fail(fmt::format("principal moments {}, {}, {} violate the triangle inequality: no physical body has them", p(0), p(1), p(2)));
  return I;
}

std::vector<JointSpec> readJoints(const YamlField& list) {
  std::vector<JointSpec> joints;
  std::set<std::string> names;
  for (const YamlField& f : list.items()) {
    f.allowKeys({"name", "position", "rotation"});
    JointSpec j;
    j.name = f.at("name").identifier();
    if (!names.insert(j.name).second) f.at("name").fail(fmt::format("duplicate joint name '{}'", j.name));
    j.position = f.position("position", Vec3::Zero());
    if (const auto r = f.find("rotation")) j.rotation = readRotation(*r);
    j.where = f.where();
    joints.push_back(std::move(j));
  }
  return joints;
}

RigidBodySpec readBody(const YamlField& f) {
  f.allowKeys({"name", "type", "mass", "centroid", "inertia", "position", "rotation", "velocity",
               "angular_velocity", "joints"});
  RigidBodySpec b;
  b.name = f.at("name").identifier();
  if (b.name == "ground") f.at("name").fail("'ground' is reserved for the inertial frame");
  if (const auto type = f.find("type")) type->choice({"rigid"});
  b.mass = f.at("mass").positive();
  b.centroid = f.position("centroid", Vec3::Zero());
  b.inertia = readInertia(f.at("inertia"));
  b.position = f.position("position", Vec3::Zero());
  if (const auto r = f.find("rotation")) b.rotation = readRotation(*r);
  b.velocity = f.vec3("velocity", Vec3::Zero());
  b.angular_velocity = f.vec3("angular_velocity", Vec3::Zero());
  if (const auto j = f.find("joints")) b.joints = readJoints(*j);
  b.where = f.where();
  return b;
}

// Cross-sections from a wire of 10 µm to a tube of 100 m radius (a crane's are 5 mm … 1 m).
constexpr double kMinRadius = 1e-5, kMaxRadius = 100.0;

Section readSection(const YamlField& f, double poisson) {
  if (f.has("radius")) {
    f.allowKeys({"radius"});
    return Section::circular(f.at("radius").within(kMinRadius, kMaxRadius, "m"), 0.0, poisson);
  }
  if (f.has("outer_radius")) {
    f.allowKeys({"outer_radius", "inner_radius"});
    const double outer = f.at("outer_radius").within(kMinRadius, kMaxRadius, "m");
    const double inner = f.has("inner_radius") ? f.at("inner_radius").nonNegative() : 0.0;
    if (inner >= outer) f.at("inner_radius").fail(fmt::format("inner radius {} must be below the outer radius {}", inner, outer));
    return Section::circular(outer, inner, poisson);
  }
  f.allowKeys({"area", "Iy", "Iz", "J", "shear_factor"});
  Section s;
  s.area = f.at("area").within(kMinRadius * kMinRadius, kMaxRadius * kMaxRadius, "m²");
  s.Iy = f.at("Iy").within(std::pow(kMinRadius, 4), std::pow(kMaxRadius, 4), "m⁴");
  s.Iz = f.at("Iz").within(std::pow(kMinRadius, 4), std::pow(kMaxRadius, 4), "m⁴");
  s.J = f.at("J").within(std::pow(kMinRadius, 4), std::pow(kMaxRadius, 4), "m⁴");
  s.shear_factor = f.has("shear_factor") ? f.at("shear_factor").positive() : 0.0;
  return s;
}

Material readMaterial(const YamlField& f, double& poisson) {
  f.allowKeys({"density", "youngs_modulus", "poisson_ratio", "shear_modulus"});
  Material m;
  m.density = f.at("density").within(1e-3, 1e6, "kg/m³");
  m.youngs_modulus = f.at("youngs_modulus").within(1e3, 1e15, "Pa");
  if (f.has("poisson_ratio") && f.has("shear_modulus")) f.at("shear_modulus").fail("give either poisson_ratio or shear_modulus");
  if (f.has("shear_modulus")) {
    m.shear_modulus = f.at("shear_modulus").positive();
    poisson = m.youngs_modulus / (2.0 * m.shear_modulus) - 1.0;
  } else {
    poisson = f.number("poisson_ratio", 0.3);
    if (poisson <= -1.0 || poisson >= 0.5) f.at("poisson_ratio").fail(fmt::format("must lie in (−1, 0.5), found {}", poisson));
    m.shear_modulus = m.youngs_modulus / (2.0 * (1.0 + poisson));
  }
  return m;
}

/// `[a, b]`: two node numbers counted from 1 as in the thesis' tables, stored from 0.
TrussNodePair readNodePair(const YamlField& f) {
  const auto items = f.items();
  if (items.size() != 2) f.fail(fmt::format("expected two node numbers [from, to], found {} entries", items.size()));
  return {{items[0].integer() - 1, items[1].integer() - 1}, f.where()};
}

std::vector<TrussNodePair> readNodePairs(const YamlField& f) {
  std::vector<TrussNodePair> pairs;
  for (const YamlField& item : f.items()) pairs.push_back(readNodePair(item));
  return pairs;
}

TrussTube readTube(const YamlField& f) {
  f.allowKeys({"outer_radius", "inner_radius"});
  return {f.at("outer_radius").within(kMinRadius, kMaxRadius, "m"), f.number("inner_radius", 0.0), f.where()};
}

/// One entry of `trusses:` (a truss type, Table D-3). Indices and radii are checked by
/// buildTrussGeometry, which reports them at the locations recorded here.
TrussDescription readTruss(const YamlField& f) {
  f.allowKeys({"name", "length", "order", "sections", "main_beams", "lacing", "tubes", "material"});
  TrussDescription d;
  d.where = f.where();
  d.name = f.at("name").identifier();
  d.length = f.at("length").positive();
  d.where_length = f.at("length").where();
  d.order = f.at("order").integer();
  d.where_order = f.at("order").where();
  const YamlField sections = f.at("sections");
  const auto section_items = sections.items();
  if (section_items.size() != 2) sections.fail(fmt::format("a truss has exactly 2 end sections, found {}", section_items.size()));
  for (int s = 0; s < 2; ++s) {
    const YamlField& sf = section_items[s];
    sf.allowKeys({"nodes", "cross_beams"});
    TrussEndSection& sec = d.sections[s];
    sec.where = sf.where();
    sec.where_nodes = sf.at("nodes").where();
    for (const YamlField& n : sf.at("nodes").items()) {
      const std::vector<double> yz = n.numbers();
      if (yz.size() != 2) n.fail(fmt::format("expected a node's [y, z] in the end-section frame, found {} numbers", yz.size()));
      if (std::max(std::abs(yz[0]), std::abs(yz[1])) > YamlField::kMaxCoordinate)
        n.fail(fmt::format("a node {:g} m from the truss axis: scene geometry must lie within {:g} m", std::max(std::abs(yz[0]), std::abs(yz[1])), YamlField::kMaxCoordinate));
      sec.nodes.emplace_back(yz[0], yz[1]);
    }
    if (const auto cb = sf.find("cross_beams")) sec.cross_beams = readNodePairs(*cb);
  }
  d.main_beams = readNodePairs(f.at("main_beams"));
  d.where_main_beams = f.at("main_beams").where();
  const std::string lacing = f.at("lacing").choice({"type1", "anti_type1", "tp_type1", "tp_anti_type1"});
  d.lacing = lacing == "type1"        ? LacingForm::Type1
             : lacing == "anti_type1" ? LacingForm::AntiType1
             : lacing == "tp_type1"   ? LacingForm::TPType1
                                      : LacingForm::TPAntiType1;
  d.where_lacing = f.at("lacing").where();
  const YamlField tubes = f.at("tubes");
  tubes.allowKeys({"main", "cross", "sub"});
  d.main_tube = readTube(tubes.at("main"));
  d.cross_tube = readTube(tubes.at("cross"));
  d.sub_tube = readTube(tubes.at("sub"));
  d.material = readMaterial(f.at("material"), d.poisson_ratio);
  return d;
}

/// A rope's unstretched length must stay positive from t_start to t_end: one that runs out
/// crawled at ever smaller steps, one that went negative stopped as a "locked mechanism". It must
/// also stay within what its elements can carry: at least kMinSegmentLength per element (a
/// length of 1e-308 m left the rope without mass, a singular saddle-point matrix and exit 1 from
/// check) and at most the scene's extent (1e308 m did the same). The profile is checked at its
/// breakpoints, the interval's ends and 10 000 points between.
void requireRopeLength(const MemberSpec& m, const YamlField& f, const SolverSpec& solver) {
  if (!m.length) return;
  constexpr double kMinSegmentLength = 1e-3;  // m
  const Profile& length = *m.length;
  std::vector<double> times = length.breakpoints();
  constexpr int kSamples = 10000;
  for (int k = 0; k <= kSamples; ++k)
    times.push_back(solver.t_start + (solver.t_end - solver.t_start) * k / kSamples);
  std::sort(times.begin(), times.end());
  double shortest = length(solver.t_start, Limit::Right), when = solver.t_start, out = solver.t_end;
  double longest = shortest, when_longest = solver.t_start;
  bool ran_out = false;
  for (const double t : times) {
    if (t < solver.t_start || t > solver.t_end) continue;
    for (const Limit side : {Limit::Left, Limit::Right}) {
      const double l = length(t, side);
      if (l < shortest) shortest = l, when = t;
      if (l > longest) longest = l, when_longest = t;
      if (l <= 0.0 && !ran_out) ran_out = true, out = t;
    }
  }
  const YamlField l = f.at("length");
  const std::string type = l.isMap() && l.has("type") ? l.at("type").text() : "constant";
  if (ran_out)
    l.fail(fmt::format("rope '{}' runs out: its length ({} profile) reaches 0 at t = {:.4g} s and {:g} m at t = {:.4g} s; it "
                       "must stay positive from t_start = {:g} s to t_end = {:g} s",
                       m.name, type, out, shortest, when, solver.t_start, solver.t_end));
  if (shortest < kMinSegmentLength * m.segments)
    l.fail(fmt::format("rope '{}' is too short for its {} element(s): its length ({} profile) is {:g} m at t = {:.4g} s; "
                       "keep at least {:g} m per element", m.name, m.segments, type, shortest, when, kMinSegmentLength));
  if (longest > YamlField::kMaxCoordinate)
    l.fail(fmt::format("rope '{}' is {:g} m long at t = {:.4g} s ({} profile): scene geometry must lie within {:g} m",
                       m.name, longest, when_longest, type, YamlField::kMaxCoordinate));
}

TrussFidelity readFidelity(const YamlField& f) {
  const std::string chosen = f.choice({"super_truss", "condensed", "beam", "members"});
  return chosen == "members"     ? TrussFidelity::Members
         : chosen == "condensed" ? TrussFidelity::Condensed
         : chosen == "beam"      ? TrussFidelity::Beam
                                 : TrussFidelity::SuperTruss;
}

/// `defaults:`, what members take where they leave a key out.
struct MemberDefaults {
  std::optional<TrussFidelity> truss_fidelity;
};

MemberDefaults readDefaults(const YamlField& f) {
  f.allowKeys({"truss_fidelity"});
  MemberDefaults d;
  if (const auto fidelity = f.find("truss_fidelity")) d.truss_fidelity = readFidelity(*fidelity);
  return d;
}

/// `type: truss`: a placed truss type (its drawn length is checked by placeMemberEnds).
void readTrussMember(const YamlField& f, MemberSpec& m, const std::vector<TrussDescription>& trusses,
                     const MemberDefaults& defaults) {
  const YamlField tf = f.at("truss");
  m.truss = tf.text();
  const auto type = std::find_if(trusses.begin(), trusses.end(), [&](const TrussDescription& d) { return d.name == m.truss; });
  if (type == trusses.end()) {
    std::string known;
    for (const TrussDescription& d : trusses) known += (known.empty() ? "" : ", ") + d.name;
    tf.fail(fmt::format("unknown truss type '{}' (types under trusses: {})", m.truss, known.empty() ? "none" : known));
  }
  if (const auto fidelity = f.find("fidelity")) {
    m.fidelity = readFidelity(*fidelity);
  } else if (defaults.truss_fidelity) {
    m.fidelity = *defaults.truss_fidelity;
    m.fidelity_by_default = true;
  } else {
    f.fail("missing field 'fidelity': give the section its fidelity, or the scene's defaults.truss_fidelity");
  }
  if (const auto e = f.find("element")) {
    if (m.fidelity != TrussFidelity::Members) e->fail("'element' chooses the tubes' beam element of fidelity 'members' only");
    e->choice({"timoshenko"});
  }
  if (m.fidelity != TrussFidelity::Members && m.fidelity != TrussFidelity::Beam && f.has("segments"))
    f.at("segments").fail("'segments' splits the tubes of fidelity 'members' or the beam of fidelity 'beam' only");
}

/// A member's `start` or `end`: coordinates, or a joint's name (placed by placeMemberEnds).
void readMemberEnd(const YamlField& f, Vec3& position, std::string& joint, SourceLocation& where) {
  where = f.where();
  if (f.isScalar()) joint = f.text();
  else position = f.position();
}

/// A drive's or a rope length's profile: any but a step table or a first-order value input,
/// whose jumps would have to move a joint or reel a rope in no time (a load's `scale` may step).
Profile readDrive(const YamlField& f) {
  Profile p = readProfile(f);
  if (p.jumps())
    f.at("interpolation").fail("a drive or a rope length cannot jump (it would move a joint or reel a rope in no "
                               "time): use interpolation: linear or cubic");
  if (const InputProfile* input = p.input(); input && input->spec.command == InputCommand::Value && input->spec.order == 1)
    f.fail("a drive or a rope length that follows value commands needs order: 2 (through one lag its speed would jump "
           "at every command); or command its speed");
  return p;
}

/// A massless rope reeved over sheaves (`element: reeved`): its path, section, material,
/// length and damping; no start, end or segments.
MemberSpec readReevedRope(const YamlField& f, MemberSpec& m) {
  std::vector<const char*> keys = {"name", "type", "element", "section", "material", "length", "damping", "breaking_force"};
  keys.insert(keys.end(), std::begin(kReevingKeys), std::end(kReevingKeys));
  f.allowKeys(keys);
  m.rope_element = RopeElement::Reeved;
  m.reeving = readReeving(f);
  double poisson = 0.3;
  m.material = readMaterial(f.at("material"), poisson);
  m.section = readSection(f.at("section"), poisson);
  if (const auto d = f.find("damping")) m.damping = d->nonNegative();
  if (const auto l = f.find("length")) m.length = readDrive(*l);
  if (const auto b = f.find("breaking_force")) m.breaking_force = b->within(1.0, 1e12, "N");
  return m;
}

/// `section: {EA, EI_y, EI_z, GJ, rhoA, rhoI_y, rhoI_z, [GA_y, GA_z], [rhoI_p]}`: a beam's section
/// by its properties per unit length (section.hpp); without GA_y and GA_z the beam is
/// shear-rigid; ρI_p defaults to ρI_y + ρI_z (a section's polar moment).
Section readSectionProperties(const YamlField& f) {
  f.allowKeys({"EA", "GA_y", "GA_z", "EI_y", "EI_z", "GJ", "rhoA", "rhoI_y", "rhoI_z", "rhoI_p"});
  SectionProperties p;
  p.EA = f.at("EA").within(1e-3, 1e15, "N");
  p.EIy = f.at("EI_y").within(1e-9, 1e15, "N·m²");
  p.EIz = f.at("EI_z").within(1e-9, 1e15, "N·m²");
  p.GJ = f.at("GJ").within(1e-9, 1e15, "N·m²");
  if (f.has("GA_y") != f.has("GA_z")) f.at(f.has("GA_y") ? "GA_y" : "GA_z").fail("give GA_y and GA_z together, or neither (shear-rigid)");
  if (f.has("GA_y")) {
    p.GAy = f.at("GA_y").within(1e-3, 1e15, "N");
    p.GAz = f.at("GA_z").within(1e-3, 1e15, "N");
  }
  p.rhoA = f.at("rhoA").within(1e-9, 1e9, "kg/m");
  p.rhoIy = f.at("rhoI_y").within(1e-15, 1e9, "kg·m");
  p.rhoIz = f.at("rhoI_z").within(1e-15, 1e9, "kg·m");
  p.rhoIp = f.has("rhoI_p") ? f.at("rhoI_p").within(1e-15, 1e9, "kg·m") : p.rhoIy + p.rhoIz;
  // The rotary inertias about three perpendicular axes of any body satisfy the triangle
  // inequalities (a plane section: ρI_p = ρI_y + ρI_z exactly).
  const double slack = 1e-12 * (p.rhoIp + p.rhoIy + p.rhoIz);
  if (p.rhoIp > p.rhoIy + p.rhoIz + slack || p.rhoIy > p.rhoIp + p.rhoIz + slack || p.rhoIz > p.rhoIp + p.rhoIy + slack)
    f.fail(fmt::format("rotary inertias ρI_p = {}, ρI_y = {}, ρI_z = {} kg·m violate the triangle inequality (each at "
                       "most the sum of the other two)", p.rhoIp, p.rhoIy, p.rhoIz));
  Section s;
  s.given = p;
  return s;
}

MemberSpec readMember(const YamlField& f, const std::vector<TrussDescription>& trusses, const MemberDefaults& defaults) {
  MemberSpec m;
  m.where = f.where();
  m.name = f.at("name").identifier();
  if (m.name == "ground") f.at("name").fail("'ground' is reserved for the inertial frame");
  const std::string type = f.at("type").choice({"strut_tie", "timoshenko", "spline_beam", "rope", "truss"});
  m.type = type == "strut_tie" ? MemberType::StrutTie
           : type == "timoshenko" ? MemberType::Timoshenko
           : type == "spline_beam" ? MemberType::SplineBeam
           : type == "rope"        ? MemberType::Rope
                                   : MemberType::Truss;
  if (m.type == MemberType::Rope)
    if (const auto e = f.find("element"); e && e->choice({"spline", "cable", "reeved"}) == "reeved")
      return readReevedRope(f, m);
  std::vector<const char*> keys = {"name", "type", "start", "end", "z_axis", "segments", "quadrature", "damping"};
  if (m.type == MemberType::Truss) keys.insert(keys.end(), {"truss", "fidelity", "element"});
  else keys.insert(keys.end(), {"section", "material"});
  if (m.type == MemberType::Rope) keys.insert(keys.end(), {"length", "transverse_damping", "element", "breaking_force"});
  if (m.type == MemberType::StrutTie) keys.insert(keys.end(), {"constant_volume", "smoothing"});
  if (m.type == MemberType::Timoshenko) keys.push_back("arc");
  f.allowKeys(keys);
  readMemberEnd(f.at("start"), m.start, m.start_joint, m.where_start);
  readMemberEnd(f.at("end"), m.end, m.end_joint, m.where_end);
  m.z_axis = f.vec3("z_axis", Vec3::UnitZ());
  if (const auto arc = f.find("arc")) {
    if (f.has("z_axis")) f.at("z_axis").fail("an arc's sections turn their z axis to the arc's axis; give no z_axis");
    arc->allowKeys({"centre", "axis"});
    ArcSpec a;
    a.where = arc->where();
    a.centre = arc->at("centre").vec3();
    if (arc->has("axis")) {
      a.axis = arc->at("axis").vec3();
      if (!(a.axis.norm() > 0.0)) arc->at("axis").fail("the arc's axis must not be zero");
    }
    m.arc = a;
  }
  if (f.has("segments")) {
    m.segments = f.at("segments").integer();
    if (m.segments < 1 || m.segments > 10000) f.at("segments").fail(fmt::format("must be 1…10000, found {}", m.segments));
  }
  if (f.has("quadrature")) {
    m.quadrature = f.at("quadrature").integer();
    if (m.quadrature < 1 || m.quadrature > kMaxGaussPoints)
      f.at("quadrature").fail(fmt::format("Gauss points must be 1…{}, found {}", kMaxGaussPoints, m.quadrature));
  }
  if (const auto d = f.find("damping")) m.damping = d->nonNegative();
  if (const auto b = f.find("breaking_force")) m.breaking_force = b->within(1.0, 1e12, "N");
  if (m.type == MemberType::Rope)
    if (const auto e = f.find("element"))
      m.rope_element = e->choice({"spline", "cable"}) == "cable" ? RopeElement::Cable : RopeElement::Spline;
  if (m.rope_element == RopeElement::Cable && f.has("quadrature"))
    f.at("quadrature").fail("a cable (element: cable) is integrated exactly: it takes no quadrature");
  if (const auto c = f.find("transverse_damping")) {
    if (m.rope_element == RopeElement::Cable)
      c->fail("a cable (element: cable) is straight: it has no sideways vibration to damp");
    m.transverse_damping = c->nonNegative();
    // It damps the turning of the centre line against each element's chord: on one element,
    // the rope's sideways vibration; on several, only what bends within each element, a
    // damping that would depend on the segments.
    if (m.transverse_damping > 0.0 && m.segments != 1)
      c->fail(fmt::format("transverse damping acts on a rope of one segment (this one has {}): it damps the turning "
                          "of the centre line against the element's chord, which on several segments would depend on "
                          "their number", m.segments));
  }
  if (m.type == MemberType::Truss) {
    readTrussMember(f, m, trusses, defaults);
    return m;
  }
  const YamlField section = f.at("section");
  if (section.isMap() && section.has("EA")) {
    if (m.type != MemberType::Timoshenko && m.type != MemberType::SplineBeam)
      section.fail(fmt::format("a section given by its properties (EA, EI, ρA …) is for timoshenko and spline_beam "
                               "members; give this {}'s section by its shape and material", type));
    if (f.has("material")) f.at("material").fail("a section given by its properties (EA, EI, ρA …) takes no material");
    m.section = readSectionProperties(section);
  } else {
    double poisson = 0.3;
    m.material = readMaterial(f.at("material"), poisson);
    m.section = readSection(section, poisson);
  }
  if (const auto l = f.find("length")) m.length = readDrive(*l);
  if (const auto cv = f.find("constant_volume")) m.constant_volume = cv->boolean();
  if (const auto h = f.find("smoothing")) m.smoothing = h->nonNegative();
  return m;
}

int readAxis(const YamlField& f) {
  const std::string a = f.choice({"x", "y", "z"});
  return a[0] - 'x';
}

ConstraintSpec readConstraint(const YamlField& f) {
  ConstraintSpec c;
  c.where = f.where();
  c.name = f.at("name").identifier();
  const std::string type = f.at("type").choice({"fixed", "revolute", "prismatic", "spherical", "distance"});
  const auto joints = f.at("joints");
  const auto items = joints.items();
  if (items.size() != 2) joints.fail(fmt::format("a constraint connects exactly 2 joints, found {}", items.size()));
  c.joint1 = items[0].text();
  c.joint2 = items[1].text();
  c.where_joint1 = items[0].where();
  c.where_joint2 = items[1].where();
  if (type == "fixed") {
    f.allowKeys({"name", "type", "joints", "pose"});
    c.type = ConstraintType::Fixed;
    if (const auto pose = f.find("pose")) {
      c.keep_drawn_pose = pose->choice({"joints", "drawn"}) == "drawn";
      c.where_pose = pose->where();
    }
  } else if (type == "spherical") {
    f.allowKeys({"name", "type", "joints"});
    c.type = ConstraintType::Spherical;
  } else if (type == "distance") {
    f.allowKeys({"name", "type", "joints", "length"});
    c.type = ConstraintType::Distance;
    c.drive = readDrive(f.at("length"));
    if (!((*c.drive)(0.0) > 0.0)) f.at("length").fail("a distance must be positive");
  } else {
    f.allowKeys({"name", "type", "joints", "axis", "drive"});
    c.type = type == "revolute" ? ConstraintType::Revolute : ConstraintType::Prismatic;
    c.axis = readAxis(f.at("axis"));
    if (const auto d = f.find("drive")) c.drive = readDrive(*d);
  }
  return c;
}

LoadSpec readLoad(const YamlField& f) {
  f.allowKeys({"name", "joint", "force", "torque", "frame", "scale"});
  LoadSpec l;
  l.where = f.where();
  l.name = f.at("name").identifier();
  l.joint = f.at("joint").text();
  l.where_joint = f.at("joint").where();
  l.force = f.vec3("force", Vec3::Zero());
  l.torque = f.vec3("torque", Vec3::Zero());
  if (const auto fr = f.find("frame")) l.frame = fr->choice({"inertial", "joint"}) == "joint" ? LoadFrame::Joint : LoadFrame::Inertial;
  if (const auto s = f.find("scale")) l.scale = readProfile(*s);
  return l;
}

/// `output.section_forces`: names of members made of beams, or of ropes (their tensions).
std::vector<std::string> readSectionForceMembers(const YamlField& f, const std::vector<MemberSpec>& members) {
  const auto hasBeams = [](const MemberSpec& m) {
    return m.type == MemberType::Timoshenko || (m.type == MemberType::Rope && !m.reeving) ||
           (m.type == MemberType::Truss && (m.fidelity == TrussFidelity::Members || m.fidelity == TrussFidelity::Beam));
  };
  std::string eligible;
  for (const MemberSpec& m : members)
    if (hasBeams(m)) eligible += (eligible.empty() ? "" : ", ") + m.name;
  std::vector<std::string> names;
  for (const YamlField& item : f.items()) {
    const std::string name = item.text();
    const auto m = std::find_if(members.begin(), members.end(), [&](const MemberSpec& spec) { return spec.name == name; });
    if (m == members.end() || !hasBeams(*m))
      item.fail(fmt::format("{} '{}': section forces are recorded for timoshenko members, ropes (not reeved) and trusses "
                            "of fidelity members or beam (here: {})", m == members.end() ? "no member" : "no beams in member", name,
                            eligible.empty() ? "none" : eligible));
    if (std::find(names.begin(), names.end(), name) != names.end()) item.fail(fmt::format("'{}' is listed twice", name));
    names.push_back(name);
  }
  return names;
}

/// `output.constraint_loads`: names of constraints.
std::vector<std::string> readConstraintLoadNames(const YamlField& f, const std::vector<ConstraintSpec>& constraints) {
  std::vector<std::string> names;
  for (const YamlField& item : f.items()) {
    const std::string name = item.text();
    if (std::none_of(constraints.begin(), constraints.end(), [&](const ConstraintSpec& c) { return c.name == name; }))
      item.fail(fmt::format("no constraint '{}' (here: {})", name, listedNames(namesOf(constraints))));
    if (std::find(names.begin(), names.end(), name) != names.end()) item.fail(fmt::format("'{}' is listed twice", name));
    names.push_back(name);
  }
  return names;
}

/// `output.tipping_lines`: [{name, supports: [constraints between the ground and the structure],
/// line: [[x, y, z], [x, y, z]]}].
std::vector<TippingLineSpec> readTippingLines(const YamlField& f, const std::vector<ConstraintSpec>& constraints) {
  std::vector<TippingLineSpec> lines;
  const auto onGround = [](const std::string& joint) { return joint.rfind("ground.", 0) == 0; };
  for (const YamlField& item : f.items()) {
    item.allowKeys({"name", "supports", "line"});
    TippingLineSpec line;
    line.name = item.at("name").identifier();
    if (std::any_of(lines.begin(), lines.end(), [&](const TippingLineSpec& l) { return l.name == line.name; }))
      item.at("name").fail(fmt::format("duplicate tipping line name '{}'", line.name));
    const YamlField supports = item.at("supports");
    for (const YamlField& s : supports.items()) {
      const std::string name = s.text();
      const auto c = std::find_if(constraints.begin(), constraints.end(), [&](const ConstraintSpec& k) { return k.name == name; });
      if (c == constraints.end()) s.fail(fmt::format("no constraint '{}'", name));
      if (onGround(c->joint1) == onGround(c->joint2))
        s.fail(fmt::format("constraint '{}' does not join the structure to the ground", name));
      if (std::find(line.supports.begin(), line.supports.end(), name) != line.supports.end())
        s.fail(fmt::format("'{}' is listed twice", name));
      line.supports.push_back(name);
    }
    if (line.supports.empty()) supports.fail("name at least one constraint that holds the structure on the ground");
    const std::array<Vec3, 2> points = item.at("line").tippingLine();
    line.from = points[0];
    line.to = points[1];
    lines.push_back(std::move(line));
  }
  return lines;
}

/// The scene's inputs (rope lengths, drives, load scales of `type: input`) and whether each
/// takes speed commands.
std::map<std::string, bool> sceneInputs(const Scene& s) {
  std::map<std::string, bool> inputs;
  const auto add = [&](const std::string& name, const Profile& p) {
    if (p.input()) inputs[name] = p.input()->spec.command == InputCommand::Speed;
  };
  for (const MemberSpec& m : s.members)
    if (m.length) add(m.name, *m.length);
  for (const ConstraintSpec& c : s.constraints)
    if (c.drive) add(c.name, *c.drive);
  for (const LoadSpec& l : s.loads) add(l.name, l.scale);
  return inputs;
}

/// `feedback: {type: anti_sway, sample_time, start, slewing, luffing_rope, hoist_rope, hook,
/// sheave, shaping, steady_angle_time, sensor, references: {input: profile}}`, its inputs checked against the scene's.
FeedbackSpec readFeedback(const YamlField& f, const Scene& s) {
  f.allowKeys({"type", "sample_time", "start", "slewing", "luffing_rope", "hoist_rope", "hook", "sheave", "shaping",
               "steady_angle_time", "sensor", "references"});
  f.at("type").choice({"anti_sway"});
  FeedbackSpec spec;
  spec.where = f.where();
  if (const auto h = f.find("sample_time")) spec.sample_time = h->within(1e-4, 10.0, "s");
  if (const auto t = f.find("start")) spec.start = t->nonNegative();
  const std::map<std::string, bool> inputs = sceneInputs(s);
  std::vector<std::string> names;
  for (const auto& [name, speed] : inputs) names.push_back(name);
  // `name`, an input of the scene that takes speed commands; errors at `field`.
  const auto speedInput = [&](const std::string& name, const YamlField& field) {
    const auto it = inputs.find(name);
    if (it == inputs.end()) field.fail(unknownName("input", name, names));
    if (!it->second) field.fail(fmt::format("input '{}' takes value commands; the feedback commands speeds", name));
  };
  // Each role's input: named under its key, or the input of the role's name.
  for (const auto& [key, name] : {std::pair<const char*, std::string*>{"slewing", &spec.slewing},
                                  {"luffing_rope", &spec.luffing_rope}, {"hoist_rope", &spec.hoist_rope}}) {
    const std::optional<YamlField> named = f.find(key);
    if (named) *name = named->text();
    speedInput(*name, named ? *named : f);
  }
  if (const auto x = f.find("hook")) spec.hook = x->text();
  if (const auto x = f.find("sheave")) spec.sheave = x->text();
  if (const auto shaping = f.find("shaping")) {
    shaping->allowKeys({"period", "boom_period"});
    spec.shaping_period = shaping->at("period").within(0.1, 1000.0, "s");
    if (const auto b = shaping->find("boom_period")) spec.boom_period = b->within(0.01, 100.0, "s");
  }
  if (const auto x = f.find("steady_angle_time")) spec.steady_angle_time = x->within(0.1, 1e4, "s");
  if (const auto x = f.find("sensor")) spec.sensor = readSwaySensor(*x);
  if (const auto refs = f.find("references"))
    for (const std::string& name : refs->keys()) {
      const YamlField reference = refs->at(name);
      speedInput(name, reference);
      if (reference.isMap() && (reference.has("unit") || (reference.has("type") && reference.at("type").text() == "input")))
        reference.fail("a reference is a speed in its input's unit per second: no 'unit', no 'type: input'");
      spec.references.emplace(name, readProfile(reference));
    }
  return spec;
}

/// The figures a boom's equilibrium is to meet, with the way to draw the scene otherwise: the
/// composed scene read again with the angle and the hoist rope's length it searches in place of
/// `from_equilibrium`.
StatedEquilibrium statedEquilibrium(StatedEquilibrium stated, const ComposedScene& composed, const Scene& scene) {
  const std::string boom_foot = stated.boom + "_foot";
  const SourceLocation& where = stated.angle_figure ? stated.angle_figure->where : stated.hook_height->where;
  if (!scene.crane)
    throw SceneError(where, "a stated equilibrium is measured on the crane: give the scene a crane: block (its "
                            "slewing, boom_foot, boom_head and hook)");
  if (scene.crane->boom_foot != boom_foot)
    throw SceneError(where, fmt::format("the crane: block measures the boom whose foot is '{}': state the "
                                        "equilibrium of that boom, not of '{}' (foot '{}')",
                                        scene.crane->boom_foot, stated.boom, boom_foot));
  const YAML::Node root = YAML::Clone(composed.root);
  stated.drawn_at = [root, text = composed.text, path = scene.path, boom = stated.boom, angle = stated.angle_figure.has_value(),
                     length = stated.hook_height.has_value()](const BoomDrawing& drawing) {
    const YAML::Node redrawn = YAML::Clone(root);
    for (YAML::Node b : redrawn["booms"])
      if (b["name"].as<std::string>() == boom) {
        if (angle) b["angle_deg"] = fmt::format("{:.17g}", drawing.angle_deg);
        if (length) b["hoist"]["hanging_length"] = fmt::format("{:.17g}", drawing.hanging_length);
        b.remove("equilibrium");
      }
    return sceneFromComposed({redrawn, text}, path);
  };
  return stated;
}

}  // namespace

Scene sceneFromComposed(const ComposedScene& composed, const std::string& path) {
  const ExpandedBooms expanded = expandBooms(composed.root);
  const YAML::Node& root = expanded.root;
  const YamlField f(root, "");
  if (!root.IsMap()) throw SceneError({"<document>", 1, 1}, "a scene must be a YAML mapping");
  f.allowKeys({"name", "gravity", "ground", "bodies", "trusses", "members", "constraints", "loads", "wind", "solver",
               "output", "feedback", "crane", "defaults", "booms"});
  Scene s;
  s.path = path;
  s.text = composed.text;
  s.name = f.has("name") ? f.at("name").text() : path;
  s.gravity = f.vec3("gravity", s.gravity);
  if (const auto g = f.find("ground")) {
    g->allowKeys({"joints", "surface", "supports"});
    if (g->has("joints")) s.ground_joints = readJoints(g->at("joints"));
  }
  std::set<std::string> body_names;
  if (const auto bodies = f.find("bodies"))
    for (const YamlField& b : bodies->items()) {
      s.bodies.push_back(readBody(b));
      if (!body_names.insert(s.bodies.back().name).second)
        b.at("name").fail(fmt::format("duplicate body or member name '{}'", s.bodies.back().name));
    }
  if (const auto trusses = f.find("trusses"))
    for (const YamlField& t : trusses->items()) {
      s.trusses.push_back(readTruss(t));
      buildTrussGeometry(s.trusses.back());  // validates the type even when no member uses it
      for (std::size_t i = 0; i + 1 < s.trusses.size(); ++i)
        if (s.trusses[i].name == s.trusses.back().name) t.at("name").fail(fmt::format("duplicate truss type name '{}'", s.trusses.back().name));
    }
  const MemberDefaults defaults = f.has("defaults") ? readDefaults(f.at("defaults")) : MemberDefaults{};
  if (const auto members = f.find("members"))
    for (const YamlField& m : members->items()) {
      s.members.push_back(readMember(m, s.trusses, defaults));
      if (!body_names.insert(s.members.back().name).second)
        m.at("name").fail(fmt::format("duplicate body or member name '{}'", s.members.back().name));
    }
  if (s.bodies.empty() && s.members.empty()) f.fail("a scene needs at least one body or member");
  std::set<std::string> constraint_names;
  if (const auto cs = f.find("constraints"))
    for (const YamlField& c : cs->items()) {
      s.constraints.push_back(readConstraint(c));
      if (!constraint_names.insert(s.constraints.back().name).second)
        c.at("name").fail(fmt::format("duplicate constraint name '{}'", s.constraints.back().name));
    }
  if (const auto ls = f.find("loads"))
    for (const YamlField& l : ls->items()) s.loads.push_back(readLoad(l));
  if (const auto w = f.find("wind")) s.wind = readWind(*w, s);
  if (const auto g = f.find("ground"); g && g->has("surface")) s.ground_surface = readGroundSurface(g->at("surface"), s);
  if (const auto g = f.find("ground"); g && g->has("supports")) s.ground_supports = readGroundSupports(g->at("supports"), s);
  const YamlField solver = f.at("solver");
  s.solver = readSolver(solver);
  s.where_solver = solver.where();
  if (const auto members = f.find("members")) {
    const std::vector<YamlField> items = members->items();
    for (std::size_t i = 0; i < items.size(); ++i) requireRopeLength(s.members[i], items[i], s.solver);
  }
  placeMemberEnds(s);
  if (const auto o = f.find("output")) {
    o->allowKeys({"interval", "section_forces", "constraint_loads", "tipping_lines"});
    s.output.interval = o->positive("interval", s.output.interval);
    if (o->has("interval")) s.output.where = o->at("interval").where();
    if (const auto sf = o->find("section_forces")) s.output.section_forces = readSectionForceMembers(*sf, s.members);
    if (const auto cl = o->find("constraint_loads")) s.output.constraint_loads = readConstraintLoadNames(*cl, s.constraints);
    if (const auto tl = o->find("tipping_lines")) s.output.tipping_lines = readTippingLines(*tl, s.constraints);
  }
  if (const auto fb = f.find("feedback")) s.feedback = readFeedback(*fb, s);
  if (const auto crane = f.find("crane")) s.crane = readCrane(*crane, s);
  if (expanded.stated) s.stated_equilibrium = statedEquilibrium(*expanded.stated, composed, s);
  return s;
}

Scene parseScene(const std::string& text, const std::string& path) {
  return sceneFromComposed(composeScene(text, path, [](const ComposedScene& base, const std::string& base_path) { sceneFromComposed(base, base_path); }), path);
}

Scene readScene(const std::string& path) {
  return parseScene(readInputFile(path, "scene file", {}), path);
}

}  // namespace cranesim
