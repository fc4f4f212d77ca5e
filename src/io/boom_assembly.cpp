#include "boom_assembly.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "cranesim/math/units.hpp"
#include "cranesim/model/closest_name.hpp"
#include "cranesim/model/source_location.hpp"
#include "profile_reader.hpp"
#include "rotation_reader.hpp"
#include "yaml_field.hpp"

namespace cranesim {
namespace {

const Vec3 kUp = Vec3::UnitZ();

/// A joint's drawn pose: its origin and its axes (columns) in the scene's frame.
struct Frame {
  Vec3 origin = Vec3::Zero();
  Mat3 axes = Mat3::Identity();
};

YAML::Node number(double value) { return YAML::Node(fmt::format("{:.17g}", value)); }

YAML::Node point(const Vec3& p) {
  YAML::Node n(YAML::NodeType::Sequence);
  for (int i = 0; i < 3; ++i) n.push_back(number(p(i)));
  return n;
}

YAML::Node rotationMatrix(const Mat3& R) {
  YAML::Node rows(YAML::NodeType::Sequence);
  for (int r = 0; r < 3; ++r) rows.push_back(point(R.row(r).transpose()));
  YAML::Node rotation(YAML::NodeType::Map);
  rotation["matrix"] = rows;
  return rotation;
}

/// A new mapping sharing the values of `map` but for the keys `except`, which the caller sets:
/// assigning a scalar to a shared value would change the scene's own node.
YAML::Node copyExcept(const YAML::Node& map, const std::set<std::string>& except) {
  YAML::Node copy(YAML::NodeType::Map);
  for (const auto& kv : map)
    if (!except.count(kv.first.as<std::string>())) copy[kv.first] = kv.second;
  return copy;
}

YAML::Node joints(const std::string& first, const std::string& second) {
  YAML::Node pair(YAML::NodeType::Sequence);
  pair.push_back(first);
  pair.push_back(second);
  return pair;
}

/// A truss type under `trusses:` as a boom places it: its length in whole bays.
struct TrussType {
  std::string name;
  double length = 0.0;
  int bays = 0;
  YAML::Node node;
};

/// A joint's pose from its `position` and `rotation` within the frame of its part.
Frame jointIn(const Frame& part, const YamlField& joint) {
  Frame j;
  j.origin = part.origin + part.axes * joint.position("position", Vec3::Zero());
  j.axes = part.axes;
  if (const auto r = joint.find("rotation")) j.axes = part.axes * readRotation(*r);
  return j;
}

/// The joint named `name` in the list `joints` of a part whose frame is `part`.
std::optional<Frame> namedJoint(const Frame& part, const std::optional<YamlField>& joints, const std::string& name) {
  if (name == "origin") return part;
  if (joints)
    for (const YamlField& j : joints->items())
      if (j.has("name") && j.at("name").text() == name) return jointIn(part, j);
  return std::nullopt;
}

class BoomAssembler {
 public:
  explicit BoomAssembler(const YAML::Node& root) : root_(root) {
    const YamlField scene(root, "");
    if (const auto trusses = scene.find("trusses"))
      for (const YamlField& t : trusses->items())
        if (t.has("name") && t.has("length") && t.has("order"))
          types_.push_back({t.at("name").text(), t.at("length").positive(), t.at("order").integer(), t.node()});
    if (const auto constraints = scene.find("constraints"))
      for (const YamlField& c : constraints->items())
        if (c.has("name")) constraint_names_.insert(c.at("name").text());
    if (const auto defaults = scene.find("defaults")) has_default_fidelity_ = defaults->has("truss_fidelity");
  }

  void assemble(const YamlField& boom) {
    boom.allowKeys({"name", "foot", "pin", "towards", "angle_deg", "equilibrium", "fidelity", "damping", "sections", "head",
                    "luffing", "hoist"});
    const std::string name = boom.at("name").identifier();
    const YamlField sections = boom.at("sections");
    const std::vector<YamlField> items = sections.items();
    if (items.empty()) sections.fail(fmt::format("boom '{}' needs at least one section (foot, inserts, top)", name));
    std::vector<std::pair<YAML::Node, double>> types;  // each section's truss type and length
    double boom_length = 0.0;
    for (const YamlField& section : items) {
      section.allowKeys({"name", "truss", "length", "fidelity"});
      section.at("name").identifier();
      types.push_back(sectionType(section));
      boom_length += types.back().second;
    }
    const Frame axes = boomAxes(boom, boomAngle(boom, boom_length));
    double along = 0.0;
    std::string previous;
    for (std::size_t k = 0; k < items.size(); ++k) {
      const YamlField& section = items[k];
      const std::string section_name = section.at("name").text();
      const auto& [type, length] = types[k];
      YAML::Node member(YAML::NodeType::Map);
      member["name"] = section.at("name").node();
      member["type"] = "truss";
      member["truss"] = type;
      if (const auto fidelity = sectionFidelity(boom, section)) member["fidelity"] = *fidelity;
      if (const auto damping = boom.find("damping")) member["damping"] = damping->node();
      Frame start = axes, end = axes;
      start.origin += along * axes.axes.col(0);
      along += length;
      end.origin += along * axes.axes.col(0);
      sections_[section_name] = {start, end};
      member["start"] = point(start.origin);
      member["end"] = point(end.origin);
      member["z_axis"] = point(axes.axes.col(2));
      members_.push_back(member);
      if (k == 0) {
        YAML::Node pin = addConstraint(boom.at("foot"), name + "_foot", "revolute", boom.at("foot").text(), section_name + ".start");
        pin["axis"] = pinAxis(boom);
      } else {
        addConstraint(section, fmt::format("{}_splice{}", name, k), "fixed", previous + ".end", section_name + ".start");
      }
      previous = section_name;
    }
    const std::optional<YamlField> head = boom.find("head");
    if (head) {
      placeHead(*head, sections_.at(previous)[1]);
      addConstraint(*head, name + "_head", "fixed", head->at("name").text() + ".origin", previous + ".end");
    }
    for (const char* rigging : {"luffing", "hoist"})
      if (boom.has(rigging) && !head)
        boom.at(rigging).fail(fmt::format("the {} hangs from the boom's head: give boom '{}' a head", rigging, name));
    if (const auto luffing = boom.find("luffing")) rigLuffingLine(*luffing, *head);
    if (const auto hoist = boom.find("hoist")) rigHoist(*hoist, *head, statesFor(boom));
    else if (statesFor(boom) && stated_->hook_height)
      throw SceneError(stated_->hook_height->where, "a stated hook height sizes the boom's hoist rope: give the boom a hoist");
  }

  /// `root` with the assembled items: members and constraints before the scene's own, heads and
  /// truss types after them, the hung loads in their bodies' places.
  YAML::Node expanded() const {
    YAML::Node out(YAML::NodeType::Map);
    for (const auto& kv : root_) out[kv.first] = kv.second;
    const auto join = [&](const char* key, const YAML::Node& first, const YAML::Node& second) {
      if (root_[key] && !root_[key].IsSequence()) return;  // the scene reader reports it
      YAML::Node list(YAML::NodeType::Sequence);
      for (const YAML::Node& item : first) list.push_back(item);
      for (const YAML::Node& item : second) list.push_back(item);
      if (list.size() > 0) out[key] = list;
    };
    const YAML::Node none;
    join("trusses", root_["trusses"] ? root_["trusses"] : none, trusses_);
    join("members", members_, root_["members"] ? root_["members"] : none);
    YAML::Node bodies(YAML::NodeType::Sequence);
    if (root_["bodies"] && root_["bodies"].IsSequence())
      for (const YAML::Node& body : root_["bodies"]) {
        const auto hung = body["name"] ? hung_bodies_.find(body["name"].as<std::string>()) : hung_bodies_.end();
        bodies.push_back(hung == hung_bodies_.end() ? body : hung->second);
      }
    join("bodies", bodies, bodies_);
    join("constraints", constraints_, root_["constraints"] ? root_["constraints"] : none);
    return out;
  }

  /// The figure a boom's equilibrium is to meet (angle_deg: from_equilibrium), if one states it.
  const std::optional<StatedEquilibrium>& stated() const { return stated_; }

 private:
  /// The boom's frame at its foot at the boom angle `angle` (deg) above the horizontal
  /// `towards`: x along the boom axis, y the foot pin, z = x × y (the sections' z axis).
  Frame boomAxes(const YamlField& boom, double angle) const {
    const Frame pin_frame = jointFrame(boom.at("foot"), "the foot");
    const YamlField towards_field = boom.at("towards");
    Vec3 towards = towards_field.vec3();
    if (towards.norm() < 1e-12 || std::abs(towards.dot(kUp)) > 1e-9 * towards.norm())
      towards_field.fail("'towards' is the horizontal direction the boom leans to: a vector [x, y, 0], not zero");
    towards.normalize();
    const Vec3 pin = pin_frame.axes.col(pinIndex(boom));
    if (std::abs(pin.dot(kUp)) > 1e-9 || std::abs(pin.dot(towards)) > 1e-9)
      boom.at(boom.has("pin") ? "pin" : "foot")
          .fail(fmt::format("the foot joint's {} axis is drawn along [{:.6g}, {:.6g}, {:.6g}]: a boom turns about a "
                            "horizontal pin across 'towards' (turn the foot joint, or choose its axis with 'pin')",
                            pinAxis(boom), pin.x(), pin.y(), pin.z()));
    Frame axes;
    axes.origin = pin_frame.origin;
    axes.axes.col(0) = std::cos(angle * kRadiansPerDegree) * towards + std::sin(angle * kRadiansPerDegree) * kUp;
    axes.axes.col(1) = pin.normalized();
    axes.axes.col(2) = axes.axes.col(0).cross(axes.axes.col(1));
    return axes;
  }

  /// `angle_deg`: the boom angle in degrees, `from_luffing_rope`: the angle at which the
  /// luffing line closes with a rope of `luffing.rope_length` (the boom `boom_length` long), or
  /// `from_equilibrium`: a first angle for the figure `equilibrium` states.
  double boomAngle(const YamlField& boom, double boom_length) {
    const YamlField field = boom.at("angle_deg");
    const bool from_equilibrium = field.isScalar() && field.text() == "from_equilibrium";
    if (const auto equilibrium = boom.find("equilibrium")) stateEquilibrium(boom, *equilibrium);
    const bool angle_stated = statesFor(boom) && stated_->angle_figure;
    if (from_equilibrium && !angle_stated)
      field.fail("'from_equilibrium' draws the boom where its equilibrium meets a stated figure: give the boom "
                 "equilibrium: {hook_radius: <m>} or {boom_angle_deg: <deg>}");
    if (angle_stated && !from_equilibrium)
      boom.at("equilibrium").fail("a stated equilibrium sets the boom angle: with a hook_radius or boom_angle_deg give "
                                  "angle_deg: from_equilibrium, or state neither");
    if (from_equilibrium) {
      stated_->drawn.angle_deg = stated_->figure == StatedEquilibrium::Figure::BoomAngle
                                     ? stated_->angle_figure->value
                                     : angleHangingHookAt(boom, boom.at("equilibrium").at("hook_radius"),
                                                          stated_->angle_figure->value, boom_length);
      return stated_->drawn.angle_deg;
    }
    const std::optional<YamlField> luffing = boom.find("luffing");
    const bool from_rope = field.isScalar() && field.text() == "from_luffing_rope";
    if (luffing && luffing->has("rope_length") != from_rope)
      (from_rope ? *luffing : luffing->at("rope_length"))
          .fail("a luffing rope_length sets the boom angle: give both it and angle_deg: from_luffing_rope, or neither");
    if (from_rope) {
      if (!luffing || !boom.has("head")) field.fail("'from_luffing_rope' needs the boom's head and luffing line");
      return angleFromLuffingRope(boom, *luffing, boom_length);
    }
    const double angle = field.number();
    if (!(angle > -90.0 && angle <= 90.0))
      field.fail(fmt::format("a boom angle lies in (−90°, 90°] above the horizontal 'towards', found {}°", angle));
    return angle;
  }

  /// Whether `boom` is the boom whose equilibrium the scene states.
  bool statesFor(const YamlField& boom) const { return stated_ && stated_->boom == boom.at("name").text(); }

  /// `equilibrium: {hook_radius: R}` (m, from the slewing axis) or `{boom_angle_deg: A}`, and/or
  /// `{hook_height: H}` (m): the figures the boom's equilibrium is to meet, recorded for the
  /// search (one boom per scene). The first drawing is left to boomAngle and rigHoist.
  void stateEquilibrium(const YamlField& boom, const YamlField& field) {
    if (!field.isMap() || field.keys().empty())
      field.fail("expected the stated figures: {hook_radius: <m>} or {boom_angle_deg: <deg>}, and {hook_height: <m>}");
    field.allowKeys({"hook_radius", "boom_angle_deg", "hook_height"});
    if (field.has("hook_radius") && field.has("boom_angle_deg"))
      field.at("boom_angle_deg").fail("one figure sets the boom angle: a hook_radius or a boom_angle_deg, not both");
    if (stated_) field.fail(fmt::format("boom '{}' states its equilibrium already: one boom per scene may", stated_->boom));
    StatedEquilibrium stated;
    stated.boom = boom.at("name").text();
    if (const auto angle = field.find("boom_angle_deg")) {
      stated.figure = StatedEquilibrium::Figure::BoomAngle;
      stated.angle_figure = {angle->within(0.5, 89.5, "°"), angle->where()};
    } else if (const auto radius = field.find("hook_radius")) {
      stated.figure = StatedEquilibrium::Figure::HookRadius;
      stated.angle_figure = {radius->positive(), radius->where()};
    }
    if (const auto height = field.find("hook_height")) stated.hook_height = {height->number(), height->where()};
    stated_ = stated;
  }

  /// The boom angle in [0°, 89.5°] at which the hoist's sheave, on the boom drawn rigid, stands
  /// `radius` m horizontally from the boom's foot (bisection: the reach falls as the boom rises).
  double angleHangingHookAt(const YamlField& boom, const YamlField& field, double radius, double boom_length) const {
    const std::optional<YamlField> hoist = boom.find("hoist");
    if (!hoist || !boom.has("head")) field.fail("a stated hook radius needs the boom's head and hoist");
    const std::optional<Frame> sheave = namedJoint(Frame{}, boom.at("head").find("joints"), hoist->at("sheave").text());
    if (!sheave) hoist->at("sheave").fail(fmt::format("the head has no joint '{}'", hoist->at("sheave").text()));
    const Vec3 in_boom = boom_length * Vec3::UnitX() + sheave->origin;
    const auto reach = [&](double angle) {
      const Frame axes = boomAxes(boom, angle);
      const Vec3 offset = axes.axes * in_boom;
      return (offset - offset.dot(kUp) * kUp).norm();
    };
    double low = 0.0, high = 89.5;
    if (radius > reach(low) || radius < reach(high))
      field.fail(fmt::format("the boom reaches {:.6g} … {:.6g} m from its foot between 0° and 89.5°: no angle hangs the "
                             "hook at {:g} m", reach(high), reach(low), radius));
    for (int k = 0; k < 60; ++k) {
      const double mid = 0.5 * (low + high);
      (reach(mid) > radius ? low : high) = mid;
    }
    return 0.5 * (low + high);
  }

  /// A rope length: a number, or a profile (a reeling drive) drawn at its value at solver.t_start.
  double lengthAtStart(const YamlField& field) const {
    if (!field.isMap()) return field.positive();
    const std::optional<YamlField> solver = YamlField(root_, "").find("solver");
    const double t_start = solver ? solver->number("t_start", 0.0) : 0.0;
    const double length = readProfile(field)(t_start, Limit::Right);
    if (!(length > 0.0)) field.fail(fmt::format("the rope's length is {:g} m at t_start = {:g} s: it must be positive", length, t_start));
    return length;
  }

  /// A luffing rope reeved between the anchor and the line's lower end (`element: reeved` in its
  /// falls form): its falls, and its lead line from the winch to the anchor.
  struct LuffingReeving {
    int falls = 1;
    double lead = 0.0;  // m
  };

  /// The reeving of the luffing `rope` whose anchor is drawn at `anchor`, if it is reeved.
  std::optional<LuffingReeving> luffingReeving(const YamlField& rope, const Vec3& anchor) const {
    const std::optional<YamlField> element = rope.isMap() ? rope.find("element") : std::nullopt;
    if (!element || element->text() != "reeved") return std::nullopt;
    if (rope.has("path"))
      rope.at("path").fail("the boom reeves its luffing rope between the anchor and the line's end: give falls, winch "
                           "and the blocks' radii (head: the anchor's, hook: the line's end), not a path");
    for (const char* block : {"head", "hook"})
      if (const auto b = rope.find(block); b && b->isMap() && b->has("joint"))
        b->at("joint").fail("the boom places its luffing rope's blocks: give the block's radius, not its joint");
    const YamlField falls = rope.at("falls");
    if (falls.integer() < 1) falls.fail("at least 1 fall");
    return LuffingReeving{falls.integer(), (anchor - jointFrame(rope.at("winch"), "the luffing winch").origin).norm()};
  }

  /// The steepest boom angle at which the straight luffing line from the head's joint to its
  /// anchor is as long as its ties and a rope of `rope_length`, all drawn unstretched (a reeved
  /// rope: its lead line and falls, each fall spanning the rest of the line).
  double angleFromLuffingRope(const YamlField& boom, const YamlField& luffing, double boom_length) const {
    const YamlField rope_field = luffing.at("rope_length");
    const Vec3 anchor = jointFrame(luffing.at("to"), "the luffing line's anchor").origin;
    double rope = lengthAtStart(rope_field);
    if (const auto reeving = luffingReeving(luffing.at("rope"), anchor)) rope = (rope - reeving->lead) / reeving->falls;
    double reach = 0.0;
    if (const auto ties = luffing.find("ties"))
      for (const YamlField& tie : ties->items()) reach += tie.at("length").positive();
    const YamlField head = boom.at("head");
    const std::optional<Frame> joint = namedJoint(Frame{}, head.find("joints"), luffing.at("from").text());
    if (!joint) luffing.at("from").fail(fmt::format("the head has no joint '{}'", luffing.at("from").text()));
    const Vec3 from = boom_length * Vec3::UnitX() + joint->origin;  // in the boom's frame
    const auto gap = [&](double angle) {
      const Frame axes = boomAxes(boom, angle);
      return (anchor - (axes.origin + axes.axes * from)).norm() - reach - rope;
    };
    constexpr double kStep = 0.25;  // deg: the scan for the steepest sign change
    double high = 90.0, shortest = gap(high), longest = shortest;
    for (double low = high - kStep; low > -90.0; high = low, low -= kStep) {
      const double g_low = gap(low), g_high = gap(high);
      shortest = std::min(shortest, g_low), longest = std::max(longest, g_low);
      if ((g_low > 0.0) == (g_high > 0.0)) continue;
      for (int k = 0; k < 100; ++k) {
        const double mid = 0.5 * (low + high);
        ((gap(mid) > 0.0) == (g_high > 0.0) ? high : low) = mid;
      }
      return 0.5 * (low + high);
    }
    rope_field.fail(fmt::format("no boom angle closes the luffing line with a {:g} m rope: over the boom's angles the "
                                "rope would be {:.6g} … {:.6g} m", rope, rope + shortest, rope + longest));
  }

  std::string pinAxis(const YamlField& boom) const {
    return boom.has("pin") ? boom.at("pin").choice({"x", "y", "z"}) : std::string("y");
  }
  int pinIndex(const YamlField& boom) const { return pinAxis(boom)[0] - 'x'; }

  /// The drawn pose of the joint named at `field` (`role` in messages): a ground joint, a body's
  /// joint, a joint of an earlier boom's head, or an end of an earlier boom's section.
  Frame jointFrame(const YamlField& field, const char* role) const {
    const std::string name = field.text();
    const std::size_t dot = name.find('.');
    if (dot == std::string::npos || dot == 0 || dot + 1 == name.size())
      field.fail(fmt::format("{} '{}' is not a joint '<part>.<joint>'", role, name));
    const std::string part = name.substr(0, dot), joint = name.substr(dot + 1);
    const YamlField scene(root_, "");
    std::optional<Frame> found;
    if (part == "ground") {
      const std::optional<YamlField> ground = scene.find("ground");
      found = namedJoint(Frame{}, ground ? ground->find("joints") : std::nullopt, joint);
    } else if (const auto head = heads_.find(part); head != heads_.end()) {
      found = namedJoint(head->second.frame, YamlField(head->second.node, "").find("joints"), joint);
    } else if (const auto section = sections_.find(part); section != sections_.end()) {
      if (joint == "start" || joint == "end") found = section->second[joint == "start" ? 0 : 1];
    } else if (const std::optional<YamlField> body = findBody(part)) {
      found = namedJoint(bodyFrame(*body), body->find("joints"), joint);
    } else {
      field.fail(fmt::format("{} '{}' names no body, ground, or section or head of an earlier boom '{}'", role, name, part));
    }
    if (!found) field.fail(fmt::format("{} '{}': '{}' has no joint '{}' a boom can use", role, name, part, joint));
    return *found;
  }

  static Frame bodyFrame(const YamlField& body) {
    Frame frame;
    frame.origin = body.position("position", Vec3::Zero());
    if (const auto r = body.find("rotation")) frame.axes = readRotation(*r);
    return frame;
  }

  std::optional<YamlField> findBody(const std::string& name) const {
    const YamlField scene(root_, "");
    if (const auto bodies = scene.find("bodies"))
      for (const YamlField& b : bodies->items())
        if (b.has("name") && b.at("name").text() == name) return b;
    return std::nullopt;
  }

  /// The truss type a section places and its length: the type itself, or a copy of it at the
  /// section's `length` in whole bays of the type.
  std::pair<YAML::Node, double> sectionType(const YamlField& section) {
    const YamlField type_field = section.at("truss");
    const std::string name = type_field.text();
    const auto type = std::find_if(types_.begin(), types_.end(), [&](const TrussType& t) { return t.name == name; });
    if (type == types_.end()) {
      std::vector<std::string> names;
      for (const TrussType& t : types_) names.push_back(t.name);
      type_field.fail(unknownName("truss type", name, names));
    }
    const std::optional<YamlField> length_field = section.find("length");
    if (!length_field) return {type_field.node(), type->length};
    const double length = length_field->positive();
    const double bay = type->length / type->bays;
    const double bays = length / bay;
    const int whole = static_cast<int>(std::lround(bays));
    if (whole < 1 || std::abs(bays - whole) > 1e-9 * bays)
      length_field->fail(fmt::format("truss type '{}' is built in bays of {:g} m ({:g} m in {} bays): {:g} m is not a whole "
                                     "number of them (the nearest: {:g} m or {:g} m)",
                                     name, bay, type->length, type->bays, length, std::max(1.0, std::floor(bays)) * bay,
                                     std::max(1.0, std::ceil(bays)) * bay));
    if (whole == type->bays) return {type_field.node(), type->length};
    const std::string derived = fmt::format("{}_{}bays", name, whole);
    const auto existing = std::find_if(types_.begin(), types_.end(), [&](const TrussType& t) { return t.name == derived; });
    if (existing == types_.end()) {
      YAML::Node copy = copyExcept(type->node, {"name", "length", "order"});
      copy["name"] = derived;
      copy["length"] = number(whole * bay);
      copy["order"] = whole;
      trusses_.push_back(copy);
      types_.push_back({derived, whole * bay, whole, copy});
    } else if (existing->bays != whole || std::abs(existing->length - whole * bay) > 1e-9 * length) {
      length_field->fail(fmt::format("the type '{}' this section would make is already a truss type under trusses", derived));
    }
    return {YAML::Node(derived), whole * bay};
  }

  /// The section's fidelity, else the boom's; without either the scene's default must give one.
  std::optional<YAML::Node> sectionFidelity(const YamlField& boom, const YamlField& section) const {
    for (const YamlField* f : {&section, &boom})
      if (const auto fidelity = f->find("fidelity")) {
        fidelity->choice({"super_truss", "condensed", "beam", "members"});
        return fidelity->node();
      }
    if (!has_default_fidelity_)
      section.fail("missing field 'fidelity': give the section or its boom a fidelity, or the scene's defaults.truss_fidelity");
    return std::nullopt;
  }

  /// The head body: the scene's fields, drawn at the boom's top in the boom's frame.
  void placeHead(const YamlField& head, const Frame& top) {
    if (!head.isMap()) head.fail("expected the head body: a mapping of name, mass, centroid, inertia, joints");
    for (const char* key : {"position", "rotation"})
      if (head.has(key))
        head.at(key).fail(fmt::format("the boom places its head: give no '{}' (the head's frame is the boom's: x along "
                                      "its axis, y the foot pin)", key));
    const std::string name = head.at("name").identifier();
    YAML::Node body = copyExcept(head.node(), {});
    body["position"] = point(top.origin);
    body["rotation"] = rotationMatrix(top.axes);
    bodies_.push_back(body);
    heads_[name] = {top, head.node()};
  }

  /// A constraint the boom adds; fails at `field` when the scene already has one of its name.
  YAML::Node addConstraint(const YamlField& field, const std::string& name, const char* type, const std::string& first,
                           const std::string& second) {
    if (!constraint_names_.insert(name).second)
      field.fail(fmt::format("the boom joins its parts by a constraint '{}', a name the scene already uses", name));
    YAML::Node c(YAML::NodeType::Map);
    c["name"] = name;
    c["type"] = type;
    c["joints"] = joints(first, second);
    constraints_.push_back(c);
    return c;
  }

  struct Head {
    Frame frame;
    YAML::Node node;
  };

  /// The drawn pose of the joint named at `field` on the boom's head.
  Frame headJoint(const YamlField& head, const YamlField& field) const {
    const std::string name = head.at("name").text();
    const std::optional<Frame> joint = namedJoint(heads_.at(name).frame, head.find("joints"), field.text());
    if (!joint) field.fail(fmt::format("head '{}' has no joint '{}'", name, field.text()));
    return *joint;
  }

  /// A member the boom's rigging places: the scene's member without `start`, `end` and the keys
  /// the tool sets, of `type` (the type it leaves out), with those keys set.
  YAML::Node riggingMember(const YamlField& member, const char* type, const std::vector<const char*>& set_by_tool) {
    if (!member.isMap()) member.fail(fmt::format("expected a {} member: a mapping with its name, section and material", type));
    for (const char* key : {"start", "end"})
      if (member.has(key)) member.at(key).fail(fmt::format("the boom places its rigging: give no '{}'", key));
    for (const char* key : set_by_tool)
      if (member.has(key)) member.at(key).fail(fmt::format("the boom sizes its rigging: give no '{}'", key));
    if (const auto t = member.find("type"); t && t->text() != type)
      t->fail(fmt::format("this member of the boom's rigging is a {}", type));
    member.at("name").identifier();
    YAML::Node out = copyExcept(member.node(), {"type", "length"});
    out["type"] = type;
    return out;
  }

  /// `luffing: {from: <head joint>, to: <joint>, ties: [strut ties with a length], rope: {…}}`:
  /// one straight line from the head's joint to the anchor, the ties first; the luffing rope
  /// closes it, its unstretched length the rest of the line — or, reeved, its falls span the rest
  /// of the line between a block at the anchor and one at the line's end, its length the lead
  /// line from its winch and the falls.
  void rigLuffingLine(const YamlField& luffing, const YamlField& head) {
    luffing.allowKeys({"from", "to", "ties", "rope", "rope_length"});
    const std::string head_name = head.at("name").text();
    const Vec3 from = headJoint(head, luffing.at("from")).origin;
    const Vec3 anchor = jointFrame(luffing.at("to"), "the luffing line's anchor").origin;
    const double line = (anchor - from).norm();
    if (line < 1e-3) luffing.at("to").fail("the luffing line's anchor lies at the head's joint");
    const Vec3 along = (anchor - from) / line;
    std::string previous = head_name + "." + luffing.at("from").text();
    double reach = 0.0;
    const std::optional<YamlField> ties = luffing.find("ties");
    if (ties)
      for (const YamlField& tie : ties->items()) {
        YAML::Node member = riggingMember(tie, "strut_tie", {});
        const std::string name = tie.at("name").text();
        member["start"] = point(from + reach * along);
        reach += tie.at("length").positive();
        member["end"] = point(from + reach * along);
        members_.push_back(member);
        addConstraint(tie.at("name"), name + "_start", "spherical", previous, name + ".start");
        previous = name + ".end";
      }
    const YamlField rope = luffing.at("rope");
    const double rope_length = line - reach;
    constexpr double kShortestRope = 0.1;  // m
    if (rope_length < kShortestRope)
      (ties ? *ties : luffing.at("to"))
          .fail(fmt::format("the ties reach {:.6g} m down the luffing line, whose anchor is {:.6g} m from the head's joint: "
                            "the luffing rope needs at least {:g} m (fewer or shorter ties)", reach, line, kShortestRope));
    YAML::Node member = riggingMember(rope, "rope", {"length"});
    const std::string name = rope.at("name").text();
    const std::optional<YamlField> given_length = luffing.find("rope_length");
    if (const auto reeving = luffingReeving(rope, anchor)) {
      const auto block = [&](const char* key, const std::string& joint) {
        YAML::Node b = rope.has(key) && rope.at(key).isMap() ? copyExcept(rope.at(key).node(), {}) : YAML::Node(YAML::NodeType::Map);
        b["joint"] = joint;
        member[key] = b;
      };
      block("head", luffing.at("to").text());
      block("hook", previous);
      member["length"] = given_length ? given_length->node() : number(reeving->lead + reeving->falls * rope_length);
      members_.push_back(member);
      return;
    }
    member["start"] = point(anchor);
    member["end"] = point(from + reach * along);
    member["length"] = given_length ? given_length->node() : number(rope_length);
    members_.push_back(member);
    addConstraint(rope.at("name"), name + "_start", "spherical", luffing.at("to").text(), name + ".start");
    addConstraint(rope.at("name"), name + "_end", "spherical", previous, name + ".end");
  }

  /// `hoist: {sheave: <head joint>, rope: {…}, hanging_length | hook_height, hook: <body>.<joint>}`:
  /// the hoist rope hangs straight down from the sheave, its unstretched length the hanging
  /// length (`from_equilibrium`: at first the distance down to the stated hook height); the load
  /// body is drawn with its hook joint at the rope's end. `stated`: the boom's equilibrium is
  /// the scene's stated one.
  void rigHoist(const YamlField& hoist, const YamlField& head, bool stated) {
    hoist.allowKeys({"sheave", "rope", "hanging_length", "hook_height", "hook"});
    const Vec3 sheave = headJoint(head, hoist.at("sheave")).origin;
    if (hoist.has("hanging_length") == hoist.has("hook_height"))
      hoist.fail("give the hook's hanging_length below the sheave or its hook_height, one of them");
    const std::optional<YamlField> hanging = hoist.find("hanging_length");
    const bool from_equilibrium = hanging && hanging->isScalar() && hanging->text() == "from_equilibrium";
    const bool height_stated = stated && stated_->hook_height;
    if (from_equilibrium && !height_stated)
      hanging->fail("'from_equilibrium' sizes the hoist rope where its equilibrium holds the hook at a stated height: give "
                    "the boom equilibrium: {hook_height: <m>}");
    if (height_stated && !from_equilibrium)
      throw SceneError(stated_->hook_height->where,
                       "a stated hook height sizes the hoist rope: give hoist.hanging_length: from_equilibrium with it");
    const auto lengthDownTo = [&](double height, const auto& fail) {
      const double length = sheave.dot(kUp) - height;
      if (length < 0.1)
        fail(fmt::format("the hook must hang at least 0.1 m below the sheave, drawn at a height of {:.6g} m", sheave.dot(kUp)));
      return length;
    };
    double length = 0.0;
    if (from_equilibrium) {
      length = lengthDownTo(stated_->hook_height->value,
                            [&](const std::string& message) { throw SceneError(stated_->hook_height->where, message); });
      stated_->drawn.hanging_length = length;
    } else if (hanging) {
      length = lengthAtStart(*hanging);
    } else {
      const YamlField height = hoist.at("hook_height");
      length = lengthDownTo(height.number(), [&](const std::string& message) { height.fail(message); });
    }
    const YamlField rope = hoist.at("rope");
    const std::string name = rope.at("name").text();
    YAML::Node member = riggingMember(rope, "rope", {"length"});
    const Vec3 hook = sheave - length * kUp;
    member["start"] = point(sheave);
    member["end"] = point(hook);
    member["length"] = hanging && !from_equilibrium ? hanging->node() : number(length);
    members_.push_back(member);
    addConstraint(rope.at("name"), name + "_start", "spherical", head.at("name").text() + "." + hoist.at("sheave").text(),
                  name + ".start");
    if (const auto hook_field = hoist.find("hook")) {
      hangLoad(*hook_field, hook);
      addConstraint(*hook_field, name + "_hook", "spherical", hook_field->text(), name + ".end");
    }
  }

  /// The body of the joint `<body>.<joint>` named at `field`, drawn with that joint at `hook`.
  void hangLoad(const YamlField& field, const Vec3& hook) {
    const std::string name = field.text();
    const std::size_t dot = name.find('.');
    const std::optional<YamlField> body = dot == std::string::npos ? std::nullopt : findBody(name.substr(0, dot));
    if (!body) field.fail(fmt::format("the hook '{}' is not a joint '<body>.<joint>' of a body under bodies", name));
    if (body->has("position"))
      body->at("position").fail("the boom's hoist hangs this body at its hook: give it no position");
    Frame frame = bodyFrame(*body);
    const std::optional<Frame> joint = namedJoint(frame, body->find("joints"), name.substr(dot + 1));
    if (!joint) field.fail(fmt::format("body '{}' has no joint '{}'", name.substr(0, dot), name.substr(dot + 1)));
    YAML::Node placed = copyExcept(body->node(), {});
    placed["position"] = point(hook - joint->origin);
    hung_bodies_[name.substr(0, dot)] = placed;
  }

  const YAML::Node root_;
  std::optional<StatedEquilibrium> stated_;
  std::vector<TrussType> types_;
  std::set<std::string> constraint_names_;
  bool has_default_fidelity_ = false;
  std::map<std::string, Head> heads_;
  std::map<std::string, std::array<Frame, 2>> sections_;  // a section's start and end
  std::map<std::string, YAML::Node> hung_bodies_;        // loads placed by a hoist, by name
  YAML::Node trusses_{YAML::NodeType::Sequence}, members_{YAML::NodeType::Sequence}, bodies_{YAML::NodeType::Sequence},
      constraints_{YAML::NodeType::Sequence};
};

}  // namespace

ExpandedBooms expandBooms(const YAML::Node& root) {
  if (!root.IsMap() || !root["booms"]) return {root, std::nullopt};
  const YamlField booms(root["booms"], "booms");
  if (!booms.isSequence()) booms.fail("expected a list of booms");
  BoomAssembler assembler(root);
  for (const YamlField& boom : booms.items()) assembler.assemble(boom);
  return {assembler.expanded(), assembler.stated()};
}

}  // namespace cranesim
