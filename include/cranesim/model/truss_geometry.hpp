#pragma once
// A lattice boom section (truss, thesis 3.5): what a scene says about it (TrussDescription) and
// the geometry built from that (TrussGeometry): every node and every tube in the truss frame.
// The same geometry feeds the super truss element (3.5) and the full-member model, so the two
// fidelities describe the same structure. Lacing forms and numbering: docs/truss.md.
//
// Truss frame: x along the truss axis, end section 1 at x = 0, end section 2 at x = length; the
// end-section frames are the truss frame translated to x = 0 and x = length.

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "cranesim/elements/section.hpp"
#include "cranesim/math/types.hpp"
#include "cranesim/model/source_location.hpp"

namespace cranesim {

enum class TrussMemberRole { Main, Cross, Sub };

struct TrussNode {
  Vec3 position;    // reference configuration in the truss frame: x along the axis, 0 … length
  int end_section;  // 0 (x = 0) or 1 (x = length) for end-section nodes, −1 for internal nodes
  int chord;        // index into TrussGeometry::chords of the main beam the node lies on (−1: none)
  double xi;        // station along that main beam, 0 … 1
};

struct TrussMember {
  int node1, node2;       // indices into TrussGeometry::nodes
  TrussMemberRole role;
  Section section;        // round tube: outer/inner radius set
  Vec3 z_axis;            // section z-axis hint in the truss frame (3-80, 3-82, 3-84)
};

struct TrussGeometry {
  double length = 0.0;
  Material material;
  std::vector<TrussNode> nodes;
  std::vector<std::array<int, 2>> chords;  // main beams: end-section node at x = 0, at x = length
  std::vector<TrussMember> members;        // main beams already split at internal nodes (sub main beams)
};

/// Sub-beam (lacing) connection forms (the thesis' "SB Connection Form", Table D-3, D-6).
/// Type1: one diagonal per bay in each side face, alternating (Warren); both end sections have
/// the same number of nodes. AntiType1: its mirror image along the truss axis. TPType1: a
/// transition piece from a 2-node end section 1 to a 4-node end section 2; TPAntiType1: from a
/// 4-node end section 1 to a 2-node end section 2 (the mirror image of TPType1).
enum class LacingForm { Type1, AntiType1, TPType1, TPAntiType1 };

/// A round tube. Inner radius 0: solid bar.
struct TrussTube {
  double outer_radius = 0.0, inner_radius = 0.0;
  SourceLocation where;
};

/// A pair of node numbers (0-based here; the scene numbers them from 1 as the thesis does).
struct TrussNodePair {
  std::array<int, 2> nodes{};
  SourceLocation where;
};

struct TrussEndSection {
  std::vector<Eigen::Vector2d> nodes;     // (y, z) of each node in the end-section frame
  std::vector<TrussNodePair> cross_beams;  // nodes of this section
  SourceLocation where, where_nodes;
};

/// What a scene says about a truss type (one entry of `trusses:`).
struct TrussDescription {
  std::string name;
  double length = 0.0;
  int order = 1;  // truss order: number of bays along the length (3.5.2)
  std::array<TrussEndSection, 2> sections;
  std::vector<TrussNodePair> main_beams;  // node of section 1, node of section 2
  LacingForm lacing = LacingForm::Type1;
  TrussTube main_tube, cross_tube, sub_tube;
  Material material;
  double poisson_ratio = 0.3;
  SourceLocation where, where_length, where_order, where_main_beams, where_lacing;
};

/// Section axes of a straight tube in the truss frame: x along `axis`, z as close to the
/// member's z-axis hint as possible.
inline Mat3 tubeAxes(const Vec3& axis, const Vec3& z_hint) {
  const Vec3 x = axis.normalized();
  Vec3 z = z_hint - z_hint.dot(x) * x;
  if (z.norm() < 1e-6) throw std::invalid_argument("truss: a tube's z-axis hint is along the tube");
  z.normalize();
  Mat3 R;
  R << x, z.cross(x), z;
  return R;
}

/// Builds and validates the geometry: end-section nodes first (section 1, then section 2, in the
/// description's order), then the internal nodes chord by chord at the bay stations
/// xi = k/order, k = 1 … order − 1. Members: main beams split at the internal nodes (chord by
/// chord, bay by bay), the cross-section beams of section 1 and 2, then the lacing face by face.
/// Throws SceneError naming the YAML path of the offending input.
TrussGeometry buildTrussGeometry(const TrussDescription& description);

}  // namespace cranesim
