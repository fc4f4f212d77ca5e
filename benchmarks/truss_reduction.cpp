// bench_truss_reduction: the thesis' type 2 lattice section (8.2, Table D-3) as a full-member
// model, as one super truss element (3.5) and, for contrast, as one equivalent Timoshenko beam
// (benchmarks/README.md). Per fidelity:
//   - mass and the equivalent stiffness of 8.2.3: tip displacement / rotation of the cantilever
//     under an end force along the axis, across it (y, z) and an end torque about the axis
//     (gravity off, small loads: the linear range), and the static tip deflection under gravity;
//   - the equivalent mass of 8.2.3: the free truss under equal end forces and torques;
//   - the lowest eigenfrequencies about the undeformed state (gravity off);
//   - speed against error: the cantilever released under gravity (8.2.1), every rtol of the
//     list, tip z against the full-member model at --ref-rtol; wall time (median of --reps),
//     steps, Jacobians.
// Relative errors are against the full-member model, which makes none of the reduction's
// assumptions. One CSV row per (fidelity, quantity).

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "cranesim/model/truss_geometry.hpp"
#include "cranesim/solvers/modes.hpp"
#include "cranesim/solvers/statics.hpp"
#include "scene_fixtures.hpp"
#include "run_statistics.hpp"

namespace {

using namespace cranesim;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Options {
  std::string out = "benchmarks/results/truss_reduction.csv";
  std::vector<double> rtols{1e-4, 1e-6};
  double ref_rtol = 1e-8;
  double t_end = 1.0;
  double free_t_end = 0.5;  // the free truss under equal end loads (equivalent mass)
  int reps = 3;
};

std::vector<double> parseList(const std::string& text) {
  std::vector<double> out;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = text.find(',', start);
    out.push_back(std::stod(text.substr(start, comma - start)));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

using cranesim_bench::median;

/// The type 2 section as one Timoshenko beam of `segments` elements with the truss' equivalent
/// section: chords by the parallel-axis theorem, the lacing faces as shear webs (Bredt for the
/// torsion of the closed lattice box), the density chosen so that the mass is the truss'.
/// Assumes four chords on a rectangle with one diagonal per bay and face (type1), as type 2.
Scene equivalentBeam(const Scene& truss_scene, int segments) {
  const TrussDescription& d = truss_scene.trusses.at(0);
  const TrussGeometry g = buildTrussGeometry(d);
  const double E = g.material.youngs_modulus, G = g.material.shear_modulus, L = g.length;
  const Section& chord = g.members.front().section;  // the members start with the main beams
  double area = 0.0, Iy = 0.0, Iz = 0.0;
  for (const auto& c : g.chords) {
    const Vec3 p = g.nodes[c[0]].position;
    area += chord.area;
    Iy += chord.area * p.z() * p.z() + chord.Iy;
    Iz += chord.area * p.y() * p.y() + chord.Iz;
  }
  // One diagonal per bay (type1): a face of width b, bay a, diagonal d carries shear with
  // stiffness S = E A_d a b² / d³, i.e. G t = E A_d a b / d³ per unit width.
  Section lacing;
  for (const TrussMember& m : g.members)
    if (m.role == TrussMemberRole::Sub) lacing = m.section;
  // Bay length, and the height (z) and width (y) of the chords' rectangle in section 1.
  Eigen::Vector2d low(1e300, 1e300), high(-1e300, -1e300);
  for (const auto& c : g.chords) {
    const Eigen::Vector2d yz = g.nodes[c[0]].position.tail<2>();
    low = low.cwiseMin(yz), high = high.cwiseMax(yz);
  }
  const double a = L / d.order, w = high(0) - low(0), h = high(1) - low(1);
  const auto faceShear = [&](double b) { return E * lacing.area * a * b * b / std::pow(std::hypot(a, b), 3); };
  const double shear_z = 2.0 * faceShear(h);
  const double Gt_side = faceShear(h) / h, Gt_top = faceShear(w) / w;
  const double GJ = 4.0 * std::pow(w * h, 2) / (2.0 * h / Gt_side + 2.0 * w / Gt_top);
  double mass = 0.0;
  for (const TrussMember& t : g.members)
    mass += g.material.density * t.section.area * (g.nodes[t.node2].position - g.nodes[t.node1].position).norm();

  Scene scene = truss_scene;
  scene.trusses.clear();
  MemberSpec& m = scene.members.at(0);
  m.type = MemberType::Timoshenko;
  m.truss.clear();
  m.segments = segments;
  m.section.area = area;
  m.section.Iy = Iy;
  m.section.Iz = Iz;
  m.section.J = GJ / G;
  m.section.shear_factor = shear_z / (G * area);
  m.material = g.material;
  m.material.density = mass / (area * L);
  return scene;
}

struct Fidelity {
  std::string name;
  Scene scene;
};

struct Csv {
  std::ofstream file;
  explicit Csv(const std::string& path) : file(path) {
    file << "fidelity,quantity,rtol,value,relative_error,wall_time_s_median,steps,jacobians,speedup\n";
  }
  void row(const std::string& fidelity, const std::string& quantity, double rtol, double value, double reference,
           double wall = kNaN, long steps = -1, long jacobians = -1, double speedup = kNaN) {
    const auto num = [](double x) { return std::isnan(x) ? std::string("nan") : fmt::format("{:.7g}", x); };
    file << fidelity << ',' << quantity << ',' << num(rtol) << ',' << num(value) << ','
         << num(std::isnan(reference) ? kNaN : value / reference - 1.0) << ',' << num(wall) << ',' << steps << ','
         << jacobians << ',' << num(speedup) << '\n';
    fmt::print("{:<13} {:<28} {:>8} {:>14.6g}  rel.err {:>9}  wall {:>9}  steps {:>6}  jac {:>5}  speed-up {}\n", fidelity,
               quantity, num(rtol), value, std::isnan(reference) ? std::string("-") : fmt::format("{:+.2f} %", 100.0 * (value / reference - 1.0)),
               num(wall), steps, jacobians, num(speedup));
    std::fflush(stdout);
  }
};

struct Released {
  std::vector<double> time, tip_z;
  double wall = kNaN;
  long steps = 0, jacobians = 0;
};

Released release(Scene scene, double rtol, double t_end, int reps) {
  scene.solver.rtol = rtol;
  scene.solver.atol = AbsoluteTolerance::uniform(rtol * 1e-2);
  scene.solver.t_end = t_end;
  scene.output.interval = 0.01;
  Released r;
  std::vector<double> walls;
  for (int k = 0; k < reps; ++k) {
    const auto start = std::chrono::steady_clock::now();
    const test::SimulationRun run(scene);
    walls.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (!run.outcome.complete) throw std::runtime_error("released cantilever failed: " + run.outcome.message);
    r.time = run.recorder.time();
    const auto& p = run.jointPositions("boom.end");
    r.tip_z.clear();
    for (std::size_t s = 0; s < r.time.size(); ++s) r.tip_z.push_back(p[3 * s + 2]);
    r.steps = run.outcome.statistics.steps;
    r.jacobians = run.outcome.statistics.jacobian_evaluations;
  }
  r.wall = median(walls);
  return r;
}

/// 8.2.3 equivalent mass: the truss set free (no constraint, no gravity) under the same force or
/// torque on both end sections for `t_end` (0.5 s: 4.5 periods of the first bending mode). The
/// mean motion of the two end sections, fitted by ½ a t² (least squares, which averages the
/// vibrations the loads excite), gives the mass 2F / a or the inertia 2T / α about the centre
/// (8-9). Torsion is read from the turn of end-section node 1 about the axis, so it needs a truss
/// (NaN for the beam).
double freeEquivalentMass(Scene scene, const Vec3& force, const Vec3& torque, double t_end) {
  scene.constraints.clear();
  scene.gravity = Vec3::Zero();
  for (const char* joint : {"boom.start", "boom.end"}) {
    LoadSpec load;
    load.name = joint;
    load.joint = joint;
    load.force = force;
    load.torque = torque;
    scene.loads.push_back(load);
  }
  scene.solver.rtol = 1e-6;
  scene.solver.atol = AbsoluteTolerance::uniform(1e-8);
  scene.solver.t_end = t_end;
  scene.output.interval = t_end / 100.0;
  const bool spin = torque.x() != 0.0;
  if (spin && compileModel(scene).findJoint("boom.s1n1") < 0) return kNaN;
  const test::SimulationRun run(scene);
  if (!run.outcome.complete) throw std::runtime_error("free truss failed: " + run.outcome.message);
  const auto& a = run.jointPositions("boom.start");
  const auto& b = run.jointPositions("boom.end");
  const auto position = [](const std::vector<double>& p, std::size_t s) { return Vec3(p[3 * s], p[3 * s + 1], p[3 * s + 2]); };
  const auto measure = [&](std::size_t s) {  // the coordinate whose second derivative is fitted
    const Vec3 ra = position(a, s), rb = position(b, s);
    if (torque.y() != 0.0) return std::atan2(-(rb - ra).z(), (rb - ra).x());
    if (spin) {
      double angle = 0.0;
      for (const char* node : {"boom.s1n1", "boom.s2n1"}) {
        const Vec3 p = position(run.jointPositions(node), s) - (node[6] == '1' ? ra : rb);
        angle += 0.5 * std::atan2(p.z(), p.y());
      }
      return angle;
    }
    return 0.5 * (ra + rb).dot(force.normalized());
  };
  double num = 0.0, den = 0.0;
  const std::vector<double>& t = run.recorder.time();
  for (std::size_t s = 0; s < t.size(); ++s) {
    const double basis = 0.5 * t[s] * t[s];
    num += basis * (measure(s) - measure(0));
    den += basis * basis;
  }
  const double load = force.norm() + torque.norm();
  return 2.0 * load / (num / den);
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--out") o.out = value();
    else if (arg == "--rtols") o.rtols = parseList(value());
    else if (arg == "--ref-rtol") o.ref_rtol = std::stod(value());
    else if (arg == "--t-end") o.t_end = std::stod(value());
    else if (arg == "--reps") o.reps = std::stoi(value());
    else if (arg == "--quick") o.rtols = {1e-4}, o.ref_rtol = 1e-5, o.t_end = 0.1, o.free_t_end = 0.05, o.reps = 1;
    else if (arg == "--help" || arg == "-h") {
      fmt::print("bench_truss_reduction [--out CSV] [--rtols 1e-4,1e-6] [--ref-rtol 1e-8] [--t-end 1] [--reps 3] [--quick]\n");
      return 0;
    } else {
      fmt::print(stderr, "unknown option {}\n", arg);
      return 2;
    }
  }

  const Scene members = test::loadScene("truss_type2_cantilever.yaml");
  const std::vector<Fidelity> fidelities = {
      {"members", members},
      {"super_truss", test::loadScene("truss_type2_super.yaml")},
      {"condensed", test::loadScene("truss_type2_condensed.yaml")},
      {"beam", equivalentBeam(members, 6)}};
  Csv csv(o.out);
  std::map<std::string, double> reference;  // the full-member model's value of each quantity
  const auto record = [&](const std::string& fidelity, const std::string& quantity, double value) {
    if (fidelity == "members") reference[quantity] = value;
    csv.row(fidelity, quantity, kNaN, value, fidelity == "members" ? kNaN : reference.at(quantity));
  };

  // 8.2.3: equivalent stiffness from end loads in the linear range, and the mass.
  struct EndLoad {
    std::string name;
    Vec3 force, torque;
    int component;  // 0–2 displacement, 3–5 rotation
  };
  const std::vector<EndLoad> loads = {{"axial_stiffness_N_per_m", Vec3(1e5, 0, 0), Vec3::Zero(), 0},
                                      {"lateral_stiffness_y_N_per_m", Vec3(0, 1e4, 0), Vec3::Zero(), 1},
                                      {"lateral_stiffness_z_N_per_m", Vec3(0, 0, 1e4), Vec3::Zero(), 2},
                                      {"torsion_stiffness_Nm_per_rad", Vec3::Zero(), Vec3(1e5, 0, 0), 3}};
  for (const Fidelity& f : fidelities) {
    const Model model = compileModel(f.scene);
    const Assembler assembler(model);
    VecX v = VecX::Zero(model.nv);
    for (const Node& n : model.nodes) v(n.v) = 1.0;
    record(f.name, "mass_kg", 2.0 * assembler.kineticEnergy(0.0, model.q0.data(), v.data()));
    // Equivalent mass (8.2.3): rotary inertia about the axis and about the transverse axes
    // through the clamped end, from 2T of a unit rigid rotation (node rotations are zero in q0,
    // so the body-frame angular velocity of every node is the rotation's own).
    for (int axis = 0; axis < 3; ++axis) {
      const Vec3 omega = Vec3::Unit(axis);
      VecX w = VecX::Zero(model.nv);
      for (std::size_t n = 0; n < model.nodes.size(); ++n) {
        const Node& node = model.nodes[n];
        w.segment<3>(node.v) = omega.cross(Vec3(model.q0.segment<3>(node.q)));
        if (node.hasRotation()) w.segment<3>(node.v + 3) = omega;
      }
      record(f.name, fmt::format("inertia_{}_kgm2", "xyz"[axis]), 2.0 * assembler.kineticEnergy(0.0, model.q0.data(), w.data()));
    }
    record(f.name, "coordinates", model.nv);
    const StaticResult gravity = solveStatics(model, model.q0, 0.0);
    if (!gravity.converged) throw std::runtime_error(f.name + ": " + gravity.message);
    record(f.name, "gravity_tip_z_m", test::jointOffset(model, gravity.q, "boom.end").z());
    for (const EndLoad& load : loads) {
      const Model loaded = compileModel(test::withEndLoad(f.scene, load.force, load.torque));
      const StaticResult eq = solveStatics(loaded, loaded.q0, 0.0);
      if (!eq.converged) throw std::runtime_error(f.name + " " + load.name + ": " + eq.message);
      const double response = load.component < 3 ? test::jointOffset(loaded, eq.q, "boom.end")(load.component) : test::jointTurn(loaded, eq.q, "boom.end")(load.component - 3);
      const double magnitude = load.component < 3 ? load.force(load.component) : load.torque(load.component - 3);
      record(f.name, load.name, magnitude / response);
      if (load.component == 3) record(f.name, "torsion_axial_coupling_m_per_rad", test::jointOffset(loaded, eq.q, "boom.end").x() / response);
    }
    record(f.name, "free_mass_x_kg", freeEquivalentMass(f.scene, Vec3(1e5, 0, 0), Vec3::Zero(), o.free_t_end));
    record(f.name, "free_mass_y_kg", freeEquivalentMass(f.scene, Vec3(0, 1e5, 0), Vec3::Zero(), o.free_t_end));
    record(f.name, "free_inertia_x_kgm2", freeEquivalentMass(f.scene, Vec3::Zero(), Vec3(1e5, 0, 0), o.free_t_end));
    record(f.name, "free_inertia_y_centre_kgm2", freeEquivalentMass(f.scene, Vec3::Zero(), Vec3(0, 1e5, 0), o.free_t_end));
    Scene unloaded = f.scene;
    unloaded.gravity = Vec3::Zero();
    const Model free_model = compileModel(unloaded);
    const ModalResult modes = computeModes(free_model, free_model.q0, 0.0, 4);
    for (int k = 0; k < modes.frequencies.size(); ++k) record(f.name, fmt::format("frequency_{}_Hz", k + 1), modes.frequencies(k));
  }

  // 8.2.1 released under gravity: speed against error.
  const Released ref = release(members, o.ref_rtol, o.t_end, 1);
  std::map<double, double> member_wall;
  for (const Fidelity& f : fidelities)
    for (const double rtol : o.rtols) {
      const Released r = release(f.scene, rtol, o.t_end, o.reps);
      double error = 0.0, peak = 0.0;
      for (std::size_t s = 0; s < std::min(r.tip_z.size(), ref.tip_z.size()); ++s) {
        error = std::max(error, std::abs(r.tip_z[s] - ref.tip_z[s]));
        peak = std::max(peak, std::abs(ref.tip_z[s]));
      }
      if (f.name == "members") member_wall[rtol] = r.wall;
      csv.row(f.name, "released_tip_z_max_error_m", rtol, error, kNaN, r.wall, r.steps, r.jacobians, member_wall.at(rtol) / r.wall);
      csv.row(f.name, "released_tip_z_error_rel_peak", rtol, error / peak, kNaN, r.wall, r.steps, r.jacobians, member_wall.at(rtol) / r.wall);
    }
  fmt::print("written {}\n", o.out);
  return 0;
}
