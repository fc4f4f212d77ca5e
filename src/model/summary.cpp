#include "cranesim/model/summary.hpp"

#include <fmt/format.h>

namespace cranesim {
namespace {

const char* typeName(ConstraintType t) {
  switch (t) {
    case ConstraintType::Fixed: return "fixed";
    case ConstraintType::Revolute: return "revolute";
    case ConstraintType::Prismatic: return "prismatic";
    case ConstraintType::Spherical: return "spherical";
    case ConstraintType::Distance: return "distance";
  }
  return "?";
}

}  // namespace

std::string modelSummary(const Assembler& assembler) {
  const Model& model = assembler.model();
  std::string out = fmt::format("scene: {}\n", model.name);
  out += fmt::format("nodes: {}   elements: {}\n", model.nodes.size(), model.elements.size());
  int rank = 0;
  if (model.m > 0) {
    const VecX v = VecX::Zero(model.nv);
    const MatX G = MatX(assembler.constraints(model.solver.t_start, model.q0.data(), v.data()).G);
    Eigen::ColPivHouseholderQR<MatX> qr(G.transpose());
    qr.setThreshold(1e-10);
    rank = static_cast<int>(qr.rank());
  }
  int drives = 0;
  out += fmt::format("constraints: {} with {} equations (rank {} at the initial state)\n", model.constraints.size(),
                     model.m, rank);
  for (const Constraint& c : model.constraints) {
    drives += c.drive ? 1 : 0;
    out += fmt::format("  {:<20} {:<10} {} — {}{}\n", c.name, typeName(c.type), model.joints[c.joint1].name,
                       model.joints[c.joint2].name, c.drive ? "  [driven]" : "");
  }
  out += fmt::format("coordinates: {} (q), {} (dq); DAE unknowns: {}\n", model.nq, model.nv, assembler.size());
  out += fmt::format("degrees of freedom: {} (= {} − {})\n", model.nv - rank, model.nv, rank);
  out += fmt::format("drives: {}   loads: {}\n", drives, model.loads.size());
  if (model.wind) {
    const WindFieldSpec& w = model.wind->spec();
    std::string parts;
    std::size_t elements = 0;
    for (const WindPart& part : model.wind_parts) parts += (parts.empty() ? "" : ", ") + part.name, elements += part.elements.size();
    out += fmt::format("wind: {:g} m/s at {:g} m towards [{:g}, {:g}, {:g}] on {} ({} wind elements)\n", w.speed,
                       w.reference_height, w.direction.x(), w.direction.y(), w.direction.z(), parts, elements);
  }
  const Envelope& envelope = model.envelope;
  if (envelope.ground_height) {
    std::string parts;
    std::size_t points = 0;
    for (const GroundContactPart& part : envelope.ground_contacts) parts += (parts.empty() ? "" : ", ") + part.name, points += part.elements.size();
    out += fmt::format("ground: surface at {:g} m; {}\n", *envelope.ground_height,
                       parts.empty() ? std::string("nothing rests on it (watched only)") : fmt::format("resting on it: {} ({} contact point{})", parts, points, points == 1 ? "" : "s"));
  }
  if (envelope.boom && envelope.boom->backstop_element >= 0)
    out += fmt::format("backstop: engages at a boom angle of {:g}°; boom angle limit {:g}°\n", envelope.boom->backstop_angle_deg,
                       envelope.boom->limit_deg);
  std::string limited;
  for (const EnvelopeRope& rope : envelope.ropes) limited += fmt::format("{}{} {:.4g} MN", limited.empty() ? "" : ", ", rope.name, rope.breaking_force / 1e6);
  if (!limited.empty()) out += fmt::format("breaking forces: {}\n", limited);
  const AbsoluteTolerance& atol = model.solver.atol;
  const std::string atol_text =
      atol.isUniform() ? fmt::format("{:g}", atol.position)
                       : fmt::format("{:g} m, {:g} rad, {:g} m/s, {:g} rad/s", atol.position, atol.rotation, atol.velocity,
                                     atol.angular_velocity);
  out += fmt::format("solver: {} formulation, rtol {:g}, atol {}, t = {:g} … {:g} s, output every {:g} s\n",
                     model.solver.formulation == Formulation::GGL ? "GGL index-2" : "Baumgarte index-1",
                     model.solver.rtol, atol_text, model.solver.t_start, model.solver.t_end, model.output.interval);
  out += fmt::format("Jacobian: {} × {}, {} non-zeros\n", assembler.size(), assembler.size(),
                     assembler.pattern().nonZeros());
  return out;
}

}  // namespace cranesim
