#pragma once
// A study (docs/studies.md): one base scene, parameters varied over grids or drawn at random, one
// analysis per case (static, run or modes) and the figures extracted from each case. Cases are
// numbered 0 … caseCount() − 1; a case's parameter values are a function of its number alone
// (grid position, and random draws from the seed and the number), so any worker computes any
// case and the case table does not depend on who computed it.

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cranesim/model/scene.hpp"
#include "cranesim/model/source_location.hpp"

namespace cranesim {

enum class StudyAnalysis { Static, Run, Modes };

/// A random parameter's distribution. Truncated normal: the normal restricted to [low, high].
struct RandomDistribution {
  enum class Kind { Uniform, Normal, TruncatedNormal } kind = Kind::Uniform;
  double low = 0.0, high = 1.0;   // uniform, truncated normal
  double mean = 0.0, std_dev = 1.0;  // normal, truncated normal
};

struct StudyParameter {
  std::string path;            // a `modify` key into the scene, e.g. bodies.load.mass
  std::vector<double> values;  // a grid parameter's values; empty for a random or following one
  std::optional<RandomDistribution> random;
  /// A parameter that follows an earlier one (`scales_with`, its index): the base scene's value
  /// (a number or a list of numbers, e.g. an inertia following a mass) times that parameter's
  /// value over its base value, `leader_base`. Its value in a case is that factor.
  std::optional<std::size_t> scales_with;
  double leader_base = 1.0;
  /// The study's scene (`scenes:`): the case's index into Study::scene_paths, the first
  /// parameter, so the slowest to vary.
  bool scene_index = false;
};

/// The path of the parameter that chooses a study's scene among its `scenes`.
inline constexpr const char* kSceneParameter = "scene";

/// What a figure measures. Time series (all but frequency) are reduced over the samples at
/// t ≥ after by the figure's statistic; a static case has one sample.
enum class FigureQuantity {
  ConstraintForce,     // ‖force rows of λ‖ of a constraint, N (rope_tension: the one at the rope's end)
  ConstraintMoment,    // ‖other rows of λ‖ of a constraint: its moments (and drive torque), N·m
  Position,            // one coordinate of a joint's origin, m
  HorizontalDistance,  // horizontal distance of a joint from another joint, m (a radius)
  HorizontalSway,      // max horizontal distance of a joint from a reference joint or its mean, m
  Frequency,           // a mode's frequency, Hz (analysis: modes)
  TippingMoment,       // moment of ground supports' reactions about a directed line, N·m
  DynamicFactor,       // a constraint's peak force over its force at the first sample (φ2)
  RopeSlack,           // time a rope is slack somewhere (a point without tension), s
  SupportPressure,     // the largest bed pressure under the carriage's pads and tracks, Pa
  StabilityMargin,     // restoring − overturning moment about the active tipping line, N·m
  TippingLoad,         // the hook load that tips the carriage, N (crane/support_statics.hpp)
  TippingLoadFraction, // the load's weight over that tipping load, 1
  BoomAngle,           // the crane's boom angle: its foot hinge to its head joint above the horizontal, deg
  PartTension,         // the largest part tension of a reeved rope, N
  LinePull,            // a reeved rope's winch pull hoisting steadily the load its falls carry, N
};
enum class FigureStatistic { Final, Max, Min };

struct FigureSpec {
  std::string name;
  FigureQuantity quantity = FigureQuantity::Position;
  FigureStatistic statistic = FigureStatistic::Final;
  std::string constraint;   // ConstraintForce
  std::string joint;        // Position, HorizontalSway
  std::string relative_to;  // HorizontalDistance, HorizontalSway: the reference joint; empty (sway): the mean position
  bool about_mean = false;  // HorizontalSway with relative_to: the offset from the reference less its mean (a steady wind's)
  int component = 0;        // Position: 0, 1, 2 for x, y, z
  double after = -std::numeric_limits<double>::infinity();  // s
  int mode = 0;             // Frequency: 1-based, as `crane-sim modes` numbers them
  std::string rope;         // RopeSlack, PartTension, LinePull
  std::vector<std::string> supports;  // TippingMoment: constraints joining the structure to the ground
  Vec3 line_from = Vec3::Zero(), line_to = Vec3::Zero();  // TippingMoment: the tipping line, directed
  std::string body;         // TippingLoad, TippingLoadFraction: the hook load's body
};

/// A bound on a figure: a case is admissible when every criterion holds (a load chart's limits).
struct StudyCriterion {
  std::size_t figure = 0;  // index into Study::figures
  double min = -std::numeric_limits<double>::infinity(), max = std::numeric_limits<double>::infinity();
  std::string source;      // where the limit comes from (a standard, a rating), stored with the results
  /// 1 when `value` lies within [min, max], 0 when not, NaN when the figure is NaN.
  double holds(double value) const;
};

/// A study's `capacity`: each case's heaviest admissible load found by bisection on a field of
/// the scene (study/capacity_search.hpp), instead of a load read off a grid.
struct CapacitySpec {
  std::string load;                 // a `modify` path to a number every scene gives, e.g. bodies.load.mass
  double from = 0.0, to = 0.0;      // the bracket: a load every case is expected to admit, and one none does
  double tolerance = 0.0;           // the bracket's width at which the bisection stops
  std::vector<std::string> scales;  // fields that follow the load in proportion to their scene's values
};

/// A study's `least_stable_angle`: each case's slewing angle at which a figure is worst, found on
/// a grid of angles and refined between the worst grid angle's neighbours by golden-section
/// search (study/least_stable_angle.hpp), instead of read off a grid parameter.
struct LeastStableAngleSpec {
  std::string angle;            // a `modify` path to a number every scene gives, e.g. constraints.slewing.drive.value
  std::vector<double> grid;     // the angles every case computes first, increasing
  std::size_t figure = 0;       // index into Study::figures: the figure whose worst value is searched
  bool worst_is_max = true;     // worst: max (a stability fraction) or min (a tipping load, a margin)
  double tolerance = 0.0;       // the search's bracket width at which it stops, in the angle's unit
};

/// The base scene's YAML, from which each case's scene is built (io/study_reader.cpp).
struct StudySceneSource;

struct Study {
  std::string path, text;  // the study file
  std::string scene_path;  // the base scene (`scenes`: their paths, one per line)
  std::vector<std::string> scene_paths;  // the base scene, or each of `scenes`
  std::string scene_text;  // its text with its own bases (`scenes`: theirs, each after a line naming it)
  StudyAnalysis analysis = StudyAnalysis::Static;
  int mode_count = 10;     // analysis: modes
  std::vector<StudyParameter> parameters;
  long samples = 1;        // draws per grid point (random parameters)
  std::uint64_t seed = 0;
  std::vector<FigureSpec> figures;
  std::vector<StudyCriterion> criteria;
  std::optional<CapacitySpec> capacity;
  std::optional<LeastStableAngleSpec> least_stable;
  bool keep_results = false;
  long cases = 1;          // the product of the grids' sizes × samples
  std::shared_ptr<const StudySceneSource> source;

  /// The parameters' values of case `index`, in the order of `parameters`. The last grid
  /// parameter varies fastest, then the draws: index = grid position × samples + draw.
  std::vector<double> parameterValues(long index) const;
};

/// More cases than any study on one machine or a cluster allocation comes near; refused up front.
inline constexpr double kMaxStudyCases = 1e7;

/// Reads and checks a study file: unknown keys, parameter paths the base scene lacks, empty or
/// absurd grids, figures naming ropes, joints or constraints the scene lacks, all refused with
/// SceneError naming the study file's YAML path and line (a problem in the base scene names it).
Study readStudy(const std::string& path);

/// What a case's scene sets besides its parameters: with `capacity` the load, with
/// `least_stable_angle` the angle.
struct CaseSetting {
  std::optional<double> load, angle;
};

/// The scene of case `index`: the base scene with the case's parameter values set (and with
/// `capacity`, the load and its followers; with `least_stable_angle`, the angle), its text
/// prefixed by the case's values. Throws SceneError (naming the parameter's path in the study
/// file) when those values make a bad scene. Safe to call from several threads.
Scene caseScene(const Study& study, long index, const CaseSetting& setting = {});

}  // namespace cranesim
