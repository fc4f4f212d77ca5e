#pragma once
// The scene: plain data read from YAML, in SI units, before compilation into a Model.

#include <optional>
#include <string>
#include <vector>

#include "cranesim/model/arc.hpp"
#include "cranesim/elements/section.hpp"
#include "cranesim/math/profile.hpp"
#include "cranesim/math/types.hpp"
#include "cranesim/model/crane_spec.hpp"
#include "cranesim/model/feedback_spec.hpp"
#include "cranesim/model/source_location.hpp"
#include "cranesim/model/stated_equilibrium.hpp"
#include "cranesim/model/truss_geometry.hpp"
#include "cranesim/model/wind_field.hpp"

namespace cranesim {

struct JointSpec {
  std::string name;
  Vec3 position = Vec3::Zero();     // in the body frame
  Mat3 rotation = Mat3::Identity();  // joint axes → body axes
  SourceLocation where;
};

struct RigidBodySpec {
  std::string name;
  double mass = 0.0;
  Vec3 centroid = Vec3::Zero();        // body frame, from the body origin
  Mat3 inertia = Mat3::Identity();     // about the centroid, body axes
  Vec3 position = Vec3::Zero();        // initial origin position, inertial
  Mat3 rotation = Mat3::Identity();    // initial body axes → inertial
  Vec3 velocity = Vec3::Zero();        // initial origin velocity, inertial
  Vec3 angular_velocity = Vec3::Zero();  // initial, body frame
  std::vector<JointSpec> joints;
  SourceLocation where;
};

enum class MemberType { StrutTie, Timoshenko, SplineBeam, Rope, Truss };

/// How a truss member is modelled: one super truss element (3.5), one condensed truss element,
/// an equivalent Timoshenko beam, or every tube its own beam.
enum class TrussFidelity { SuperTruss, Condensed, Beam, Members };

/// How a rope is modelled: cubic spline elements (sag, string vibration), straight two-node
/// cables (elements/cable.hpp), or one massless rope reeved over sheaves
/// (elements/reeved_rope.hpp).
enum class RopeElement { Spline, Cable, Reeved };

/// A sheave a reeved rope runs over: a joint at its centre, on a body; its radius and the
/// efficiency of its bearing (the tension ratio across it while the rope runs), or, for a
/// capstan (a sheave that does not turn, a drum or saddle), the rope's friction on it and the
/// angle the rope wraps it.
struct SheaveSpec {
  std::string joint;
  double radius = 0.0;      // m
  double efficiency = 1.0;  // η ∈ (0, 1]
  double friction = 0.0;    // μ of a capstan; 0: a turning sheave
  double inertia = 0.0;     // J of a turning sheave about its axle, kg·m² (massive ropes)
  std::optional<double> wrap;  // θ of a capstan, rad; empty: the drawn path's turn at the sheave
  SourceLocation where;
};

/// A reeved rope's path: from its winch (the joint where its length is reeled) over its
/// sheaves, in order, to its dead end.
struct ReevingSpec {
  std::string winch, dead_end;
  SourceLocation where_winch, where_dead_end;
  std::vector<SheaveSpec> sheaves;
  double speed_band = 1e-3;  // m/s: the rope's running speed over which a sheave's loss turns
  double pre_sliding = 0.0;  // m: every sheave's pre-sliding distance (massless); 0: from the parts' elasticity
  double drawn_length = 0.0;  // Σ of the parts' drawn chords (placeMemberEnds)
  int elements_per_part = 0;  // fidelity massive: each part's cable elements; 0: massless parts
};

/// A flexible member: a straight line of `segments` elements from `start` to `end`, with nodes
/// `<name>.n0 … <name>.n<segments>` (joints of the same names; `<name>.start`, `<name>.end`
/// name the end nodes). Section axes: x along the member, z towards `z_axis`.
/// A truss member (type Truss) places the truss type `truss` (Scene::trusses) with its axis from
/// `start` to `end` and its z axis towards `z_axis`; its end sections are the joints
/// `<name>.start` and `<name>.end`. `segments`, `quadrature` and `damping` apply to every tube
/// (fidelity Members) or to the equivalent beam (fidelity Beam).
struct MemberSpec {
  std::string name;
  MemberType type = MemberType::Timoshenko;
  Vec3 start = Vec3::Zero(), end = Vec3::UnitX();
  /// A joint named for `start` / `end` (e.g. "head.sheave") instead of coordinates; the reader
  /// places the end at that joint's drawn position (io/member_ends.cpp). Empty: coordinates.
  std::string start_joint, end_joint;
  SourceLocation where_start, where_end;
  Vec3 z_axis = Vec3::UnitZ();
  /// A timoshenko member drawn along a circular arc instead of straight (model/arc.hpp).
  std::optional<ArcSpec> arc;
  int segments = 1;
  int quadrature = 0;  // Gauss points per element; 0: the element's default
  Section section;
  Material material;
  std::optional<Profile> length;  // rope: unstretched length (default: ‖end − start‖)
  bool constant_volume = true;    // strut tie: section shrinks with stretch (3-27)
  double smoothing = 0.0;         // strut tie: smoothing factor h (3-16)
  double damping = 0.0;           // Kelvin–Voigt retardation time η of the material, s (0: undamped)
  double transverse_damping = 0.0;  // rope: damping of its sideways turning against its chords, N·s
  RopeElement rope_element = RopeElement::Spline;
  /// rope: its minimum breaking force, N; a run reports a tension above it (crane/envelope.hpp).
  std::optional<double> breaking_force;
  std::optional<ReevingSpec> reeving;  // rope element Reeved: its path (no start and end)
  std::string truss;              // truss: the truss type's name
  TrussFidelity fidelity = TrussFidelity::Members;
  bool fidelity_by_default = false;  // truss: the scene's defaults.truss_fidelity, not its own
  MemberType tube_element = MemberType::Timoshenko;  // truss with fidelity Members: the tubes' beam element
  SourceLocation where;
};

enum class ConstraintType { Fixed, Revolute, Prismatic, Spherical, Distance };

struct ConstraintSpec {
  std::string name;
  ConstraintType type = ConstraintType::Fixed;
  std::string joint1, joint2;  // "<body>.<joint>", "ground.<joint>"
  int axis = 2;                // revolute/prismatic axis of the joint frames: 0=x, 1=y, 2=z
  std::optional<Profile> drive;  // prescribed angle (revolute), displacement (prismatic), length (distance)
  /// Fixed only: keep the joints' relative pose of the drawing (members meeting at an angle)
  /// instead of making the two joint frames coincide.
  bool keep_drawn_pose = false;
  SourceLocation where, where_joint1, where_joint2, where_pose;
};

enum class LoadFrame { Inertial, Joint };

struct LoadSpec {
  std::string name;
  std::string joint;
  Vec3 force = Vec3::Zero();
  Vec3 torque = Vec3::Zero();
  LoadFrame frame = LoadFrame::Inertial;
  Profile scale = Profile(ConstantProfile{1.0});
  SourceLocation where, where_joint;
};

/// A rigid body exposed to the wind: drag coefficient c and wind area A (m²), acting at one of
/// its joints or, when `joint` is empty, at its centroid.
struct WindBodySpec {
  std::string body;
  double area = 0.0;
  double drag_coefficient = 1.2;
  std::string joint;
  SourceLocation where, where_body, where_joint;
};

/// A member exposed to the wind: every element a cylinder of `diameter` (m) with drag
/// coefficient c; of a truss member every tube, its drag times (1 + η)/2 for the shielding η of
/// the lee side.
struct WindMemberSpec {
  std::string member;
  double diameter = 0.0;  // not for a truss member: its tubes' own
  double drag_coefficient = 1.2;
  double shielding = 1.0;  // η, truss members only
  SourceLocation where, where_member;
};

struct WindSpec {
  WindFieldSpec field;
  std::vector<WindBodySpec> bodies;
  std::vector<WindMemberSpec> members;
  int quadrature = 3;  // Gauss points per member element
  SourceLocation where;
};

/// A part that rests on the ground's surface: a sphere about a body's centroid, or about every
/// node of a member (exactly one of `body`, `member`).
struct GroundContactSpec {
  std::string body, member;
  double radius = 0.0;  // m
  SourceLocation where;
};

/// The ground's surface (`ground.surface`): the plane at `height` along −gravity, the penalty law
/// and friction of its contacts (model/contact_elements.hpp), and the parts that rest on it.
/// Every other part passing below it is reported (crane/envelope.hpp).
struct GroundSurfaceSpec {
  double height = 0.0;       // m
  double stiffness = 0.0;    // N/m per contact
  double damping = 0.0;      // N·s/m per contact
  double smoothing = 0.005;  // m
  double friction = 0.5;
  double friction_speed = 0.05;  // m/s
  std::vector<GroundContactSpec> contacts;
  SourceLocation where;
};

/// The soil under a crane's supports: its modulus of subgrade reaction k_s (a pad of area A
/// settles by p/k_s under a pressure p: its spring is k_s·A) and the pressure it may carry.
struct SoilSpec {
  std::string soil_class;           // the named class the figures come from, or empty
  double subgrade_modulus = 0.0;    // N/m³
  double allowable_pressure = 0.0;  // Pa
};

/// An outrigger pad: a joint of the supported body (its pad's centre, on the ground) and the area
/// it bears on.
struct SupportPadSpec {
  std::string name, joint;
  double area = 0.0;  // m²
  SourceLocation where, where_joint;
};

/// A crawler track: the line of its ground contact from joint `from` to joint `to` of the
/// supported body, `width` wide, borne by `segments` equal stretches of bed.
struct SupportTrackSpec {
  std::string name, from, to;
  double width = 0.0;  // m
  int segments = 20;
  SourceLocation where, where_from, where_to;
};

/// A crane's lower carriage on the ground (`ground.supports`): a free body standing on pads and
/// tracks on an elastic bed (model/support_elements.hpp).
struct GroundSupportsSpec {
  std::string body;
  SoilSpec soil;
  double damping_ratio = 0.2;  // of each bed spring with its share of the crane's mass
  double shear_ratio = 0.8;    // horizontal over vertical stiffness of a support
  double friction = 0.5;       // μ between a support and the bed: steel on dry timber mats
  double smoothing = 0.1;      // the springs' smoothing band over the mean settlement
  std::vector<SupportPadSpec> pads;
  std::vector<SupportTrackSpec> tracks;
  SourceLocation where, where_body;
};

enum class Formulation { GGL, Baumgarte };

enum class StaticMethod { Newton, Relaxation };

enum class Integrator { Bdf, GeneralizedAlpha };

/// Absolute tolerances of the integrators' error test by kind of coordinate (a scalar `atol`
/// sets all four). Rotations, stretches and rope slopes are dimensionless and share `rotation`;
/// their rates share `angular_velocity`.
struct AbsoluteTolerance {
  double position = 1e-8;          // m
  double rotation = 1e-8;          // rad (and stretches, slopes)
  double velocity = 1e-8;          // m/s
  double angular_velocity = 1e-8;  // rad/s (and the rates of stretches and slopes)

  static AbsoluteTolerance uniform(double atol) { return {atol, atol, atol, atol}; }
  bool isUniform() const { return rotation == position && velocity == position && angular_velocity == position; }
};

struct SolverSpec {
  Formulation formulation = Formulation::GGL;
  double t_start = 0.0;
  double t_end = 1.0;
  double rtol = 1e-6;
  AbsoluteTolerance atol;
  /// Absolute tolerance (N, N·m) of the multipliers λ, μ in IDAS' Newton convergence test.
  /// They are excluded from the error test; a tight value stalls Newton at small steps,
  /// where round-off in index-2 multipliers grows like 1/h².
  double atol_multipliers = 1.0;
  /// IDAS' Newton convergence coefficient (IDASetNonlinConvCoef; IDAS' default is 0.33).
  /// 0.05 measured fewer steps and 5–10× smaller constraint residuals on the pendulum scenes.
  double newton_coefficient = 0.05;
  /// Include the work of drives and loads in the error test. Off by default: the integrand
  /// λ·Φ_t carries the multipliers' Newton-level noise, and controlling it costs many steps.
  bool work_error_control = false;
  /// `crane-sim run` stops at the first output sample outside the crane's envelope
  /// (crane/envelope_monitor.hpp) instead of reporting it at the end.
  bool stop_outside_envelope = false;
  double max_step = 0.0;  // 0: unlimited
  /// BDF only: the largest factor by which IDAS may grow the step after a successful one
  /// (IDASetEtaMax; IDAS' own bound is 2). 1.5 ends a chatter at order 1 in which every doubled
  /// step fails its error test (docs/numerics.md#step-growth).
  double max_step_growth = 1.5;
  /// IDAS' variable-order BDF, or the generalized-α method (solvers/generalized_alpha.hpp).
  Integrator integrator = Integrator::Bdf;
  int max_order = 5;  // BDF only
  /// Generalized-α only: the spectral radius at infinite frequency, 0 (BDF2-like, most high-
  /// frequency dissipation) … 1 (trapezoidal rule, none).
  double rho_inf = 0.8;
  /// Generalized-α only: steps of exactly this size (s; breakpoints and Newton failures may cut
  /// one), without the error test; 0: steps chosen by the error test.
  double fixed_step = 0.0;
  double initial_step = 0.0;  // 0: chosen by IDAS
  double baumgarte_alpha = 10.0;
  double baumgarte_beta = 1.0;
  /// The drawn state is assembled (closed onto the constraints by the least change of the
  /// coordinates); a joint moving farther than this fraction of the scene's size, or turning
  /// by more than this many radians, is a drawing error. Also the slack of a truss member's
  /// drawn length against its type's length.
  double assembly_tolerance = 1e-3;
  /// Start from the given state, or from the static equilibrium near it (thesis: every crane
  /// motion starts from equilibrium).
  bool start_from_equilibrium = false;
  /// How `crane-sim static` and `initial_state: equilibrium` find the equilibrium: Newton on
  /// the KKT system, or the thesis' damped dynamics (relaxation) followed by Newton.
  StaticMethod static_method = StaticMethod::Newton;
  double relaxation_damping = 1.0;     // α of the damping force α M dq, 1/s (≈ 2ω of the slowest mode)
  double relaxation_duration = 100.0;  // pseudo-time limit of the relaxation, s
};

/// A tipping line whose support moment every sample records (constraint_reaction.hpp:
/// supportMoment).
struct TippingLineSpec {
  std::string name;
  std::vector<std::string> supports;  // constraints joining the structure to the ground
  Vec3 from = Vec3::Zero(), to = Vec3::UnitX();
};

struct OutputSpec {
  double interval = 0.01;
  SourceLocation where{"output.interval", 0, 0};  // of the interval, for errors about the output's size
  /// Members whose beams' section forces are recorded (timoshenko members, trusses of fidelity
  /// members or beam).
  std::vector<std::string> section_forces;
  /// Constraints whose transmitted force and moment are recorded (constraint_reaction.hpp).
  std::vector<std::string> constraint_loads;
  std::vector<TippingLineSpec> tipping_lines;
};

struct Scene {
  std::string name;
  std::string path;
  std::string text;
  Vec3 gravity = Vec3(0.0, 0.0, -9.81);
  std::vector<JointSpec> ground_joints;
  std::optional<GroundSurfaceSpec> ground_surface;
  std::optional<GroundSupportsSpec> ground_supports;
  std::vector<RigidBodySpec> bodies;
  std::vector<TrussDescription> trusses;  // truss types, referenced by truss members
  std::vector<MemberSpec> members;
  std::vector<ConstraintSpec> constraints;
  std::vector<LoadSpec> loads;
  std::optional<WindSpec> wind;
  SolverSpec solver;
  OutputSpec output;
  SourceLocation where_solver;
  std::optional<FeedbackSpec> feedback;
  std::optional<CraneSpec> crane;
  std::optional<StatedEquilibrium> stated_equilibrium;  // a boom drawn where its equilibrium meets a figure
};

}  // namespace cranesim
