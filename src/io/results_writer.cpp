#include "cranesim/io/results_writer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>

#include "cranesim/assembly/constraint_reaction.hpp"
#include "cranesim/model/reeved_rope.hpp"
#include "cranesim/model/wind_elements.hpp"
#include "cranesim/solvers/scene_equilibrium.hpp"
#include "cranesim/version.hpp"
#include "hdf5_file.hpp"

namespace cranesim {
namespace {

/// What a tipping moment's sign means, stored with each one (the line is directed, right hand).
constexpr const char* kTippingMomentSign =
    "> 0: the supports hold the structure on its footprint (the stability margin about the line); "
    "<= 0: it tips over the line";

void append(std::vector<double>& out, const double* data, int n) { out.insert(out.end(), data, data + n); }

/// Row-major copy of a rotation matrix, so that h5py reads R[i, j] as Eigen's R(i, j).
void appendRowMajor(std::vector<double>& out, const Mat3& R) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out.push_back(R(i, j));
}

/// /constraint_loads/<name>: force and moment (N × 3 each, constraint_reaction.hpp) with their
/// peaks and the dynamic factor (peak force over the first sample's: φ2 of EN 13001-2 for a run
/// that starts from its equilibrium).
void writeConstraintLoads(Hdf5File& file, const Constraint& c, const std::vector<double>& loads) {
  const std::size_t N = loads.size() / 6;
  std::vector<double> force(3 * N), moment(3 * N);
  double peak_force = 0.0, peak_moment = 0.0;
  for (std::size_t s = 0; s < N; ++s) {
    const Eigen::Map<const Vec3> f(&loads[6 * s]), m(&loads[6 * s + 3]);
    std::copy(f.data(), f.data() + 3, &force[3 * s]);
    std::copy(m.data(), m.data() + 3, &moment[3 * s]);
    peak_force = std::max(peak_force, f.norm());
    peak_moment = std::max(peak_moment, m.norm());
  }
  const std::string path = "/constraint_loads/" + c.name;
  file.writeDoubles(path + "/force", {N, 3}, force.data());
  file.writeDoubles(path + "/moment", {N, 3}, moment.data());
  const double first = N > 0 ? Eigen::Map<const Vec3>(loads.data()).norm() : 0.0;
  file.attribute(path, "peak_force", peak_force);
  file.attribute(path, "peak_moment", peak_moment);
  file.attribute(path, "dynamic_factor", first > 0.0 ? peak_force / first : std::numeric_limits<double>::quiet_NaN());
  file.attribute(path, "axes", "the first joint's, moment about the second joint's origin, on the second joint's side");
}

/// `/crane`: the boom's figures as attributes, `/crane/ropes/<rope>` each rope's end tensions.
void writeCraneFigures(Hdf5File& file, const CraneFigures& crane) {
  file.ensureGroup("/crane");
  if (const auto& boom = crane.boom) {
    file.attribute("/crane", "boom_angle_deg", boom->boom_angle_deg);
    file.attribute("/crane", "head_height", boom->head_height);
    file.attribute("/crane", "hook_radius", boom->hook_radius);
    file.attribute("/crane", "hook_height", boom->hook_height);
    if (boom->load_radius) file.attribute("/crane", "load_radius", *boom->load_radius);
    if (boom->load_height) file.attribute("/crane", "load_height", *boom->load_height);
  }
  for (const RopeTension& rope : crane.ropes) {
    const std::string path = "/crane/ropes/" + rope.rope;
    file.ensureGroup(path);
    file.attribute(path, "tension_start", rope.at_start);
    file.attribute(path, "tension_end", rope.at_end);
  }
}

/// /envelope: the series the envelope is judged by, and its events (crane/envelope_monitor.hpp).
void writeEnvelope(Hdf5File& file, const Model& model, const EnvelopeMonitor& envelope) {
  const hsize_t N = envelope.time().size();
  file.ensureGroup("/envelope");
  const std::vector<EnvelopeEvent> events = envelope.events();
  file.attribute("/envelope", "left_envelope", static_cast<long>(leavesEnvelope(events)));
  if (const auto& boom = model.envelope.boom) {
    file.writeDoubles("/envelope/boom_angle", {N}, envelope.boomAngle().data());
    file.attribute("/envelope/boom_angle", "limit_deg", boom->limit_deg);
    if (boom->backstop_element >= 0) {
      file.writeDoubles("/envelope/backstop_moment", {N}, envelope.backstopMoment().data());
      file.attribute("/envelope/backstop_moment", "angle_deg", boom->backstop_angle_deg);
      file.writeDoubles("/envelope/backstop_compression", {N}, envelope.backstopCompression().data());
    }
  }
  for (std::size_t r = 0; r < envelope.ropeTensions().size(); ++r) {
    const std::string path = "/envelope/rope_tension/" + envelope.ropeTensions()[r].name;
    file.writeDoubles(path, {N}, envelope.ropeTensions()[r].values.data());
    file.attribute(path, "breaking_force", model.envelope.ropes[r].breaking_force);
  }
  for (const EnvelopeSeries& s : envelope.lowestPoints()) file.writeDoubles("/envelope/lowest_point/" + s.name, {N}, s.values.data());
  if (model.envelope.ground_height) file.attribute("/envelope", "ground_height", *model.envelope.ground_height);
  for (const EnvelopeSeries& s : envelope.contactForces()) file.writeDoubles("/envelope/ground_force/" + s.name, {N}, s.values.data());
  for (const EnvelopeSeries& s : envelope.contactDepths()) file.writeDoubles("/envelope/ground_penetration/" + s.name, {N}, s.values.data());
  for (std::size_t k = 0; k < events.size(); ++k) {
    const EnvelopeEvent& e = events[k];
    const std::string path = fmt::format("/envelope/events/{}", k);
    file.ensureGroup(path);
    file.attribute(path, "what", e.what);
    file.attribute(path, "part", e.part);
    file.attribute(path, "leaves_envelope", static_cast<long>(e.leaves_envelope));
    file.attribute(path, "first_time", e.first_time);
    file.attribute(path, "peak_time", e.peak_time);
    file.attribute(path, "peak", e.peak);
    file.attribute(path, "limit", e.limit);
    file.attribute(path, "unit", e.unit);
    if (!e.depth_unit.empty()) file.attribute(path, "depth", e.depth), file.attribute(path, "depth_unit", e.depth_unit);
    if (!e.why.empty()) file.attribute(path, "why", e.why);
  }
}

/// /supports: what each pad and track carries, and the carriage's stability, per sample
/// (crane/support_reading.hpp).
/// Each support's anchor (model/anchored_support_element.hpp): `column(k)` gives coordinate k of
/// the state per sample.
void writeSupports(Hdf5File& file, const Model& model, const EnvelopeSupports& supports, const EnvelopeMonitor& envelope,
                   const std::function<std::vector<double>(int)>& column) {
  const std::vector<SupportReading>& readings = envelope.supports();
  const hsize_t N = readings.size();
  const auto write = [&](const std::string& path, const auto& value) {
    std::vector<double> values;
    for (const SupportReading& r : readings) values.push_back(value(r));
    file.writeDoubles(path, {N}, values.data());
  };
  const auto writeSlide = [&](const std::string& path, const EnvelopeSupport& support) {
    if (support.anchor < 0) return;
    std::vector<std::vector<double>> coordinates;
    for (int k = 0; k < 3; ++k) coordinates.push_back(column(model.nodes[static_cast<std::size_t>(support.anchor)].q + k));
    std::vector<double> slide;
    for (hsize_t i = 0; i < N; ++i)
      for (int k = 0; k < 3; ++k) slide.push_back(coordinates[static_cast<std::size_t>(k)][i]);
    file.writeDoubles(path + "/slide", {N, 3}, slide.data());
  };
  file.ensureGroup("/supports");
  file.attribute("/supports", "body", supports.body);
  file.attribute("/supports", "allowable_pressure", supports.allowable_pressure);
  for (std::size_t p = 0; p < supports.pads.size(); ++p) {
    const std::string path = "/supports/pads/" + supports.pads[p].name;
    file.ensureGroup(path);
    file.attribute(path, "area", supports.pads[p].bearing_area);
    write(path + "/force", [&](const SupportReading& r) { return r.pads[p].force; });
    write(path + "/pressure", [&](const SupportReading& r) { return r.pads[p].pressure; });
    writeSlide(path, supports.pads[p]);
  }
  for (std::size_t t = 0; t < supports.tracks.size(); ++t) {
    const EnvelopeSupport& track = supports.tracks[t];
    const std::string path = "/supports/tracks/" + track.name;
    file.ensureGroup(path);
    file.attribute(path, "length", track.length);
    write(path + "/force", [&](const SupportReading& r) { return r.tracks[t].force; });
    write(path + "/peak_pressure", [&](const SupportReading& r) { return r.tracks[t].peak_pressure; });
    write(path + "/peak_at", [&](const SupportReading& r) { return r.tracks[t].peak_at; });
    write(path + "/contact_length", [&](const SupportReading& r) { return r.tracks[t].contact_length; });
    writeSlide(path, track);
  }
  file.writeDoubles("/supports/tipped", {N}, envelope.tipped().data());
  std::vector<double> resultant, line;
  for (const SupportReading& r : readings) {
    resultant.insert(resultant.end(), {r.resultant.x(), r.resultant.y()});
    line.insert(line.end(), {r.tipping.from.x(), r.tipping.from.y(), r.tipping.to.x(), r.tipping.to.y()});
  }
  file.writeDoubles("/supports/resultant", {N, 2}, resultant.data());
  file.writeDoubles("/supports/tipping_line", {N, 4}, line.data());
  write("/supports/carried", [](const SupportReading& r) { return r.carried; });
  write("/supports/margin", [](const SupportReading& r) { return r.tipping.margin; });
}

}  // namespace

ResultsRecorder::ResultsRecorder(const Assembler& assembler)
    : assembler_(assembler),
      body_position_(assembler.model().nodes.size()),
      body_rotation_(assembler.model().nodes.size()),
      body_velocity_(assembler.model().nodes.size()),
      body_omega_(assembler.model().nodes.size()),
      joint_position_(assembler.model().joints.size()),
      joint_rotation_(assembler.model().joints.size()),
      section_forces_(assembler.model().section_force_groups.size()),
      wind_forces_(assembler.model().wind_parts.size()),
      part_tensions_(assembler.model().reeved_ropes.size()),
      envelope_(assembler.model()) {
  const Model& model = assembler.model();
  for (const std::string& name : model.output.constraint_loads) load_constraints_.push_back(model.findConstraint(name));
  constraint_loads_.resize(load_constraints_.size());
  for (const TippingLineSpec& line : model.output.tipping_lines) {
    std::vector<int> supports;
    for (const std::string& name : line.supports) supports.push_back(model.findConstraint(name));
    tipping_supports_.push_back(std::move(supports));
  }
  tipping_moments_.resize(tipping_supports_.size());
}

void ResultsRecorder::keepBefore(double t) {
  const std::size_t recorded = time_.size();
  const std::size_t kept = static_cast<std::size_t>(std::lower_bound(time_.begin(), time_.end(), t) - time_.begin());
  if (kept == recorded) return;
  const auto keep = [&](std::vector<double>& series) { series.resize(series.size() / recorded * kept); };
  for (auto* group : {&body_position_, &body_rotation_, &body_velocity_, &body_omega_, &joint_position_, &joint_rotation_,
                      &section_forces_, &constraint_loads_, &tipping_moments_, &wind_forces_, &part_tensions_})
    for (std::vector<double>& series : *group) keep(series);
  for (auto* series : {&time_, &state_, &kinetic_, &potential_, &drive_work_, &load_work_, &winch_work_, &dissipated_,
                       &balance_, &residual_position_, &residual_velocity_})
    keep(*series);
  envelope_.keep(kept);
}

DynamicState ResultsRecorder::motionAt(double t, const double* y, const ConstraintState& constraints,
                                       const Eigen::SparseMatrix<double>& mass) const {
  const Model& model = assembler_.model();
  DynamicState s;
  s.t = t;
  s.q = Eigen::Map<const VecX>(y, model.nq);
  s.v = Eigen::Map<const VecX>(y + assembler_.vOffset(), model.nv);
  try {
    accelerations_.solve(assembler_, s, constraints, mass, Limit::Left);
  } catch (const std::exception&) {
    s.lambda = Eigen::Map<const VecX>(y + assembler_.lambdaOffset(), model.m);
    s.a = VecX::Constant(model.nv, std::numeric_limits<double>::quiet_NaN());
  }
  return s;
}

void ResultsRecorder::sample(double t, const double* y, const WorkTerms& work) {
  const Model& model = assembler_.model();
  const double* q = y;
  const double* v = y + assembler_.vOffset();
  const ConstraintState C = assembler_.constraints(t, q, v);
  const Eigen::SparseMatrix<double> M = assembler_.massMatrix(t, q);  // for λ and T = ½ dqᵀ M dq
  time_.push_back(t);
  append(state_, y, model.nq + model.nv);
  const DynamicState motion = motionAt(t, y, C, M);
  append(state_, motion.lambda.data(), model.m);
  for (std::size_t n = 0; n < model.nodes.size(); ++n) {
    if (!model.nodes[n].member.empty()) continue;  // drawn by model.drawing_lines, not written
    const Frame f = model.nodeFrame(q, static_cast<int>(n));
    append(body_position_[n], f.r.data(), 3);
    appendRowMajor(body_rotation_[n], f.R);
    append(body_velocity_[n], v + model.nodes[n].v, 3);
    append(body_omega_[n], v + model.nodes[n].v + 3, 3);
  }
  for (std::size_t j = 0; j < model.joints.size(); ++j) {
    const Frame f = model.jointFrame(q, static_cast<int>(j));
    append(joint_position_[j], f.r.data(), 3);
    appendRowMajor(joint_rotation_[j], f.R);
  }
  const Eigen::Map<const VecX> dq(v, model.nv);
  const double T = 0.5 * dq.dot(M * dq), V = assembler_.potentialEnergy(t, q);
  kinetic_.push_back(T);
  potential_.push_back(V);
  drive_work_.push_back(work.drive);
  load_work_.push_back(work.load);
  winch_work_.push_back(work.winch);
  dissipated_.push_back(work.dissipated);
  balance_.push_back(T + V - work.drive - work.load - work.winch + work.dissipated);
  const ElementInput in{q, v, motion.a.data(), t, model.gravity};
  for (std::size_t g = 0; g < model.section_force_groups.size(); ++g)
    for (const int e : model.section_force_groups[g].elements) {
      double forces[std::max(12, kTensionPoints)];
      if (model.section_force_groups[g].rope) {
        model.elements[e]->tensions(in, forces);
        append(section_forces_[g], forces, kTensionPoints);
      } else {
        model.elements[e]->sectionForces(in, forces);
        append(section_forces_[g], forces, 12);
      }
    }
  for (std::size_t p = 0; p < model.wind_parts.size(); ++p) {
    Vec3 force = Vec3::Zero();
    for (const int e : model.wind_parts[p].elements) force += dynamic_cast<const WindElement&>(*model.elements[e]).resultantForce(in);
    append(wind_forces_[p], force.data(), 3);
  }
  for (std::size_t r = 0; r < model.reeved_ropes.size(); ++r) {
    const ReevedRope& rope = reevedRope(model, static_cast<int>(r));
    double tensions[ReevedRope::kMaxParts];
    rope.partTensions(in, tensions);
    append(part_tensions_[r], tensions, rope.parts());
  }
  for (std::size_t k = 0; k < load_constraints_.size(); ++k) {
    const ConstraintReaction load = constraintReaction(model, model.constraints[load_constraints_[k]], C.G, q, motion.lambda.data());
    append(constraint_loads_[k], load.force.data(), 3);
    append(constraint_loads_[k], load.moment.data(), 3);
  }
  for (std::size_t k = 0; k < tipping_supports_.size(); ++k) {
    const TippingLineSpec& line = model.output.tipping_lines[k];
    tipping_moments_[k].push_back(supportMoment(model, tipping_supports_[k], line.from, line.to, C.G, q, motion.lambda.data()));
  }
  envelope_.sample(t, q, v);
  if (model.m > 0) {
    residual_position_.push_back(C.phi.cwiseAbs().maxCoeff());
    residual_velocity_.push_back(C.phi_dot.cwiseAbs().maxCoeff());
  } else {
    residual_position_.push_back(0.0);
    residual_velocity_.push_back(0.0);
  }
}

double ResultsRecorder::energyScale() const {
  double scale = 0.0;
  for (std::size_t s = 0; s < time_.size(); ++s)
    scale = std::max(scale, kinetic_[s] + std::abs(potential_[s] - potential_.front()) + std::abs(drive_work_[s]) +
                                std::abs(load_work_[s]) + std::abs(winch_work_[s]) + dissipated_[s]);
  return scale;
}

double ResultsRecorder::relativeBalanceDrift() const {
  double drift = 0.0;
  for (const double b : balance_) drift = std::max(drift, std::abs(b - balance_.front()));
  const double scale = energyScale();
  return scale > 0.0 ? drift / scale : 0.0;
}

double ResultsRecorder::estimatedBytes(const Model& model, double samples) {
  // Per sample: the state and multipliers, every node's position, rotation, velocity and angular
  // velocity, every joint's position and rotation, time, energies and residuals (10 numbers),
  // the recorded section forces and wind forces; twice: recorded, then the file's image.
  double section_forces = 0.0;
  for (const Model::SectionForceGroup& g : model.section_force_groups) section_forces += (g.rope ? kTensionPoints : 12.0) * g.elements.size();
  for (const int e : model.reeved_ropes) section_forces += static_cast<double>(model.elements[e]->size());  // ≥ its parts
  const double per_sample = 8.0 * (model.nq + model.nv + model.m + 18.0 * model.nodes.size() + 12.0 * model.joints.size() + 10.0 +
                                   section_forces + 6.0 * model.output.constraint_loads.size() +
                                   static_cast<double>(model.output.tipping_lines.size()) + 3.0 * model.wind_parts.size());
  return 2.0 * per_sample * samples;
}

std::vector<double> ResultsRecorder::stateColumn(int k) const {
  const Model& model = assembler_.model();
  const int width = model.nq + model.nv + model.m;
  std::vector<double> out(time_.size());
  for (std::size_t s = 0; s < time_.size(); ++s) out[s] = state_[s * width + k];
  return out;
}

void ResultsRecorder::writeCheckpoint(const std::string& path, const Metadata& meta, double wall_time_s) const {
  SimulationOutcome checkpoint;
  checkpoint.t_reached = time_.empty() ? 0.0 : time_.back();
  checkpoint.message = fmt::format("checkpoint at t = {:.6g} s, {:.3g} s into the run: the run was still going when "
                                   "this was written (solver statistics not recorded)", checkpoint.t_reached, wall_time_s);
  checkpoint.statistics.wall_time_s = wall_time_s;
  write(path, meta, checkpoint);
}

void ResultsRecorder::write(const std::string& path, const Metadata& meta, const SimulationOutcome& outcome) const {
  const Model& model = assembler_.model();
  writeResultsFile(path, [&](Hdf5File& file) {
    const hsize_t N = time_.size();
    const int width = model.nq + model.nv + model.m;
    file.attribute("/", "engine_version", std::string(kVersion));
    file.attribute("/", "scene_path", meta.scene_path);
    file.attribute("/", "scene_text", meta.scene_text);
    file.attribute("/", "status", std::string(outcome.complete ? "complete" : "incomplete"));
    file.attribute("/", "message", outcome.message);
    file.attribute("/", "formulation", meta.formulation);
    file.attribute("/", "t_end_requested", meta.t_end_requested);
    file.attribute("/", "t_reached", outcome.t_reached);

    file.writeDoubles("/time", {N}, time_.data());
    std::vector<double> q, v, lambda;
    for (std::size_t s = 0; s < N; ++s) {
      const double* row = state_.data() + s * width;
      append(q, row, model.nq);
      append(v, row + model.nq, model.nv);
      append(lambda, row + model.nq + model.nv, model.m);
    }
    file.writeDoubles("/q", {N, hsize_t(model.nq)}, q.data());
    file.writeDoubles("/v", {N, hsize_t(model.nv)}, v.data());
    file.writeDoubles("/lambda", {N, hsize_t(model.m)}, lambda.data());

    std::vector<std::string> bodies, joints, rows, constraints, constraint_joints, member_segments;
    for (std::size_t n = 0; n < model.nodes.size(); ++n) {
      const Node& node = model.nodes[n];
      if (!node.member.empty()) continue;  // drawn by model.drawing_lines
      const std::string g = "/bodies/" + node.name;
      bodies.push_back(node.name);
      file.writeDoubles(g + "/position", {N, 3}, body_position_[n].data());
      file.writeDoubles(g + "/rotation", {N, 3, 3}, body_rotation_[n].data());
      file.writeDoubles(g + "/velocity", {N, 3}, body_velocity_[n].data());
      file.writeDoubles(g + "/angular_velocity", {N, 3}, body_omega_[n].data());
    }
    for (std::size_t j = 0; j < model.joints.size(); ++j) {
      const std::string g = "/joints/" + model.joints[j].name;
      joints.push_back(model.joints[j].name);
      file.writeDoubles(g + "/position", {N, 3}, joint_position_[j].data());
      file.writeDoubles(g + "/rotation", {N, 3, 3}, joint_rotation_[j].data());
    }
    for (const Constraint& c : model.constraints) {
      constraints.push_back(c.name);
      constraint_joints.push_back(model.joints[c.joint1].name);
      constraint_joints.push_back(model.joints[c.joint2].name);
      rows.insert(rows.end(), c.row_labels.begin(), c.row_labels.end());
    }
    file.writeStrings("/model/bodies", {bodies.size()}, bodies);
    file.writeStrings("/model/joints", {joints.size()}, joints);
    file.writeStrings("/model/constraints", {constraints.size()}, constraints);
    file.writeStrings("/model/constraint_joints", {constraints.size(), 2}, constraint_joints);
    file.writeStrings("/model/constraint_rows", {rows.size()}, rows);
    for (const auto& line : model.drawing_lines)
      for (const int j : line) member_segments.push_back(model.joints[j].name);
    file.writeStrings("/model/member_segments", {member_segments.size() / 2, 2}, member_segments);

    file.writeDoubles("/energy/kinetic", {N}, kinetic_.data());
    file.writeDoubles("/energy/potential", {N}, potential_.data());
    file.writeDoubles("/energy/drive_work", {N}, drive_work_.data());
    file.writeDoubles("/energy/load_work", {N}, load_work_.data());
    file.writeDoubles("/energy/winch_work", {N}, winch_work_.data());
    file.writeDoubles("/energy/dissipated", {N}, dissipated_.data());
    file.writeDoubles("/energy/balance", {N}, balance_.data());
    for (std::size_t g = 0; g < model.section_force_groups.size(); ++g) {
      const Model::SectionForceGroup& group = model.section_force_groups[g];
      const std::string path = "/section_forces/" + group.member;
      std::vector<std::string> nodes;
      for (const int e : group.elements)
        for (const int n : model.elements[e]->nodes()) nodes.push_back(model.nodes[n].name);
      if (group.rope)
        file.writeDoubles(path + "/tension", {N, hsize_t(group.elements.size()), hsize_t(kTensionPoints)}, section_forces_[g].data());
      else
        file.writeDoubles(path + "/forces", {N, hsize_t(group.elements.size()), 12}, section_forces_[g].data());
      file.writeStrings(path + "/element_nodes", {group.elements.size(), 2}, nodes);
    }
    for (std::size_t p = 0; p < model.wind_parts.size(); ++p)
      file.writeDoubles("/wind/" + model.wind_parts[p].name + "/force", {N, 3}, wind_forces_[p].data());
    for (std::size_t r = 0; r < model.reeved_ropes.size(); ++r) {
      const ReevedRope& rope = reevedRope(model, static_cast<int>(r));
      file.writeDoubles("/ropes/" + rope.name() + "/part_tension", {N, hsize_t(rope.parts())}, part_tensions_[r].data());
    }
    for (std::size_t k = 0; k < load_constraints_.size(); ++k) writeConstraintLoads(file, model.constraints[load_constraints_[k]], constraint_loads_[k]);
    for (std::size_t k = 0; k < tipping_moments_.size(); ++k) {
      const TippingLineSpec& line = model.output.tipping_lines[k];
      const std::string path = "/tipping_moments/" + line.name;
      file.writeDoubles(path, {N}, tipping_moments_[k].data());
      file.attribute(path, "min", N > 0 ? *std::min_element(tipping_moments_[k].begin(), tipping_moments_[k].end())
                                        : std::numeric_limits<double>::quiet_NaN());
      file.attribute(path, "line", fmt::format("[[{}, {}, {}], [{}, {}, {}]]", line.from.x(), line.from.y(), line.from.z(),
                                               line.to.x(), line.to.y(), line.to.z()));
      std::string supports;
      for (const std::string& s : line.supports) supports += (supports.empty() ? "" : ", ") + s;
      file.attribute(path, "supports", supports);
      file.attribute(path, "sign", kTippingMomentSign);
    }
    if (meta.crane) writeCraneFigures(file, *meta.crane);
    if (!envelope_.empty()) writeEnvelope(file, model, envelope_);
    if (const auto& supports = model.envelope.supports) writeSupports(file, model, *supports, envelope_, [&](int k) { return stateColumn(k); });
    file.writeDoubles("/residual/position", {N}, residual_position_.data());
    file.writeDoubles("/residual/velocity", {N}, residual_velocity_.data());

    const SolverStatistics& st = outcome.statistics;
    file.ensureGroup("/solver");
    file.attribute("/solver", "steps", st.steps);
    file.attribute("/solver", "residual_evaluations", st.residual_evaluations);
    file.attribute("/solver", "jacobian_evaluations", st.jacobian_evaluations);
    file.attribute("/solver", "linear_setups", st.linear_setups);
    file.attribute("/solver", "nonlinear_iterations", st.nonlinear_iterations);
    file.attribute("/solver", "nonlinear_failures", st.nonlinear_failures);
    file.attribute("/solver", "error_test_failures", st.error_test_failures);
    file.attribute("/solver", "reparameterisations", st.reparameterisations);
    file.attribute("/solver", "restarts", st.restarts);
    file.attribute("/solver", "wall_time_s", st.wall_time_s);
    file.attribute("/solver", "max_step_constraint_residual", st.max_step_constraint_residual);
    file.attribute("/solver", "rtol", model.solver.rtol);
    file.attribute("/solver", "atol", model.solver.atol.position);  // positions; by kind below
    file.attribute("/solver", "atol_rotation", model.solver.atol.rotation);
    file.attribute("/solver", "atol_velocity", model.solver.atol.velocity);
    file.attribute("/solver", "atol_angular_velocity", model.solver.atol.angular_velocity);
    file.attribute("/solver", "last_step_size", st.last_step_size);
    file.attribute("/solver", "last_order", static_cast<long>(st.last_order));
  });
}

void writeEquilibriumResults(const std::string& path, const Assembler& assembler, const StaticResult& eq,
                             const std::string& scene_path, const std::string& scene_text, const std::string& unstable,
                             const CraneFigures* crane) {
  ResultsRecorder recorder(assembler);
  recorder.sample(eq.t, equilibriumSample(assembler, eq).data(), WorkTerms{});
  SimulationOutcome outcome;
  outcome.complete = unstable.empty();
  outcome.t_reached = eq.t;
  outcome.message = unstable;
  recorder.write(path, {scene_path, scene_text, "static", eq.t, crane}, outcome);
}

void requireResultsFit(const Scene& scene, const Model& model) {
  constexpr double kMaxResultsBytes = 4.0 * (1u << 30);
  const double samples = (scene.solver.t_end - scene.solver.t_start) / scene.output.interval + 1.0;
  const double bytes = ResultsRecorder::estimatedBytes(model, samples);
  if (!(bytes <= kMaxResultsBytes))
    throw SceneError(scene.output.where,
                     fmt::format("output.interval = {:g} s asks for {:.3g} samples over {:g} s, about {:.3g} GB of results "
                                 "(at most {:.3g} GB); choose a longer interval",
                                 scene.output.interval, samples, scene.solver.t_end - scene.solver.t_start, bytes / 1e9,
                                 kMaxResultsBytes / 1e9));
}

}  // namespace cranesim
