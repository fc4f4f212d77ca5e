#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <mutex>
#include <set>

#include "bounded_yaml.hpp"
#include "cranesim/model/closest_name.hpp"
#include "cranesim/model/compile.hpp"
#include "cranesim/study/random_draw.hpp"
#include "cranesim/study/study.hpp"
#include "scene_composition.hpp"
#include "yaml_field.hpp"

namespace cranesim {

/// yaml-cpp's nodes are not safe to read from several threads at once (reading a node may
/// change its reference counts and zombie children), so case scenes are built one at a time.
struct StudySceneSource {
  std::vector<ComposedScene> bases;        // `scene`, or each of `scenes`, with the study's `modify`
  std::vector<YamlField> parameter_paths;  // where each parameter is named in the study file
  std::vector<YamlField> capacity_paths;   // capacity: where its load, then each follower, is named
  std::vector<YamlField> angle_path;       // least_stable_angle: where its angle is named
  mutable std::mutex lock;
};

namespace {

/// No grid on one axis comes near this many values; refused before it is allocated.
constexpr double kMaxGridValues = 1e6;

/// Names a figure may not take: the case table's own columns.
const std::set<std::string> kReservedFigureNames = {"status", "message", "steps", "wall_time_s"};

std::vector<double> readRange(const YamlField& f) {
  f.allowKeys({"from", "to", "count"});
  const double from = f.at("from").number(), to = f.at("to").number();
  const YamlField count_field = f.at("count");
  const double count = count_field.number();
  if (count != std::floor(count) || count < 1) count_field.fail(fmt::format("expected a whole number of values ≥ 1, found {:g}", count));
  if (count > kMaxGridValues) count_field.fail(fmt::format("{:g} values: at most {:g} per parameter", count, kMaxGridValues));
  if (count == 1 && from != to) count_field.fail(fmt::format("one value cannot span {:g} … {:g}: give count ≥ 2, or from = to", from, to));
  std::vector<double> values(static_cast<std::size_t>(count));
  for (std::size_t k = 0; k < values.size(); ++k) values[k] = from + (to - from) * static_cast<double>(k) / (count - 1);
  values.back() = to;
  return values;
}

RandomDistribution readDistribution(const YamlField& f) {
  RandomDistribution d;
  const std::string kind = f.at("distribution").choice({"uniform", "normal", "truncated_normal"});
  if (kind == "uniform") {
    f.allowKeys({"distribution", "low", "high"});
    d.kind = RandomDistribution::Kind::Uniform;
  } else if (kind == "normal") {
    f.allowKeys({"distribution", "mean", "std"});
    d.kind = RandomDistribution::Kind::Normal;
  } else {
    f.allowKeys({"distribution", "mean", "std", "low", "high"});
    d.kind = RandomDistribution::Kind::TruncatedNormal;
  }
  if (kind != "uniform") {
    d.mean = f.at("mean").number();
    d.std_dev = f.at("std").positive();
  }
  if (kind != "normal") {
    d.low = f.at("low").number();
    d.high = f.at("high").number();
    if (!(d.high > d.low)) f.at("high").fail(fmt::format("must be above low ({:g}), found {:g}", d.low, d.high));
  }
  if (kind == "truncated_normal" && normalMassWithin(d) < kMinTruncatedMass)
    f.fail(fmt::format("[{:g}, {:g}] holds only {:.2g} of the normal's probability: at least {:g}", d.low, d.high,
                       normalMassWithin(d), kMinTruncatedMass));
  return d;
}

/// A joint named by `body` (its origin) or `joint`; fails unless exactly one is given and exists.
std::string readJointOf(const YamlField& f, const Model& model) {
  if (f.has("body") == f.has("joint")) f.fail("name exactly one of body (its origin) or joint");
  const YamlField named = f.has("body") ? f.at("body") : f.at("joint");
  const std::string joint = f.has("body") ? named.text() + ".origin" : named.text();
  if (model.findJoint(joint) < 0) {
    std::string bodies;
    for (const Node& n : model.nodes)
      if (n.member.empty()) bodies += (bodies.empty() ? "" : ", ") + n.name;
    named.fail(fmt::format("the scene has no {} '{}' (bodies: {}; joints are named <body>.<joint>)",
                           f.has("body") ? "body" : "joint", named.text(), bodies));
  }
  return joint;
}

std::string readReferenceJoint(const YamlField& f, const Model& model) {
  const std::string joint = f.text();
  if (model.findJoint(joint) < 0) f.fail(fmt::format("the scene has no joint '{}' (joints are named <body>.<joint>)", joint));
  return joint;
}

/// A rope of the scene named by `f`.
std::string readRopeName(const YamlField& f, const Scene& scene) {
  const std::string rope = f.text();
  std::string ropes;
  bool found = false;
  for (const MemberSpec& m : scene.members)
    if (m.type == MemberType::Rope) {
      ropes += (ropes.empty() ? "" : ", ") + m.name;
      found = found || m.name == rope;
    }
  if (!found) f.fail(fmt::format("the scene has no rope '{}' (ropes: {})", rope, ropes.empty() ? "none" : ropes));
  return rope;
}

bool isReeved(const Scene& scene, const std::string& rope) {
  return std::any_of(scene.members.begin(), scene.members.end(),
                     [&](const MemberSpec& m) { return m.name == rope && m.reeving; });
}

/// A reeved rope of the scene named by `f`.
std::string readReevedRopeName(const YamlField& f, const Scene& scene) {
  const std::string rope = readRopeName(f, scene);
  if (!isReeved(scene, rope))
    f.fail(fmt::format("rope '{}' is not reeved (element: reeved): its tension is quantity: rope_tension", rope));
  return rope;
}

/// The constraint holding a rope's end: its force is the rope's tension there.
std::string constraintAtRopeEnd(const YamlField& f, const Scene& scene, const Model& model) {
  const YamlField rope_field = f.at("rope");
  const std::string rope = readRopeName(rope_field, scene);
  if (isReeved(scene, rope))
    rope_field.fail(fmt::format("rope '{}' is reeved: its ends are joints of other parts; use quantity: part_tension or "
                                "line_pull", rope));
  const std::string end = f.has("end") ? f.at("end").choice({"start", "end"}) : "end";
  const int node = model.joints[model.findJoint(rope + "." + end)].node;
  std::vector<std::string> held_by;
  for (const Constraint& c : model.constraints)
    if (model.joints[c.joint1].node == node || model.joints[c.joint2].node == node) held_by.push_back(c.name);
  if (held_by.size() != 1)
    rope_field.fail(fmt::format("the {} of rope '{}' is held by {} constraints{}: name one with quantity: constraint_force",
                                end, rope, held_by.size(), held_by.empty() ? "" : fmt::format(" ({})", fmt::join(held_by, ", "))));
  return held_by.front();
}

/// A rigid body of the scene named by `f`.
std::string readBodyName(const YamlField& f, const Scene& scene) {
  const std::string body = f.text();
  std::string bodies;
  for (const RigidBodySpec& b : scene.bodies) {
    if (b.name == body) return body;
    bodies += (bodies.empty() ? "" : ", ") + b.name;
  }
  f.fail(fmt::format("the scene has no body '{}' (bodies: {})", body, bodies));
}

/// A constraint of the scene named by `f`.
const Constraint& readConstraintName(const YamlField& f, const Model& model) {
  const std::string name = f.text();
  std::string known;
  for (const Constraint& k : model.constraints) {
    if (k.name == name) return k;
    known += (known.empty() ? "" : ", ") + k.name;
  }
  f.fail(fmt::format("the scene has no constraint '{}' (constraints: {})", name, known));
}

FigureStatistic readStatistic(const YamlField& f) {
  if (!f.has("statistic")) return FigureStatistic::Final;
  const std::string s = f.at("statistic").choice({"final", "max", "min"});
  return s == "final" ? FigureStatistic::Final : s == "max" ? FigureStatistic::Max : FigureStatistic::Min;
}

FigureSpec readFigure(const YamlField& f, const Study& study, const Scene& scene, const Model& model) {
  FigureSpec fig;
  if (!f.isMap()) f.fail("expected a mapping {name, quantity, …}");
  fig.name = f.at("name").identifier();
  if (kReservedFigureNames.count(fig.name)) f.at("name").fail(fmt::format("'{}' is a column of every case table already", fig.name));
  const std::string quantity =
      f.at("quantity").choice({"rope_tension", "constraint_force", "constraint_moment", "position", "horizontal_distance",
                               "horizontal_sway", "frequency", "tipping_moment", "dynamic_factor", "rope_slack",
                               "support_pressure", "stability_margin", "tipping_load", "tipping_load_fraction", "boom_angle",
                               "part_tension", "line_pull"});
  const bool of_supports = quantity == "support_pressure" || quantity == "stability_margin" || quantity == "tipping_load" ||
                           quantity == "tipping_load_fraction";
  if (of_supports && !model.envelope.supports)
    f.at("quantity").fail(fmt::format("{} needs a scene whose crane stands on ground.supports", quantity));
  if (quantity == "rope_tension") {
    f.allowKeys({"name", "quantity", "rope", "end", "statistic", "after"});
    fig.quantity = FigureQuantity::ConstraintForce;
    fig.constraint = constraintAtRopeEnd(f, scene, model);
  } else if (quantity == "constraint_force" || quantity == "constraint_moment" || quantity == "dynamic_factor") {
    if (quantity == "dynamic_factor") {
      f.allowKeys({"name", "quantity", "constraint", "after"});
      fig.quantity = FigureQuantity::DynamicFactor;
      fig.statistic = FigureStatistic::Max;
    } else {
      f.allowKeys({"name", "quantity", "constraint", "statistic", "after"});
      fig.quantity = quantity == "constraint_force" ? FigureQuantity::ConstraintForce : FigureQuantity::ConstraintMoment;
    }
    fig.constraint = readConstraintName(f.at("constraint"), model).name;
  } else if (quantity == "part_tension" || quantity == "line_pull") {
    f.allowKeys({"name", "quantity", "rope", "statistic", "after"});
    fig.quantity = quantity == "part_tension" ? FigureQuantity::PartTension : FigureQuantity::LinePull;
    fig.rope = readReevedRopeName(f.at("rope"), scene);
  } else if (quantity == "rope_slack") {
    f.allowKeys({"name", "quantity", "rope", "after"});
    fig.quantity = FigureQuantity::RopeSlack;
    fig.rope = readRopeName(f.at("rope"), scene);
  } else if (quantity == "tipping_moment") {
    f.allowKeys({"name", "quantity", "supports", "line", "statistic", "after"});
    fig.quantity = FigureQuantity::TippingMoment;
    const YamlField supports = f.at("supports");
    for (const YamlField& item : supports.items()) {
      const Constraint& c = readConstraintName(item, model);
      if ((model.joints[c.joint1].node < 0) == (model.joints[c.joint2].node < 0))
        item.fail(fmt::format("constraint '{}' does not join the structure to the ground", c.name));
      fig.supports.push_back(c.name);
    }
    if (fig.supports.empty()) supports.fail("name at least one constraint that holds the structure on the ground");
    const std::array<Vec3, 2> line = f.at("line").tippingLine();
    fig.line_from = line[0];
    fig.line_to = line[1];
  } else if (quantity == "support_pressure" || quantity == "stability_margin") {
    f.allowKeys({"name", "quantity", "statistic", "after"});
    fig.quantity = quantity == "support_pressure" ? FigureQuantity::SupportPressure : FigureQuantity::StabilityMargin;
  } else if (quantity == "tipping_load" || quantity == "tipping_load_fraction") {
    f.allowKeys({"name", "quantity", "body", "statistic", "after"});
    fig.quantity = quantity == "tipping_load" ? FigureQuantity::TippingLoad : FigureQuantity::TippingLoadFraction;
    fig.body = readBodyName(f.at("body"), scene);
  } else if (quantity == "position") {
    f.allowKeys({"name", "quantity", "body", "joint", "component", "statistic", "after"});
    fig.quantity = FigureQuantity::Position;
    fig.joint = readJointOf(f, model);
    const std::string axis = f.at("component").choice({"x", "y", "z"});
    fig.component = axis[0] - 'x';
  } else if (quantity == "horizontal_distance") {
    f.allowKeys({"name", "quantity", "body", "joint", "relative_to", "statistic", "after"});
    fig.quantity = FigureQuantity::HorizontalDistance;
    fig.joint = readJointOf(f, model);
    fig.relative_to = readReferenceJoint(f.at("relative_to"), model);
  } else if (quantity == "boom_angle") {
    f.allowKeys({"name", "quantity", "statistic", "after"});
    fig.quantity = FigureQuantity::BoomAngle;
    if (!scene.crane) f.at("quantity").fail("a boom angle is the crane's: give the scene a crane: block (its boom_foot and boom_head)");
    const auto foot = std::find_if(scene.constraints.begin(), scene.constraints.end(),
                                   [&](const ConstraintSpec& c) { return c.name == scene.crane->boom_foot; });
    fig.relative_to = foot->joint1;
    fig.joint = scene.crane->boom_head;
  } else if (quantity == "horizontal_sway") {
    f.allowKeys({"name", "quantity", "body", "joint", "relative_to", "about_mean", "after"});
    fig.quantity = FigureQuantity::HorizontalSway;
    fig.statistic = FigureStatistic::Max;
    fig.joint = readJointOf(f, model);
    if (const auto r = f.find("relative_to")) fig.relative_to = readReferenceJoint(*r, model);
    if (const auto m = f.find("about_mean")) {
      fig.about_mean = m->boolean();
      if (fig.about_mean && fig.relative_to.empty())
        m->fail("about_mean needs relative_to (without it the sway is taken about the mean position already)");
    }
  } else {
    f.allowKeys({"name", "quantity", "mode"});
    fig.quantity = FigureQuantity::Frequency;
    if (study.analysis != StudyAnalysis::Modes) f.at("quantity").fail("a frequency needs analysis: modes");
    const YamlField mode = f.at("mode");
    fig.mode = mode.integer();
    if (fig.mode < 1 || fig.mode > study.mode_count)
      mode.fail(fmt::format("mode {} of the {} computed (modes: {}): expected 1 … {}", fig.mode, study.mode_count,
                            study.mode_count, study.mode_count));
    return fig;
  }
  if (fig.quantity != FigureQuantity::HorizontalSway && fig.quantity != FigureQuantity::DynamicFactor &&
      fig.quantity != FigureQuantity::RopeSlack)
    fig.statistic = readStatistic(f);
  if (const auto after = f.find("after")) fig.after = after->number();
  return fig;
}

/// The index of the study's figure that `figure` names.
std::size_t readFigureName(const YamlField& figure, const std::vector<FigureSpec>& figures) {
  const std::string name = figure.text();
  const auto named = std::find_if(figures.begin(), figures.end(), [&](const FigureSpec& s) { return s.name == name; });
  if (named == figures.end()) figure.fail(fmt::format("no figure named '{}' in figures", name));
  return static_cast<std::size_t>(named - figures.begin());
}

StudyCriterion readCriterion(const YamlField& f, const std::vector<FigureSpec>& figures) {
  f.allowKeys({"figure", "min", "max", "source"});
  StudyCriterion c;
  c.figure = readFigureName(f.at("figure"), figures);
  if (!f.has("min") && !f.has("max")) f.fail("a criterion needs min, max or both");
  if (const auto min = f.find("min")) c.min = min->number();
  if (const auto max = f.find("max")) c.max = max->number();
  if (!(c.max >= c.min)) f.at("max").fail(fmt::format("must not be below min ({:g}), found {:g}", c.min, c.max));
  c.source = f.at("source").text();
  return c;
}

/// `node` (a number, or a list of numbers or of such lists) with every number times `factor`;
/// throws std::invalid_argument on anything else.
YAML::Node scaled(const YAML::Node& node, double factor) {
  if (node.IsSequence()) {
    YAML::Node out(YAML::NodeType::Sequence);
    for (const YAML::Node& item : node) out.push_back(scaled(item, factor));
    return out;
  }
  double value = 0.0;
  if (!node.IsScalar() || !YAML::convert<double>::decode(node, value) || !std::isfinite(value))
    throw std::invalid_argument("not a number or a list of numbers");
  return YAML::Node(fmt::format("{}", value * factor));
}

/// A parameter's `scales_with`: the earlier parameter it follows, and that parameter's value in
/// the base scene, which must be a non-zero number.
void readLeader(StudyParameter& p, const YamlField& path, const YamlField& leader_field,
                const std::vector<StudyParameter>& earlier, const std::vector<YamlField>& earlier_paths,
                const std::vector<ComposedScene>& scenes) {
  const std::string leader = leader_field.text();
  std::vector<std::string> names;
  for (const StudyParameter& e : earlier) names.push_back(e.path);
  const auto found = std::find(names.begin(), names.end(), leader);
  if (found == names.end()) {
    const std::string closest = closestName(leader, names);
    leader_field.fail(fmt::format("no parameter above this one varies '{}'{}", leader,
                                  closest.empty() ? "" : fmt::format("; did you mean '{}'?", closest)));
  }
  const std::size_t k = static_cast<std::size_t>(found - names.begin());
  if (earlier[k].scales_with) leader_field.fail(fmt::format("'{}' follows another parameter itself: follow that one", leader));
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    double base = 0.0;
    const YAML::Node base_node = sceneField(scenes[i].root, earlier_paths[k], leader);
    if (!base_node.IsScalar() || !YAML::convert<double>::decode(base_node, base) || !std::isfinite(base) || base == 0.0)
      leader_field.fail(fmt::format("the base scene's '{}' must be a non-zero number to scale by", leader));
    if (i > 0 && base != p.leader_base)
      leader_field.fail(fmt::format("the scenes give '{}' different values ({:g} and {:g}): a parameter scales with one "
                                    "base value", leader, p.leader_base, base));
    p.leader_base = base;
    try {
      scaled(sceneField(scenes[i].root, path, p.path), 1.0);
    } catch (const std::invalid_argument&) {
      path.fail(fmt::format("the base scene's '{}' must be a number or a list of numbers to scale", p.path));
    }
  }
  p.scales_with = k;
}

StudyParameter readParameter(const YamlField& f, const std::vector<ComposedScene>& scenes,
                             const std::vector<StudyParameter>& earlier, std::vector<YamlField>& paths) {
  f.allowKeys({"path", "values", "range", "random", "scales_with"});
  StudyParameter p;
  const YamlField path = f.at("path");
  p.path = path.text();
  if (f.has("values") + f.has("range") + f.has("random") + f.has("scales_with") != 1)
    f.fail("give exactly one of values, range, random or scales_with");
  if (const auto leader = f.find("scales_with")) {
    readLeader(p, path, *leader, earlier, paths, scenes);
  } else if (const auto values = f.find("values")) {
    if (!values->isSequence()) values->fail("expected a list of numbers");
    p.values = values->numbers();
    if (p.values.empty()) values->fail("an empty grid: give at least one value");
    if (static_cast<double>(p.values.size()) > kMaxGridValues)
      values->fail(fmt::format("{} values: at most {:g} per parameter", p.values.size(), kMaxGridValues));
  } else if (const auto range = f.find("range")) {
    p.values = readRange(*range);
  } else {
    p.random = readDistribution(f.at("random"));
  }
  // The path must name a field every scene gives (a study varies what the scene says).
  for (const ComposedScene& scene : scenes) modifyScene(YAML::Clone(scene.root), path, p.path, YAML::Node(0.0), /*require_field=*/true);
  paths.push_back(path);
  return p;
}

/// `capacity: {load, from, to, tolerance, scales}`: the field bisected to each case's capacity
/// and the fields that follow it; `paths` gets where each is named. Needs criteria to bisect
/// by, a load no parameter varies, and numbers to scale.
CapacitySpec readCapacity(const YamlField& f, const Study& study, const std::vector<ComposedScene>& scenes,
                          std::vector<YamlField>& paths) {
  f.allowKeys({"load", "from", "to", "tolerance", "scales"});
  if (study.criteria.empty()) f.fail("a capacity is the heaviest load every criterion admits: give the study criteria");
  CapacitySpec c;
  const auto varied = [&](const YamlField& path) {
    for (const StudyParameter& p : study.parameters)
      if (p.path == path.text())
        path.fail(fmt::format("'{}' is varied by a parameter: the capacity sets it in each case itself", p.path));
  };
  const YamlField load = f.at("load");
  c.load = load.text();
  varied(load);
  for (const ComposedScene& scene : scenes) {
    double base = 0.0;
    const YAML::Node value = sceneField(scene.root, load, c.load);
    if (!value.IsScalar() || !YAML::convert<double>::decode(value, base) || !std::isfinite(base) || base == 0.0)
      load.fail(fmt::format("the scene's '{}' must be a non-zero number: the load bisected, and scaled by", c.load));
  }
  paths.push_back(load);
  c.from = f.at("from").positive();
  c.to = f.at("to").number();
  if (!(c.to > c.from)) f.at("to").fail(fmt::format("the bracket's heavy end must lie above from ({:g}), found {:g}", c.from, c.to));
  const YamlField tolerance = f.at("tolerance");
  c.tolerance = tolerance.positive();
  if (c.tolerance >= c.to - c.from)
    tolerance.fail(fmt::format("the bracket [{:g}, {:g}] is narrower than the tolerance already", c.from, c.to));
  if (const auto scales = f.find("scales"))
    for (const YamlField& follower : scales->items()) {
      c.scales.push_back(follower.text());
      varied(follower);
      for (const ComposedScene& scene : scenes) try {
          scaled(sceneField(scene.root, follower, c.scales.back()), 1.0);
        } catch (const std::invalid_argument&) {
          follower.fail(fmt::format("the scene's '{}' must be a number or a list of numbers to scale", c.scales.back()));
        }
      paths.push_back(follower);
    }
  return c;
}

/// `least_stable_angle: {angle, values | range, figure, worst, tolerance}`: the field searched
/// for the angle at which the figure is worst, the grid of angles every case computes, and the
/// search's tolerance; `path` gets where the angle is named. The angle must be a number of every
/// scene that no parameter and no capacity sets.
LeastStableAngleSpec readLeastStableAngle(const YamlField& f, const Study& study, const std::vector<ComposedScene>& scenes,
                                          std::vector<YamlField>& path) {
  f.allowKeys({"angle", "values", "range", "figure", "worst", "tolerance"});
  LeastStableAngleSpec spec;
  const YamlField angle = f.at("angle");
  spec.angle = angle.text();
  for (const StudyParameter& p : study.parameters)
    if (p.path == spec.angle) angle.fail(fmt::format("'{}' is varied by a parameter: the search sets it in each case itself", p.path));
  if (study.capacity && (study.capacity->load == spec.angle ||
                         std::find(study.capacity->scales.begin(), study.capacity->scales.end(), spec.angle) != study.capacity->scales.end()))
    angle.fail(fmt::format("'{}' is set by the capacity: the search needs a field of its own", spec.angle));
  for (const ComposedScene& scene : scenes) {
    double base = 0.0;
    const YAML::Node value = sceneField(scene.root, angle, spec.angle);
    if (!value.IsScalar() || !YAML::convert<double>::decode(value, base) || !std::isfinite(base))
      angle.fail(fmt::format("the scene's '{}' must be a number: the angle searched", spec.angle));
  }
  path.push_back(angle);
  if (f.has("values") == f.has("range")) f.fail("give the grid of angles every case computes first: one of values or range");
  if (const auto values = f.find("values")) {
    if (!values->isSequence()) values->fail("expected a list of angles");
    spec.grid = values->numbers();
  } else {
    spec.grid = readRange(f.at("range"));
  }
  const YamlField grid = f.has("values") ? f.at("values") : f.at("range");
  if (spec.grid.size() < 2) grid.fail("a search between grid angles needs at least two of them");
  if (static_cast<double>(spec.grid.size()) > kMaxGridValues) grid.fail(fmt::format("{} angles: at most {:g}", spec.grid.size(), kMaxGridValues));
  double step = std::numeric_limits<double>::infinity();
  for (std::size_t k = 1; k < spec.grid.size(); ++k) {
    if (!(spec.grid[k] > spec.grid[k - 1]))
      grid.fail(fmt::format("the angles must increase: {:g} follows {:g}", spec.grid[k], spec.grid[k - 1]));
    step = std::min(step, spec.grid[k] - spec.grid[k - 1]);
  }
  spec.figure = readFigureName(f.at("figure"), study.figures);
  spec.worst_is_max = f.at("worst").choice({"max", "min"}) == std::string("max");
  const YamlField tolerance = f.at("tolerance");
  spec.tolerance = tolerance.positive();
  if (spec.tolerance >= step)
    tolerance.fail(fmt::format("the grid's angles lie {:g} apart: a search to {:g} would not refine them", step, spec.tolerance));
  return spec;
}

/// The study's scenes: `scene`, or each of `scenes`, composed as scene files are, with the
/// study's `modify` set in each, and read; their paths and texts go into `study`.
std::vector<Scene> readStudyScenes(const YamlField& f, const std::string& path, Study& study, std::vector<ComposedScene>& bases) {
  if (f.has("scene") == f.has("scenes")) f.fail("give the base scene, or a list of them under scenes: one of scene and scenes");
  const std::vector<YamlField> fields = f.has("scene") ? std::vector<YamlField>{f.at("scene")} : f.at("scenes").items();
  if (fields.empty()) f.at("scenes").fail("an empty list: give at least one scene");
  const std::optional<YamlField> modify = f.find("modify");
  if (modify) {
    if (!modify->isMap()) modify->fail("expected a mapping of <path>: <value>, set in every scene");
    modify->rejectDuplicateKeys();
  }
  std::vector<Scene> scenes;
  for (const YamlField& field : fields) {
    const std::string scene_path = (std::filesystem::path(path).parent_path() / field.text()).string();
    ComposedScene composed;
    try {
      const auto validate = [](const ComposedScene& base, const std::string& base_path) { sceneFromComposed(base, base_path); };
      composed = composeScene(readInputFile(scene_path, "scene file", {}), scene_path, validate);
    } catch (const SceneError& e) {
      field.fail(fmt::format("in the scene '{}': {}", scene_path, e.what()));
    }
    if (modify)
      for (const std::string& key : modify->keys()) modifyScene(composed.root, modify->at(key), key, modify->at(key).node());
    try {
      scenes.push_back(sceneFromComposed(composed, scene_path));
    } catch (const SceneError& e) {
      field.fail(fmt::format("in the scene '{}'{}: {}", scene_path, modify ? " with the study's modify" : "", e.what()));
    }
    study.scene_paths.push_back(scene_path);
    study.scene_path += (study.scene_path.empty() ? "" : "\n") + scene_path;
    study.scene_text += fields.size() == 1 ? composed.text : fmt::format("# ---- scene: {} ----\n{}\n", scene_path, composed.text);
    bases.push_back(std::move(composed));
  }
  return scenes;
}

}  // namespace

double StudyCriterion::holds(double value) const {
  if (std::isnan(value)) return value;
  return value >= min && value <= max ? 1.0 : 0.0;
}

std::vector<double> Study::parameterValues(long index) const {
  std::vector<double> values(parameters.size());
  long grid = index / samples;
  for (std::size_t k = parameters.size(); k-- > 0;) {
    const StudyParameter& p = parameters[k];
    if (p.scales_with) continue;  // below, from the value it follows
    if (p.random) {
      values[k] = randomDraw(*p.random, seed, static_cast<std::uint64_t>(index), k);
    } else {
      const long n = static_cast<long>(p.values.size());
      values[k] = p.values[static_cast<std::size_t>(grid % n)];
      grid /= n;
    }
  }
  for (std::size_t k = 0; k < parameters.size(); ++k)
    if (const auto leader = parameters[k].scales_with) values[k] = values[*leader] / parameters[k].leader_base;
  return values;
}

Study readStudy(const std::string& path) {
  Study study;
  study.path = path;
  study.text = readInputFile(path, "study file", {});
  const YAML::Node root = loadBoundedYaml(study.text);
  const YamlField f(root, "");
  if (!f.isMap()) f.fail("a study file is a mapping (scene, analysis, parameters, figures, …)");
  f.allowKeys({"name", "scene", "scenes", "modify", "analysis", "modes", "parameters", "samples", "seed", "figures",
               "criteria", "capacity", "least_stable_angle", "keep_results"});

  auto source = std::make_shared<StudySceneSource>();
  const std::vector<Scene> scenes = readStudyScenes(f, path, study, source->bases);
  const Scene& scene = scenes.front();
  std::vector<Model> models;
  for (const Scene& s : scenes) models.push_back(compileModel(s));
  const Model& model = models.front();

  const std::string analysis = f.at("analysis").choice({"static", "run", "modes"});
  study.analysis = analysis == "static" ? StudyAnalysis::Static : analysis == "run" ? StudyAnalysis::Run : StudyAnalysis::Modes;
  if (const auto modes = f.find("modes")) {
    if (study.analysis != StudyAnalysis::Modes) modes->fail("modes counts the modes of analysis: modes");
    study.mode_count = modes->integer();
    if (study.mode_count < 1 || study.mode_count > model.nv)
      modes->fail(fmt::format("expected 1 … {} (the model's velocity coordinates), found {}", model.nv, study.mode_count));
  }

  double cases = 1.0;
  bool random = false;
  if (scenes.size() > 1) {
    StudyParameter choice;
    choice.path = kSceneParameter;
    for (std::size_t k = 0; k < scenes.size(); ++k) choice.values.push_back(static_cast<double>(k));
    choice.scene_index = true;
    study.parameters.push_back(choice);
    source->parameter_paths.push_back(f.at("scenes"));
    cases = static_cast<double>(scenes.size());
  }
  if (const auto parameters = f.find("parameters")) {
    std::set<std::string> seen;
    for (const YamlField& p : parameters->items()) {
      study.parameters.push_back(readParameter(p, source->bases, study.parameters, source->parameter_paths));
      if (!seen.insert(study.parameters.back().path).second) p.at("path").fail("this path is varied twice");
      random = random || study.parameters.back().random.has_value();
      cases *= static_cast<double>(std::max<std::size_t>(1, study.parameters.back().values.size()));
    }
  }
  if (const auto samples = f.find("samples")) {
    if (!random) samples->fail("samples are draws of the random parameters, and no parameter is random");
    const double n = samples->number();
    if (n != std::floor(n) || n < 1) samples->fail(fmt::format("expected a whole number ≥ 1, found {:g}", n));
    if (n > kMaxStudyCases) samples->fail(fmt::format("{:g} draws: a study has at most {:g} cases", n, kMaxStudyCases));
    study.samples = static_cast<long>(n);
  } else if (random) {
    f.fail("random parameters need samples: the number of draws per grid point");
  }
  cases *= static_cast<double>(study.samples);
  if (cases > kMaxStudyCases)
    (f.has("parameters") ? f.at("parameters") : f).fail(
        fmt::format("{:.4g} cases: a study has at most {:g} (split it into several studies)", cases, kMaxStudyCases));
  study.cases = static_cast<long>(cases);
  if (const auto seed = f.find("seed")) {
    const double s = seed->number();
    if (s != std::floor(s) || s < 0 || s > 0x1.0p53) seed->fail(fmt::format("expected a whole number 0 … 2⁵³, found {:g}", s));
    study.seed = static_cast<std::uint64_t>(s);
  } else if (random) {
    f.fail("random parameters need a seed (a whole number), so that the study can be repeated");
  }

  if (const auto figures = f.find("figures")) {
    std::set<std::string> names;
    for (const YamlField& fig : figures->items()) {
      study.figures.push_back(readFigure(fig, study, scene, model));
      if (!names.insert(study.figures.back().name).second) fig.at("name").fail("duplicate figure name");
      for (std::size_t k = 1; k < scenes.size(); ++k)
        if (const FigureSpec other = readFigure(fig, study, scenes[k], models[k]); other.constraint != study.figures.back().constraint)
          fig.fail(fmt::format("this figure is the constraint '{}' in the scene '{}' but '{}' in '{}': a figure measures the "
                               "same in every scene", study.figures.back().constraint, scenes.front().path,
                               other.constraint, scenes[k].path));
    }
  }
  if (const auto criteria = f.find("criteria"))
    for (const YamlField& c : criteria->items()) study.criteria.push_back(readCriterion(c, study.figures));
  if (const auto capacity = f.find("capacity"))
    study.capacity = readCapacity(*capacity, study, source->bases, source->capacity_paths);
  if (const auto search = f.find("least_stable_angle"))
    study.least_stable = readLeastStableAngle(*search, study, source->bases, source->angle_path);
  if (const auto keep = f.find("keep_results")) study.keep_results = keep->boolean();
  study.source = std::move(source);
  return study;
}

Scene caseScene(const Study& study, long index, const CaseSetting& setting) {
  const std::optional<double>& load = setting.load;
  const std::vector<double> values = study.parameterValues(index);
  const StudySceneSource& source = *study.source;
  std::size_t scene = 0;
  std::string header = fmt::format("# study {}, case {}:", study.path, index);
  for (std::size_t k = 0; k < values.size(); ++k) {
    header += fmt::format(" {} = {}", study.parameters[k].path, values[k]);
    if (study.parameters[k].scene_index) scene = static_cast<std::size_t>(values[k]);
  }
  if (load) header += fmt::format(" {} = {} (capacity)", study.capacity->load, *load);
  if (setting.angle) header += fmt::format(" {} = {} (least stable angle search)", study.least_stable->angle, *setting.angle);
  const std::lock_guard<std::mutex> lock(source.lock);
  const ComposedScene& base = source.bases[scene];
  ComposedScene composed{YAML::Clone(base.root), header + "\n" + base.text};
  for (std::size_t k = 0; k < values.size(); ++k) {
    const StudyParameter& p = study.parameters[k];
    if (p.scene_index) continue;
    const YamlField& where = source.parameter_paths[k];
    const YAML::Node value = p.scales_with ? scaled(sceneField(base.root, where, p.path), values[k])
                                           : YAML::Node(fmt::format("{}", values[k]));
    modifyScene(composed.root, where, p.path, value);
  }
  if (load) {
    // The followers first: they scale with the load over the scene's own value of it.
    const std::vector<YamlField>& paths = source.capacity_paths;
    const double factor = *load / sceneField(base.root, paths[0], study.capacity->load).as<double>();
    for (std::size_t k = 0; k < study.capacity->scales.size(); ++k)
      modifyScene(composed.root, paths[k + 1], study.capacity->scales[k],
                  scaled(sceneField(base.root, paths[k + 1], study.capacity->scales[k]), factor));
    modifyScene(composed.root, paths[0], study.capacity->load, YAML::Node(fmt::format("{}", *load)));
  }
  if (setting.angle)
    modifyScene(composed.root, source.angle_path.front(), study.least_stable->angle, YAML::Node(fmt::format("{}", *setting.angle)));
  return sceneFromComposed(composed, study.scene_paths[scene]);
}

}  // namespace cranesim
