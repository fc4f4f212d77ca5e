#include "cranesim/planning/target.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <tuple>

#include "bounded_yaml.hpp"
#include "cranesim/crane/stated_equilibrium_search.hpp"
#include "cranesim/io/scene_reader.hpp"
#include "cranesim/model/closest_name.hpp"
#include "cranesim/model/compile.hpp"
#include "cranesim/planning/rest_to_rest_path.hpp"
#include "cranesim/planning/slewing_axis.hpp"
#include "sensor_reader.hpp"
#include "solver_reader.hpp"
#include "wind_reader.hpp"
#include "yaml_field.hpp"

namespace cranesim {
namespace {

// Sizes no plan comes near, refused before they exhaust memory or time.
constexpr long kMaxTrajectorySteps = 100000;
constexpr long kMaxSplinePoints = 10000;
constexpr double kMaxSettleTime = 86400.0;  // s

/// {from, to, step} → from, from + step, …, to.
std::vector<double> readGrid(const YamlField& f) {
  f.allowKeys({"from", "to", "step"});
  const double from = f.at("from").number(), to = f.at("to").number(), step = f.at("step").positive();
  if (!(to > from)) f.at("to").fail(fmt::format("must be above from ({}), found {}", from, to));
  const double count = (to - from) / step;
  if (std::abs(count - std::round(count)) > 1e-9 * std::max(1.0, count))
    f.at("step").fail(fmt::format("the range {} … {} is not a whole number of steps of {}", from, to, step));
  if (count > 1000) f.at("step").fail(fmt::format("{} grid points: at most 1000 per axis", count + 1));
  std::vector<double> values;
  for (int k = 0; k <= std::lround(count); ++k) values.push_back(from + k * step);
  return values;
}

template <int N> Eigen::Matrix<double, N, 1> readVector(const YamlField& f) {
  const std::vector<double> v = f.numbers();
  if (static_cast<int>(v.size()) != N) f.fail(fmt::format("expected a list of {} numbers, found {}", N, v.size()));
  return Eigen::Map<const Eigen::Matrix<double, N, 1>>(v.data());
}

/// A weight matrix given by its diagonal.
template <int N> Eigen::Matrix<double, N, N> readDiagonal(const YamlField& f) {
  const Eigen::Matrix<double, N, 1> d = readVector<N>(f);
  if ((d.array() < 0.0).any()) f.fail("weights must not be negative");
  return d.asDiagonal();
}

CraneControls readControls(const YamlField& f) {
  f.allowKeys({"luffing_rope", "hoist_rope", "boom_angle", "end_point"});
  CraneControls c;
  c.luffing_rope = f.at("luffing_rope").text();
  c.hoist_rope = f.at("hoist_rope").text();
  const YamlField boom = f.at("boom_angle");
  const std::vector<YamlField> joints = boom.items();
  if (joints.size() != 2) boom.fail("expected [foot joint, head joint]");
  c.boom_foot = joints[0].text();
  c.boom_head = joints[1].text();
  c.end_point = f.at("end_point").text();
  return c;
}

/// `slewing: {constraint, turn}`: a driven revolute constraint of the scene about the vertical
/// (at the drawn state), and the turn in degrees; sets the target's slewing and its axis.
void readSlewing(const YamlField& f, TargetSpec& t) {
  f.allowKeys({"constraint", "turn"});
  SlewingSpec s;
  s.where = f.where();
  const YamlField turn = f.at("turn");
  const double degrees = turn.number();
  if (!(std::abs(degrees) <= 360.0)) turn.fail(fmt::format("a turn of {}°: at most one revolution (±360°)", degrees));
  s.turn = degrees * std::numbers::pi / 180.0;
  const YamlField name = f.at("constraint");
  s.constraint = name.text();
  const auto c = std::find_if(t.scene.constraints.begin(), t.scene.constraints.end(),
                              [&](const ConstraintSpec& spec) { return spec.name == s.constraint; });
  if (c == t.scene.constraints.end()) name.fail(fmt::format("the scene has no constraint '{}'", s.constraint));
  if (c->type != ConstraintType::Revolute || !c->drive)
    name.fail(fmt::format("'{}' is no driven revolute constraint: the slewing needs one (type: revolute, with a drive)", s.constraint));
  s.start = (*c->drive)(t.scene.solver.t_start);
  try {
    t.slewing_axis = slewingAxisOf(t.scene, s.constraint, t.controls.end_point);
  } catch (const std::invalid_argument& e) {
    name.fail(std::string(e.what()) + ": the slewing turns the crane about the vertical");
  }
  t.slewing = s;
}

/// `drive_limits: {luffing, hoist, slewing}`, each `{speed, acceleration, jerk}` (any of them;
/// the slewing's in degrees).
ControlLimits readDriveLimits(const YamlField& f, bool slewing) {
  f.allowKeys({"luffing", "hoist", "slewing"});
  ControlLimits limits;
  limits.where = f.where();
  for (const auto& [key, drive, scale] : {std::tuple{"luffing", &limits.luffing, 1.0}, std::tuple{"hoist", &limits.hoist, 1.0},
                                          std::tuple{"slewing", &limits.slewing, std::numbers::pi / 180.0}}) {
    const auto d = f.find(key);
    if (!d) continue;
    if (std::string(key) == "slewing" && !slewing) d->fail("slewing limits need a slewing target (slewing: {constraint, turn})");
    d->allowKeys({"speed", "acceleration", "jerk"});
    for (const auto& [name, value] : {std::pair{"speed", &drive->speed}, std::pair{"acceleration", &drive->acceleration},
                                      std::pair{"jerk", &drive->jerk}})
      if (const auto v = d->find(name)) *value = scale * v->positive();
  }
  return limits;
}

MinimumTimeSpec readMinimumTime(const YamlField& f) {
  f.allowKeys({"intervals", "rise_time", "tolerance", "clearance_allowance"});
  MinimumTimeSpec m;
  m.where = f.where();
  if (const auto n = f.find("intervals")) {
    m.intervals = n->integer();
    if (m.intervals < 10 || m.intervals > 2000) n->fail(fmt::format("{} intervals: between 10 and 2000", m.intervals));
  }
  m.rise_time = f.positive("rise_time", m.rise_time);
  m.tolerance = f.positive("tolerance", m.tolerance);
  if (const auto a = f.find("clearance_allowance")) m.clearance_allowance = a->nonNegative();
  return m;
}

/// A minimum-time lift needs every drive it moves bounded in speed: else no time is the least.
void checkMinimumTimeLimits(const YamlField& f, const TargetSpec& t) {
  std::string missing;
  for (const auto& [name, drive] : {std::pair{"luffing", &t.drive_limits.luffing}, std::pair{"hoist", &t.drive_limits.hoist},
                                    std::pair{"slewing", &t.drive_limits.slewing}})
    if (!drive->speed && (std::string(name) != "slewing" || t.slewing))
      missing += fmt::format("{}{}: {{speed: …}}", missing.empty() ? "" : ", ", name);
  if (missing.empty()) return;
  const std::string what =
      fmt::format("method minimum_time needs a speed limit for every drive it moves; missing: drive_limits: {{{}}}", missing);
  if (const auto l = f.find("drive_limits")) l->fail(what);
  f.at("method").fail(what);
}

StaticMapSpec readMap(const YamlField& f) {
  f.allowKeys({"boom_angle", "hoist_change", "hoist_length", "tolerance", "max_iterations", "threads"});
  StaticMapSpec m;
  m.boom_angles_deg = readGrid(f.at("boom_angle"));
  if (m.boom_angles_deg.front() <= 0.0 || m.boom_angles_deg.back() >= 90.0)
    f.at("boom_angle").fail("boom angles must lie between 0° and 90° (exclusive)");
  m.hoist_changes = readGrid(f.at("hoist_change"));
  if (const auto h = f.find("hoist_length")) m.hoist_length = h->positive();
  m.tolerance = f.positive("tolerance", m.tolerance);
  if (const auto it = f.find("max_iterations")) m.max_iterations = it->integer();
  if (const auto t = f.find("threads")) m.threads = t->integer();
  if (m.threads < 0) f.at("threads").fail("must not be negative (0: all cores)");
  return m;
}

SurfaceSpec readFit(const YamlField& f) {
  f.allowKeys({"type", "order"});
  SurfaceSpec s;
  s.kind = f.at("type").choice({"polynomial", "spline"}) == "spline" ? SurfaceKind::Spline : SurfaceKind::Polynomial;
  if (const auto o = f.find("order")) {
    if (s.kind == SurfaceKind::Spline) o->fail("a spline surface has no order (it is bicubic)");
    const std::vector<YamlField> orders = o->items();
    if (orders.size() != 2) o->fail("expected [order in boom angle, order in hoist change]");
    s.order_u = orders[0].integer();
    s.order_v = orders[1].integer();
    for (const YamlField& order : orders)
      if (order.integer() < 1 || order.integer() > 5) order.fail("polynomial orders run from 1 to 5");
  }
  return s;
}

/// The slewing axis of a target that does not slew, for radii: the one the scene's `crane:` block
/// names; none without it, or where that one turns about no vertical (it serves radii only).
std::optional<SlewingAxis> craneBlockAxis(const TargetSpec& t) {
  if (!t.scene.crane) return std::nullopt;
  try {
    return slewingAxisOf(t.scene, t.scene.crane->slewing, t.controls.end_point);
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

/// `pick` or `set`: `{radius, height}` of the end point, m, as a state at rest in trajectory coordinates.
EndState liftEnd(const YamlField& f, const TargetSpec& t) {
  f.allowKeys({"radius", "height"});
  if (!t.slewing_axis)
    f.fail("a radius is measured from the slewing axis: give the target a slewing block or the scene a crane block naming "
           "its slewing constraint (a revolute constraint about the vertical)");
  const YamlField radius = f.at("radius");
  double x = 0.0;
  try {
    x = t.slewing_axis->xAtRadius(radius.positive());
  } catch (const std::domain_error& e) {
    radius.fail(e.what());
  }
  return EndState(x - t.origin.x(), f.at("height").number() - t.origin.y(), 0.0, 0.0);
}

void readTrajectory(const YamlField& f, TargetSpec& t) {
  f.allowKeys({"origin", "start", "target", "pick", "set", "state_min", "state_max", "control_min", "control_max", "Q", "R",
               "P_end", "steps", "sample_time", "receding_horizon", "tolerance"});
  QrProblem& p = t.trajectory;
  if (const auto o = f.find("origin")) t.origin = readVector<2>(*o);
  for (const auto& [state, where, key, engineers] : {std::tuple{&p.start, &t.where_start, "start", "pick"},
                                                     std::tuple{&p.target, &t.where_target, "target", "set"}}) {
    const auto given = f.find(key), given_by_radius = f.find(engineers);
    if (given && given_by_radius) given_by_radius->fail(fmt::format("give the {} or the {}, not both", key, engineers));
    if (!given && !given_by_radius) f.fail(fmt::format("missing key '{}' (or '{}': {{radius, height}})", key, engineers));
    *state = given ? readVector<4>(*given) : liftEnd(*given_by_radius, t);
    *where = (given ? *given : *given_by_radius).where();
  }
  // Without bounds the end point may run 10 m beyond the box of its start and target, at 1 m/s.
  const Eigen::Vector4d reach(10.0, 10.0, 1.0, 1.0);
  p.state_min = f.find("state_min") ? readVector<4>(f.at("state_min")) : Eigen::Vector4d(p.start.cwiseMin(p.target) - reach);
  p.state_max = f.find("state_max") ? readVector<4>(f.at("state_max")) : Eigen::Vector4d(p.start.cwiseMax(p.target) + reach);
  p.control_min = readVector<2>(f.at("control_min"));
  p.control_max = readVector<2>(f.at("control_max"));
  p.Q = readDiagonal<4>(f.at("Q"));
  p.R = readDiagonal<2>(f.at("R"));
  p.P_end = readDiagonal<4>(f.at("P_end"));
  p.steps = f.at("steps").integer();
  if (p.steps > kMaxTrajectorySteps)
    f.at("steps").fail(fmt::format("{} steps: at most {} steps (Table 8-2 takes 400); the NLP's memory grows with them",
                                   p.steps, kMaxTrajectorySteps));
  p.sample_time = f.at("sample_time").positive();
  if (const auto h = f.find("receding_horizon")) p.receding_horizon = h->integer();
  p.tolerance = f.positive("tolerance", p.tolerance);
  try {
    validate(p);
  } catch (const std::invalid_argument& e) {
    f.fail(e.what());
  }
}

/// A number within [low, high] (either sign), `what` saying what it means.
double between(const YamlField& f, double low, double high, const char* what) {
  const double x = f.number();
  if (!(x >= low && x <= high)) f.fail(fmt::format("{:g} lies outside [{:g}, {:g}]: {}", x, low, high, what));
  return x;
}

TrackingCase readTrackingCase(const YamlField& f, const Scene& scene) {
  f.allowKeys({"name", "load_mass", "hoist_rope", "initial_sway", "gust", "wind", "sensor"});
  TrackingCase c;
  c.where = f.where();
  c.name = f.at("name").text();
  if (const auto m = f.find("load_mass")) c.load_mass = between(*m, 0.1, 10.0, "a factor on the planned load's mass and inertia");
  if (const auto h = f.find("hoist_rope"))
    c.hoist_rope = between(*h, -0.5, 0.5, "the fraction by which the real hoist rope is longer than the planned one");
  if (const auto s = f.find("initial_sway")) c.initial_sway = between(*s, -20.0, 20.0, "m the load starts displaced outwards");
  if (const auto g = f.find("gust")) {
    g->allowKeys({"force", "start", "duration", "direction"});
    TrackingGust gust;
    gust.force = between(g->at("force"), -1e8, 1e8, "N, the gust's peak force on the load");
    if (const auto s = g->find("start")) gust.start = s->nonNegative();
    if (const auto d = g->find("duration")) gust.duration = d->positive();
    if (const auto d = g->find("direction")) gust.across = d->choice({"across", "radial"}) == "across";
    c.gust = gust;
  }
  if (const auto w = f.find("wind")) c.wind = readWind(*w, scene);
  if (const auto s = f.find("sensor")) c.sensor = readSwaySensor(*s);
  return c;
}

TrackingSpec readTracking(const YamlField& f, const TargetSpec& target) {
  f.allowKeys({"sample_time", "slewing", "sheave", "settle_band", "rtol", "atol", "cases"});
  TrackingSpec spec;
  spec.where = f.where();
  spec.slewing = target.slewing ? target.slewing->constraint : "slewing";
  if (const auto s = f.find("slewing")) spec.slewing = s->text();
  const auto driven = std::find_if(target.scene.constraints.begin(), target.scene.constraints.end(),
                                   [&](const ConstraintSpec& c) { return c.name == spec.slewing && c.drive; });
  if (driven == target.scene.constraints.end()) {
    std::vector<std::string> names;
    for (const ConstraintSpec& c : target.scene.constraints)
      if (c.drive) names.push_back(c.name);
    (f.find("slewing") ? *f.find("slewing") : f)
        .fail(fmt::format("the feedback damps the swing across the boom by slewing the crane: {} (name the slewing "
                          "drive with feedback.slewing)",
                          unknownName("driven constraint", spec.slewing, names)));
  }
  if (const auto s = f.find("sample_time")) spec.sample_time = s->within(1e-4, 1.0, "s");
  if (const auto b = f.find("settle_band")) spec.settle_band = b->positive();
  if (const auto r = f.find("rtol")) spec.rtol = readRelativeTolerance(*r);
  if (const auto a = f.find("atol")) spec.atol = readAbsoluteTolerance(*a);
  if (const auto s = f.find("sheave")) {
    spec.sheave = s->text();
    const Model model = compileModel(target.scene);
    if (model.findJoint(spec.sheave) < 0) s->fail(unknownName("joint", spec.sheave, namesOf(model.joints)));
  }
  const YamlField cases = f.at("cases");
  if (!cases.isSequence() || cases.items().empty())
    cases.fail("a list of cases, each a crane that differs from the planned one: {name: …, load_mass: …, hoist_rope: …, "
               "initial_sway: …, gust: {…}, wind: {…}, sensor: {…}}");
  const std::string load = target.controls.end_point.substr(0, target.controls.end_point.find('.'));
  if (std::none_of(target.scene.bodies.begin(), target.scene.bodies.end(),
                   [&](const RigidBodySpec& b) { return b.name == load; }))
    f.fail(fmt::format("the feedback's cases act on the load, a body: the end point '{}' is not a body's joint",
                       target.controls.end_point));
  for (const YamlField& item : cases.items()) {
    TrackingCase c = readTrackingCase(item, target.scene);
    for (const TrackingCase& other : spec.cases)
      if (other.name == c.name) item.at("name").fail(fmt::format("a second case named '{}'", c.name));
    spec.cases.push_back(std::move(c));
  }
  return spec;
}

/// `{name, shape: box, centre, size, yaw}` (yaw in degrees), `{name, shape: cylinder, base, radius,
/// height}` or `{name, shape: prism, footprint: [[x, y], …], bottom, top}` (a convex footprint).
Obstacle readObstacle(const YamlField& f) {
  if (!f.isMap()) f.fail("an obstacle is a mapping: {name: …, shape: box | cylinder | prism, …}");
  Obstacle o;
  o.where = f.where();
  o.name = f.at("name").text();
  const std::string shape = f.at("shape").choice({"box", "cylinder", "prism"});
  if (shape == "box") {
    f.allowKeys({"name", "shape", "centre", "size", "yaw"});
    const YamlField size = f.at("size");
    const Vec3 edges = size.vec3();
    if (!(edges.array() > 0.0).all())
      size.fail(fmt::format("a box's edge lengths must be positive, found [{:g}, {:g}, {:g}]", edges.x(), edges.y(), edges.z()));
    const auto yaw = f.find("yaw");
    o.shape = BoxShape(f.at("centre").vec3(), edges, yaw ? yaw->number() * std::numbers::pi / 180.0 : 0.0);
  } else if (shape == "cylinder") {
    f.allowKeys({"name", "shape", "base", "radius", "height"});
    o.shape = CylinderShape{f.at("base").vec3(), f.at("radius").positive(), f.at("height").positive()};
  } else {
    f.allowKeys({"name", "shape", "footprint", "bottom", "top"});
    PrismShape prism;
    const YamlField footprint = f.at("footprint");
    if (!footprint.isSequence() || footprint.items().size() < 3)
      footprint.fail("a footprint is a polygon of at least 3 points [[x, y], …]");
    for (const YamlField& point : footprint.items()) prism.footprint.push_back(readVector<2>(point));
    if (!makeConvexCounterClockwise(prism.footprint))
      footprint.fail("the footprint is not convex (or has three points on a line): split it into convex prisms");
    prism.bottom = f.at("bottom").number();
    prism.top = f.at("top").number();
    if (!(prism.top > prism.bottom)) f.at("top").fail(fmt::format("must be above bottom ({:g}), found {:g}", prism.bottom, prism.top));
    o.shape = prism;
  }
  return o;
}

std::vector<Obstacle> readObstacles(const YamlField& f) {
  if (!f.isSequence()) f.fail("a list of obstacles, each {name: …, shape: box | cylinder | prism, …}");
  std::vector<Obstacle> obstacles;
  for (const YamlField& item : f.items()) {
    Obstacle o = readObstacle(item);
    for (const Obstacle& other : obstacles)
      if (other.name == o.name) item.at("name").fail(fmt::format("a second obstacle named '{}'", o.name));
    obstacles.push_back(std::move(o));
  }
  return obstacles;
}

}  // namespace

TargetSpec readTarget(const std::string& path) {
  const std::string text = readInputFile(path, "target file", {});
  const YAML::Node root = loadBoundedYaml(text);
  const YamlField f(root, "");
  // An empty document has no mark of its own: the defect is the file from its first line on.
  if (!f.isMap()) throw SceneError({"<document>", 1, 1}, "a target file is a mapping (scene, crane, map, fit, trajectory, …)");
  f.allowKeys({"name", "scene", "method", "minimum_time", "crane", "slewing", "drive_limits", "map", "fit", "trajectory",
               "control_spline", "verification", "feedback", "obstacles", "clearance_margin", "load_radius"});

  TargetSpec t;
  t.path = path;
  t.text = text;
  const YamlField scene = f.at("scene");
  const std::string scene_path = (std::filesystem::path(path).parent_path() / scene.text()).string();
  try {
    t.scene = sceneAtStatedEquilibrium(readScene(scene_path), true);
  } catch (const SceneError& e) {
    scene.fail(fmt::format("in the scene '{}': {}", scene_path, e.what()));
  }
  if (const auto method = f.find("method")) {
    const std::string m = method->choice({"quasi_static", "zv", "zvd", "flatness", "minimum_time"});
    t.method = m == "zv"             ? PlanMethod::ZV
               : m == "zvd"          ? PlanMethod::ZVD
               : m == "flatness"     ? PlanMethod::Flatness
               : m == "minimum_time" ? PlanMethod::MinimumTime
                                     : PlanMethod::QuasiStatic;
  }
  if (const auto m = f.find("minimum_time")) {
    if (t.method != PlanMethod::MinimumTime) m->fail("minimum_time settings need method: minimum_time");
    t.minimum_time = readMinimumTime(*m);
  }
  const YamlField crane = f.at("crane");
  t.controls = readControls(crane);
  t.where_controls = crane.where();
  checkControls(t.scene, t.controls, t.where_controls);
  if (const auto s = f.find("slewing")) readSlewing(*s, t);
  if (const auto l = f.find("drive_limits")) t.drive_limits = readDriveLimits(*l, t.slewing.has_value());
  if (t.method == PlanMethod::MinimumTime) checkMinimumTimeLimits(f, t);
  t.map = readMap(f.at("map"));
  if (const auto fit = f.find("fit")) t.fit = readFit(*fit);
  if (!t.slewing) t.slewing_axis = craneBlockAxis(t);
  const YamlField trajectory = f.at("trajectory");
  t.where_trajectory = trajectory.where();
  readTrajectory(trajectory, t);
  if (startsFromFlatness(t.method)) {
    try {
      restToRestPath(t.trajectory);
    } catch (const std::invalid_argument& e) {
      trajectory.fail(e.what());
    }
  }
  if (const auto c = f.find("control_spline")) {
    c->allowKeys({"resample_points", "steady_points"});
    if (const auto r = c->find("resample_points")) t.resample_points = r->integer();
    if (const auto s = c->find("steady_points")) t.steady_points = s->integer();
    if (t.resample_points < 2) c->at("resample_points").fail("at least 2 points");
    if (t.resample_points > kMaxSplinePoints)
      c->at("resample_points").fail(fmt::format("{} points: at most {}", t.resample_points, kMaxSplinePoints));
    if (t.steady_points < 0) c->at("steady_points").fail("must not be negative");
    if (t.steady_points > kMaxSplinePoints)
      c->at("steady_points").fail(fmt::format("{} points: at most {}", t.steady_points, kMaxSplinePoints));
  }
  if (const auto v = f.find("verification")) {
    v->allowKeys({"settle_time", "rtol", "atol"});
    if (const auto r = v->find("rtol")) t.verification_rtol = readRelativeTolerance(*r);
    if (const auto a = v->find("atol")) t.verification_atol = readAbsoluteTolerance(*a);
    if (const auto s = v->find("settle_time")) {
      t.settle_time = s->nonNegative();
      if (t.settle_time > kMaxSettleTime)
        s->fail(fmt::format("{:g} s of settling: at most {:g} s (a day) of simulated time after the last knot",
                            t.settle_time, kMaxSettleTime));
    }
  }
  if (const auto fb = f.find("feedback")) t.feedback = readTracking(*fb, t);
  if (const auto o = f.find("obstacles")) t.obstacles = readObstacles(*o);
  if (const auto m = f.find("clearance_margin")) t.clearance_margin = m->nonNegative();
  if (const auto r = f.find("load_radius")) t.load_radius = r->nonNegative();
  return t;
}

}  // namespace cranesim
