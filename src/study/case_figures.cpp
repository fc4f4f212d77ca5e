#include "cranesim/study/case_figures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "cranesim/assembly/assembler.hpp"
#include "cranesim/assembly/constraint_reaction.hpp"
#include "cranesim/crane/support_reading.hpp"
#include "cranesim/model/element.hpp"
#include "cranesim/model/reeved_rope.hpp"
#include "cranesim/solvers/scene_equilibrium.hpp"

namespace cranesim {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The recorded force (or, with `moment`, the moment) constraint `name` carries at every sample.
std::vector<double> constraintLoads(const Model& model, const ResultsRecorder& recorder, const std::string& name, bool moment) {
  const Constraint& c = model.constraints[model.findConstraint(name)];
  std::vector<std::vector<double>> rows;
  for (int k = 0; k < c.rows; ++k) rows.push_back(recorder.stateColumn(model.nq + model.nv + c.row + k));
  std::vector<double> forces(recorder.samples());
  VecX lambda = VecX::Zero(model.m);
  for (std::size_t s = 0; s < forces.size(); ++s) {
    for (int k = 0; k < c.rows; ++k) lambda(c.row + k) = rows[k][s];
    const ConstraintLoad load = constraintLoad(c, lambda.data());
    forces[s] = moment ? load.other : load.force;
  }
  return forces;
}

std::vector<double> coordinate(const Model& model, const ResultsRecorder& recorder, const std::string& joint, int axis) {
  const std::vector<double>& p = recorder.jointPositions(model.findJoint(joint));
  std::vector<double> out(recorder.samples());
  for (std::size_t s = 0; s < out.size(); ++s) out[s] = p[3 * s + axis];
  return out;
}

/// The horizontal distance of a joint, at every sample, from the reference joint at the same
/// time (less the mean of that offset over the samples in the window with `about_mean`), or (no
/// reference) from its own mean position over the samples in the window.
std::vector<double> horizontalDistances(const FigureSpec& fig, const Model& model, const ResultsRecorder& recorder,
                                        const std::vector<std::size_t>& window) {
  std::vector<double> x = coordinate(model, recorder, fig.joint, 0), y = coordinate(model, recorder, fig.joint, 1);
  if (!fig.relative_to.empty()) {
    const std::vector<double> rx = coordinate(model, recorder, fig.relative_to, 0), ry = coordinate(model, recorder, fig.relative_to, 1);
    for (std::size_t s = 0; s < x.size(); ++s) x[s] -= rx[s], y[s] -= ry[s];
  }
  if (fig.relative_to.empty() || fig.about_mean) {
    double mx = 0.0, my = 0.0;
    for (const std::size_t s : window) mx += x[s], my += y[s];
    mx /= static_cast<double>(window.size());
    my /= static_cast<double>(window.size());
    for (std::size_t s = 0; s < x.size(); ++s) x[s] -= mx, y[s] -= my;
  }
  std::vector<double> distances(x.size());
  for (std::size_t s = 0; s < x.size(); ++s) distances[s] = std::hypot(x[s], y[s]);
  return distances;
}

/// At every sample, the moment about the tipping line of the ground's loads on the structure
/// through `fig.supports` (constraint_reaction.hpp: supportMoment).
std::vector<double> tippingMoments(const FigureSpec& fig, const Model& model, const ResultsRecorder& recorder) {
  const Assembler assembler(model);
  std::vector<int> supports;
  for (const std::string& name : fig.supports) supports.push_back(model.findConstraint(name));
  std::vector<std::vector<double>> columns(model.nq + model.nv + model.m);
  for (int k = 0; k < static_cast<int>(columns.size()); ++k) columns[k] = recorder.stateColumn(k);
  std::vector<double> moments(recorder.samples());
  VecX q(model.nq), v(model.nv), lambda(model.m);
  for (std::size_t s = 0; s < moments.size(); ++s) {
    for (int k = 0; k < model.nq; ++k) q(k) = columns[k][s];
    for (int k = 0; k < model.nv; ++k) v(k) = columns[model.nq + k][s];
    for (int k = 0; k < model.m; ++k) lambda(k) = columns[model.nq + model.nv + k][s];
    const Eigen::SparseMatrix<double> G = assembler.constraints(recorder.time()[s], q.data(), v.data()).G;
    moments[s] = supportMoment(model, supports, fig.line_from, fig.line_to, G, q.data(), lambda.data());
  }
  return moments;
}

/// At every sample, what the carriage's supports say (crane/support_reading.hpp): the largest
/// bed pressure, or the stability margin about the active tipping line.
std::vector<double> supportSeries(const FigureSpec& fig, const ResultsRecorder& recorder) {
  std::vector<double> series;
  for (const SupportReading& r : recorder.envelope().supports())
    series.push_back(fig.quantity == FigureQuantity::SupportPressure ? r.peakPressure() : r.tipping.margin);
  return series;
}

/// At every sample, the tipping load of the hook load `fig.body` (its weight W_L plus the force
/// that, added where its centroid hangs, brings the supports' resultant onto the support
/// polygon's edge: crane/support_statics.hpp, tippingForce), or W_L over it. The crane's
/// geometry is the sample's: the extra load is assumed not to deflect it further.
std::vector<double> tippingLoads(const FigureSpec& fig, const Scene& scene, const Model& model, const ResultsRecorder& recorder) {
  const RigidBodySpec& body = *std::find_if(scene.bodies.begin(), scene.bodies.end(), [&](const RigidBodySpec& b) { return b.name == fig.body; });
  const auto node = static_cast<int>(std::find_if(model.nodes.begin(), model.nodes.end(), [&](const Node& n) {
                                       return n.member.empty() && n.name == fig.body;
                                     }) - model.nodes.begin());
  const double weight = body.mass * model.gravity.norm();
  const auto [e1, e2] = groundPlaneAxes(model.envelope.up);
  std::vector<std::vector<double>> columns(model.nq);
  for (int k = 0; k < model.nq; ++k) columns[k] = recorder.stateColumn(k);
  const std::vector<SupportReading>& readings = recorder.envelope().supports();
  std::vector<double> loads(readings.size());
  VecX q(model.nq);
  for (std::size_t s = 0; s < loads.size(); ++s) {
    for (int k = 0; k < model.nq; ++k) q(k) = columns[k][s];
    const Frame frame = model.nodeFrame(q.data(), node);
    const Vec3 centroid = frame.r + frame.R * body.centroid;
    const SupportReading& r = readings[s];
    const double tipping = weight + tippingForce(r.polygon, r.carried, r.resultant, {e1.dot(centroid), e2.dot(centroid)});
    loads[s] = fig.quantity == FigureQuantity::TippingLoad ? tipping : weight / tipping;
  }
  return loads;
}

/// The time within the window during which some point of the rope carries no tension (its
/// elements' tensions at kTensionPoints points each, element.hpp), every sample standing for the
/// interval to the next (the window's last sample for none).
double slackTime(const FigureSpec& fig, const Model& model, const ResultsRecorder& recorder,
                 const std::vector<std::size_t>& window) {
  std::vector<const Element*> elements;
  double tension[kTensionPoints];
  const VecX zero = VecX::Zero(model.nv);
  for (const auto& e : model.elements)
    if (model.nodes[e->nodes().front()].member == fig.rope &&
        e->tensions({model.q0.data(), zero.data(), zero.data(), 0.0, model.gravity}, tension))
      elements.push_back(e.get());
  std::vector<std::vector<double>> columns(model.nq);
  for (int k = 0; k < model.nq; ++k) columns[k] = recorder.stateColumn(k);
  VecX q(model.nq);
  double slack = 0.0;
  for (std::size_t w = 0; w + 1 < window.size(); ++w) {
    const std::size_t s = window[w];
    const double t = recorder.time()[s];
    for (int k = 0; k < model.nq; ++k) q(k) = columns[k][s];
    const ElementInput in{q.data(), zero.data(), zero.data(), t, model.gravity};
    const bool somewhere = std::any_of(elements.begin(), elements.end(), [&](const Element* e) {
      e->tensions(in, tension);
      return *std::min_element(tension, tension + kTensionPoints) <= 0.0;
    });
    if (somewhere) slack += recorder.time()[window[w + 1]] - t;
  }
  return slack;
}

/// The angle, deg, above the horizontal (normal to gravity) of the line from `relative_to` (the
/// boom's foot hinge) to `joint` (its head) at every sample.
std::vector<double> elevations(const FigureSpec& fig, const Model& model, const ResultsRecorder& recorder) {
  const Vec3 up = model.gravity.norm() > 0.0 ? Vec3(-model.gravity.normalized()) : Vec3::UnitZ();
  const std::vector<double>& head = recorder.jointPositions(model.findJoint(fig.joint));
  const std::vector<double>& foot = recorder.jointPositions(model.findJoint(fig.relative_to));
  std::vector<double> out(recorder.samples());
  for (std::size_t s = 0; s < out.size(); ++s) {
    const Vec3 line = Vec3(head[3 * s], head[3 * s + 1], head[3 * s + 2]) - Vec3(foot[3 * s], foot[3 * s + 1], foot[3 * s + 2]);
    out[s] = std::atan2(line.dot(up), (line - line.dot(up) * up).norm()) * 180.0 / std::numbers::pi;
  }
  return out;
}

/// At every sample, reeved rope `fig.rope`'s largest part tension (PartTension) or the winch's
/// pull hoisting steadily the load its falls carry (LinePull, reeved_rope.hpp).
std::vector<double> reevedRopeFigures(const FigureSpec& fig, const Model& model, const ResultsRecorder& recorder) {
  const int r = findReevedRope(model, fig.rope);
  const ReevedRope& rope = reevedRope(model, r);
  const std::vector<double>& tensions = recorder.partTensions(r);
  std::vector<double> out(recorder.samples());
  for (std::size_t s = 0; s < out.size(); ++s) {
    const double* parts = tensions.data() + s * static_cast<std::size_t>(rope.parts());
    out[s] = fig.quantity == FigureQuantity::PartTension ? *std::max_element(parts, parts + rope.parts())
                                                         : rope.hoistingLinePull(parts);
  }
  return out;
}

double reduce(const std::vector<double>& series, const std::vector<std::size_t>& window, FigureStatistic statistic) {
  double out = series[window.front()];
  for (const std::size_t s : window)
    out = statistic == FigureStatistic::Final ? series[s]
        : statistic == FigureStatistic::Max   ? std::max(out, series[s])
                                              : std::min(out, series[s]);
  return out;
}

}  // namespace

std::vector<double> caseFigures(const Study& study, const Scene& scene, const Model& model, const ResultsRecorder& recorder,
                                const ModalResult* modes) {
  std::vector<double> figures;
  for (const FigureSpec& fig : study.figures) {
    if (fig.quantity == FigureQuantity::Frequency) {
      figures.push_back(modes && fig.mode <= modes->frequencies.size() ? modes->frequencies(fig.mode - 1) : kNaN);
      continue;
    }
    std::vector<std::size_t> window;
    for (std::size_t s = 0; s < recorder.samples(); ++s)
      if (recorder.time()[s] >= fig.after) window.push_back(s);
    if (window.empty()) {
      figures.push_back(kNaN);
      continue;
    }
    switch (fig.quantity) {
      case FigureQuantity::ConstraintForce:
      case FigureQuantity::ConstraintMoment:
        figures.push_back(reduce(constraintLoads(model, recorder, fig.constraint, fig.quantity == FigureQuantity::ConstraintMoment),
                                 window, fig.statistic));
        break;
      case FigureQuantity::Position:
        figures.push_back(reduce(coordinate(model, recorder, fig.joint, fig.component), window, fig.statistic));
        break;
      case FigureQuantity::HorizontalDistance:
      case FigureQuantity::HorizontalSway:
        figures.push_back(reduce(horizontalDistances(fig, model, recorder, window), window, fig.statistic));
        break;
      case FigureQuantity::TippingMoment:
        figures.push_back(reduce(tippingMoments(fig, model, recorder), window, fig.statistic));
        break;
      case FigureQuantity::DynamicFactor: {
        // φ2 (EN 13001-2): the peak over the static force, the first sample's (a run that starts
        // from its equilibrium, initial_state: equilibrium).
        const std::vector<double> forces = constraintLoads(model, recorder, fig.constraint, false);
        figures.push_back(forces.front() > 0.0 ? reduce(forces, window, FigureStatistic::Max) / forces.front() : kNaN);
        break;
      }
      case FigureQuantity::RopeSlack:
        figures.push_back(slackTime(fig, model, recorder, window));
        break;
      case FigureQuantity::SupportPressure:
      case FigureQuantity::StabilityMargin:
        figures.push_back(reduce(supportSeries(fig, recorder), window, fig.statistic));
        break;
      case FigureQuantity::TippingLoad:
      case FigureQuantity::TippingLoadFraction:
        figures.push_back(reduce(tippingLoads(fig, scene, model, recorder), window, fig.statistic));
        break;
      case FigureQuantity::BoomAngle:
        figures.push_back(reduce(elevations(fig, model, recorder), window, fig.statistic));
        break;
      case FigureQuantity::PartTension:
      case FigureQuantity::LinePull:
        figures.push_back(reduce(reevedRopeFigures(fig, model, recorder), window, fig.statistic));
        break;
      case FigureQuantity::Frequency:
        break;
    }
  }
  return figures;
}

}  // namespace cranesim
