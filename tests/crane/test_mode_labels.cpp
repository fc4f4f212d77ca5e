// What each crane mode moves (crane/mode_labels.hpp) on the thesis crane with condensed lattice
// sections (configs/crane_condensed.yaml): its two pendulum modes, the boom's bending and the
// ropes' string modes, told apart by their shares of the kinetic energy.

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "cranesim/crane/mode_labels.hpp"
#include "cranesim/solvers/scene_equilibrium.hpp"
#include "scene_fixtures.hpp"

using namespace cranesim;

namespace {

double sum(const ModeShares& s) {
  return s.load() + s.boom() + s.ropes + s.rest;
}

}  // namespace

TEST_CASE("Crane modes are labelled by what they move", "[crane][modes]") {
  const Scene scene = test::loadScene("crane_condensed.yaml");
  const Model model = compileModel(scene);
  const StaticResult eq = solveEquilibrium(scene, model, 0.0);
  REQUIRE(eq.converged);
  const ModalResult modal = computeModes(model, eq.q, eq.t, 40);
  const std::vector<ModeLabel> labels = labelModes(scene, model, eq.q, eq.t, modal);
  REQUIRE(labels.size() == static_cast<std::size_t>(modal.frequencies.size()));

  // Mass-normalised shapes: the shares of each mode's kinetic energy add up to 1.
  for (const ModeLabel& l : labels) CHECK(sum(l.shares) == Approx(1.0).margin(1e-9));

  // The boom plane is x–z (the boom leans towards −x). The two slowest elastic modes are the
  // load's pendulum swings, 2π √(L / g) ≈ 15 s on the 55.1 m rope and longer where the boom's
  // head gives way: across the boom plane only the 55 m boom's lattice holds the head, in it the
  // luffing line does, so the load swings out of the plane more slowly (17.1 s) than in it
  // (15.6 s).
  const int load = [&] {
    for (std::size_t n = 0; n < model.nodes.size(); ++n)
      if (model.nodes[n].member.empty() && model.nodes[n].name == "load") return model.nodes[n].v;
    return -1;
  }();
  REQUIRE(load >= 0);
  REQUIRE(modal.rigid[0]);  // the slewing ring's free turn
  const auto period = [&](int k) { return 1.0 / modal.frequencies(k); };
  CHECK(period(1) == Approx(17.09).margin(0.01));
  CHECK(period(2) == Approx(15.63).margin(0.01));
  CHECK(labels[1].label == "out-of-plane sway");
  CHECK(labels[2].label == "in-plane sway");
  for (int k : {1, 2}) {
    INFO("mode " << k + 1);
    CHECK(labels[static_cast<std::size_t>(k)].shares.load() > 0.95);
    // The load's own displacement in the mode shape: across the plane (y) or within it (x).
    const Vec3 d = modal.shapes.col(k).segment<3>(load);
    if (k == 1) CHECK(std::abs(d.y()) > 20.0 * std::hypot(d.x(), d.z()));
    else CHECK(std::abs(d.x()) > 20.0 * std::hypot(d.y(), d.z()));
  }

  // The head gives way under the swinging load: a pendulum whose pivot moves by a fraction r of
  // the hook's swing has the length L / (1 − r), so the periods of the two swings stand as
  // √((1 − r_in) / (1 − r_out)).
  const auto swing = [&](int k, const char* joint) {
    const Joint& J = model.joints[static_cast<std::size_t>(model.findJoint(joint))];
    const Node& n = model.nodes[static_cast<std::size_t>(J.node)];
    const VecX phi = modal.shapes.col(k);
    return Vec3(phi.segment<3>(n.v) + model.nodeFrame(eq.q.data(), J.node).R * Vec3(phi.segment<3>(n.v + 3)).cross(J.offset));
  };
  const double r_out = swing(1, "head.sheave").y() / swing(1, "load.origin").y();
  const double r_in = swing(2, "head.sheave").x() / swing(2, "load.origin").x();
  CHECK(r_out == Approx(0.23).margin(0.01));  // the boom's head gives way across its plane ...
  CHECK(r_in == Approx(0.077).margin(0.005)); // ... three times as much as in it
  CHECK(period(1) / period(2) == Approx(std::sqrt((1.0 - r_in) / (1.0 - r_out))).epsilon(0.01));

  // Next, the load turns about the hook (3.0 s, docs/control.md) and bounces on the hoist rope:
  // below √(EA / (L m)) / 2π = 0.964 Hz of the rope alone under a rigid head (L = 54.83 m,
  // EA = 1e11 π 0.05², m = 390 t), as the boom and the luffing line give way in series.
  CHECK(labels[0].label == "rigid");  // the load spinning on its rope
  CHECK(labels[3].label == "load turning");
  CHECK(labels[4].label == "load turning");
  CHECK(labels[5].label == "load bouncing");
  const double bounce_bound = std::sqrt(1.0e11 * std::numbers::pi * 0.05 * 0.05 / (54.8342 * 390000.6)) / (2.0 * std::numbers::pi);
  CHECK(modal.frequencies(5) < bounce_bound);
  CHECK(modal.frequencies(5) > 0.7 * bounce_bound);

  // Then the boom bends, across its plane first (0.86 Hz), and the ropes vibrate as strings.
  CHECK(labels[6].label == "boom bending out of plane");
  CHECK(labels[7].label == "boom bending in plane");
  const auto found = [&](const std::string& label) {
    return std::any_of(labels.begin(), labels.end(), [&](const ModeLabel& l) { return l.label == label; });
  };
  CHECK(found("rope"));
}
