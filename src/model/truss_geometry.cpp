#include "cranesim/model/truss_geometry.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <set>

namespace cranesim {
namespace {

const char* lacingName(LacingForm form) {
  switch (form) {
    case LacingForm::Type1: return "type1";
    case LacingForm::AntiType1: return "anti_type1";
    case LacingForm::TPType1: return "tp_type1";
    case LacingForm::TPAntiType1: return "tp_anti_type1";
  }
  return "";
}

void checkTube(const TrussTube& t, const char* role) {
  if (!(t.outer_radius > 0.0)) throw SceneError(t.where, fmt::format("the {} tube's outer radius must be positive, found {}", role, t.outer_radius));
  if (t.inner_radius < 0.0) throw SceneError(t.where, fmt::format("the {} tube's inner radius must not be negative, found {}", role, t.inner_radius));
  if (t.inner_radius >= t.outer_radius)
    throw SceneError(t.where, fmt::format("the {} tube's inner radius {} must be below its outer radius {}", role, t.inner_radius,
                                          t.outer_radius));
}

void checkNodeIndex(const TrussNodePair& pair, int which, int count, const std::string& what) {
  const int i = pair.nodes[which];
  if (i < 0 || i >= count)
    throw SceneError(pair.where, fmt::format("{} node {} does not exist: the section has nodes 1…{}", what, i + 1, count));
}

/// Everything buildTrussGeometry can check before it builds: sizes, indices, radii, the lacing
/// form against the end sections.
void validate(const TrussDescription& d) {
  if (!(d.length > 0.0)) throw SceneError(d.where_length, fmt::format("a truss length must be positive, found {}", d.length));
  if (d.order < 1) throw SceneError(d.where_order, fmt::format("the truss order (number of bays) must be at least 1, found {}", d.order));
  for (int s = 0; s < 2; ++s) {
    const TrussEndSection& sec = d.sections[s];
    if (sec.nodes.size() < 2)
      throw SceneError(sec.where_nodes, fmt::format("end section {} needs at least 2 nodes, found {}", s + 1, sec.nodes.size()));
    for (std::size_t i = 0; i < sec.nodes.size(); ++i)
      for (std::size_t j = 0; j < i; ++j)
        if ((sec.nodes[i] - sec.nodes[j]).norm() < 1e-9 * d.length)
          throw SceneError(sec.where_nodes, fmt::format("nodes {} and {} of end section {} coincide", j + 1, i + 1, s + 1));
    std::set<std::pair<int, int>> seen;
    for (const TrussNodePair& c : sec.cross_beams) {
      for (int k = 0; k < 2; ++k) checkNodeIndex(c, k, static_cast<int>(sec.nodes.size()), fmt::format("cross-section beam: section {}", s + 1));
      if (c.nodes[0] == c.nodes[1]) throw SceneError(c.where, "a cross-section beam needs two different nodes");
      if (!seen.insert(std::minmax(c.nodes[0], c.nodes[1])).second)
        throw SceneError(c.where, fmt::format("cross-section beam {}–{} is given twice", c.nodes[0] + 1, c.nodes[1] + 1));
    }
  }
  if (d.main_beams.size() < 2) throw SceneError(d.where_main_beams, fmt::format("a truss needs at least 2 main beams, found {}", d.main_beams.size()));
  std::set<std::pair<int, int>> seen;
  std::array<std::vector<int>, 2> chords_at{std::vector<int>(d.sections[0].nodes.size()), std::vector<int>(d.sections[1].nodes.size())};
  for (const TrussNodePair& m : d.main_beams) {
    for (int s = 0; s < 2; ++s) checkNodeIndex(m, s, static_cast<int>(d.sections[s].nodes.size()), fmt::format("main beam: section {}", s + 1));
    if (!seen.insert({m.nodes[0], m.nodes[1]}).second)
      throw SceneError(m.where, fmt::format("main beam {}–{} is given twice", m.nodes[0] + 1, m.nodes[1] + 1));
    for (int s = 0; s < 2; ++s) ++chords_at[s][m.nodes[s]];
  }
  for (int s = 0; s < 2; ++s)
    for (std::size_t i = 0; i < chords_at[s].size(); ++i)
      if (chords_at[s][i] == 0)
        throw SceneError(d.where_main_beams,
                         fmt::format("node {} of end section {} lies on no main beam: every end-section node must be the end of a main beam", i + 1, s + 1));
  checkTube(d.main_tube, "main");
  checkTube(d.cross_tube, "cross-section");
  checkTube(d.sub_tube, "sub-beam");

  const std::size_t n1 = d.sections[0].nodes.size(), n2 = d.sections[1].nodes.size();
  const bool applicable = d.lacing == LacingForm::TPType1       ? n1 == 2 && n2 == 4
                          : d.lacing == LacingForm::TPAntiType1 ? n1 == 4 && n2 == 2
                                                                : n1 == n2;
  if (!applicable) {
    const std::string needs = d.lacing == LacingForm::TPType1       ? "a 2-node end section 1 and a 4-node end section 2"
                              : d.lacing == LacingForm::TPAntiType1 ? "a 4-node end section 1 and a 2-node end section 2"
                                                                    : "end sections with the same number of nodes";
    throw SceneError(d.where_lacing, fmt::format("lacing '{}' needs {}; the sections have {} and {} nodes", lacingName(d.lacing), needs, n1, n2));
  }
}

/// A side face: the plane of two main beams that carries lacing (a "sub-beam plane", 3-82).
struct Face {
  int chord_a, chord_b;  // the diagonal of bay k runs between these two chords
  Vec3 normal;           // unit, pointing out of the truss
};

/// A unit vector perpendicular to `direction`, as close to `preferred` as possible.
Vec3 perpendicular(const Vec3& direction, const Vec3& preferred) {
  const Vec3 x = direction.normalized();
  Vec3 z = preferred - preferred.dot(x) * x;
  if (z.norm() < 1e-6) z = Vec3::UnitY() - x.y() * x;
  return z.normalized();
}

class Builder {
 public:
  explicit Builder(const TrussDescription& d) : d_(d) {}

  TrussGeometry build() {
    g_.length = d_.length;
    g_.material = d_.material;
    addEndSectionNodes();
    addInternalNodes();
    findFaces();
    addMainBeams();
    addCrossBeams();
    addLacing();
    return std::move(g_);
  }

 private:
  int sectionNode(int section, int i) const { return section == 0 ? i : static_cast<int>(d_.sections[0].nodes.size()) + i; }

  /// The node of chord c at bay station k (0 … order).
  int station(int c, int k) const {
    if (k == 0) return g_.chords[c][0];
    if (k == d_.order) return g_.chords[c][1];
    return first_internal_ + c * (d_.order - 1) + (k - 1);
  }

  Vec3 position(int node) const { return g_.nodes[node].position; }

  void addEndSectionNodes() {
    for (int s = 0; s < 2; ++s)
      for (std::size_t i = 0; i < d_.sections[s].nodes.size(); ++i) {
        int chord = -1;
        for (std::size_t c = 0; c < d_.main_beams.size() && chord < 0; ++c)
          if (d_.main_beams[c].nodes[s] == static_cast<int>(i)) chord = static_cast<int>(c);
        const Eigen::Vector2d& yz = d_.sections[s].nodes[i];
        g_.nodes.push_back({Vec3(s == 0 ? 0.0 : d_.length, yz.x(), yz.y()), s, chord, s == 0 ? 0.0 : 1.0});
      }
    for (const TrussNodePair& m : d_.main_beams) g_.chords.push_back({sectionNode(0, m.nodes[0]), sectionNode(1, m.nodes[1])});
  }

  void addInternalNodes() {
    first_internal_ = static_cast<int>(g_.nodes.size());
    for (std::size_t c = 0; c < g_.chords.size(); ++c)
      for (int k = 1; k < d_.order; ++k) {
        const double xi = static_cast<double>(k) / d_.order;
        const Vec3 p = (1.0 - xi) * position(g_.chords[c][0]) + xi * position(g_.chords[c][1]);
        g_.nodes.push_back({p, -1, static_cast<int>(c), xi});
      }
  }

  /// The chord whose end in section s is node i; the node must be on exactly one.
  int chordAt(int s, int i, const TrussNodePair& where) const {
    int found = -1, count = 0;
    for (std::size_t c = 0; c < d_.main_beams.size(); ++c)
      if (d_.main_beams[c].nodes[s] == i) found = static_cast<int>(c), ++count;
    if (count != 1)
      throw SceneError(where.where, fmt::format("node {} of end section {} lies on {} main beams; a side face needs exactly one", i + 1, s + 1, count));
    return found;
  }

  bool joinedInSection(int s, int i, int j) const {
    if (i == j) return true;
    for (const TrussNodePair& c : d_.sections[s].cross_beams)
      if ((c.nodes[0] == i && c.nodes[1] == j) || (c.nodes[0] == j && c.nodes[1] == i)) return true;
    return false;
  }

  /// Side faces: each cross-section beam of the reference section (the one with more nodes,
  /// section 1 on a tie) spans a face between the chords ending at its two nodes. In the other
  /// section the two chords must meet in one node or be joined by a cross-section beam too, and
  /// the face must be plane (3-82).
  void findFaces() {
    const int ref = d_.sections[1].nodes.size() > d_.sections[0].nodes.size() ? 1 : 0, other = 1 - ref;
    Vec3 centre = Vec3::Zero();
    for (int n = 0; n < first_internal_; ++n) centre += position(n);
    centre /= first_internal_;
    for (const TrussNodePair& cb : d_.sections[ref].cross_beams) {
      const int a = chordAt(ref, cb.nodes[0], cb), b = chordAt(ref, cb.nodes[1], cb);
      if (!joinedInSection(other, d_.main_beams[a].nodes[other], d_.main_beams[b].nodes[other]))
        throw SceneError(cb.where, fmt::format("the main beams through nodes {} and {} of end section {} do not bound a side face: "
                                               "their nodes {} and {} in end section {} are not joined by a cross-section beam",
                                               cb.nodes[0] + 1, cb.nodes[1] + 1, ref + 1, d_.main_beams[a].nodes[other] + 1,
                                               d_.main_beams[b].nodes[other] + 1, other + 1));
      const Vec3 a0 = position(g_.chords[a][0]), a1 = position(g_.chords[a][1]);
      const Vec3 b0 = position(g_.chords[b][0]), b1 = position(g_.chords[b][1]);
      const Vec3 n0 = (a1 - a0).cross(b0 - a0), n1 = (a1 - a0).cross(b1 - a0);
      Vec3 normal = n0.norm() > n1.norm() ? n0 : n1;
      normal.normalize();
      const double scale = std::max({d_.length, (b0 - a0).norm(), (b1 - a1).norm()});
      if (std::abs(normal.dot(b0 - a0)) > 1e-9 * scale || std::abs(normal.dot(b1 - a0)) > 1e-9 * scale)
        throw SceneError(cb.where, fmt::format("the main beams through nodes {} and {} of end section {} do not lie in one plane: "
                                               "lacing needs plane side faces (3-82)",
                                               cb.nodes[0] + 1, cb.nodes[1] + 1, ref + 1));
      if (normal.dot(0.25 * (a0 + a1 + b0 + b1) - centre) < 0.0) normal = -normal;
      faces_.push_back({a, b, normal});
    }
  }

  Section tube(const TrussTube& t) const { return Section::circular(t.outer_radius, t.inner_radius, d_.poisson_ratio); }

  /// Main beams: split at the internal nodes; section z along the normal of the chord's first
  /// side face (3-82).
  void addMainBeams() {
    const Section s = tube(d_.main_tube);
    for (std::size_t c = 0; c < g_.chords.size(); ++c) {
      const Vec3 dir = position(g_.chords[c][1]) - position(g_.chords[c][0]);
      Vec3 z = perpendicular(dir, Vec3::UnitZ());
      for (const Face& f : faces_)
        if (f.chord_a == static_cast<int>(c) || f.chord_b == static_cast<int>(c)) {
          z = f.normal;
          break;
        }
      for (int k = 0; k < d_.order; ++k) g_.members.push_back({station(c, k), station(c, k + 1), TrussMemberRole::Main, s, z});
    }
  }

  /// Cross-section beams: section z along the truss axis, normal to the end section (3-80).
  void addCrossBeams() {
    const Section s = tube(d_.cross_tube);
    for (int sec = 0; sec < 2; ++sec)
      for (const TrussNodePair& c : d_.sections[sec].cross_beams)
        g_.members.push_back({sectionNode(sec, c.nodes[0]), sectionNode(sec, c.nodes[1]), TrussMemberRole::Cross, s, Vec3::UnitX()});
  }

  /// One diagonal per bay and face, alternating (docs/truss.md): bay k runs from station k of
  /// chord a to station k + 1 of chord b when it "rises", else from k + 1 on a to k on b. The
  /// anti forms are the mirror images along the axis. A bay where the chords meet (the apex of a
  /// transition piece's triangular face) has no diagonal. Section z: the face normal (3-84).
  void addLacing() {
    const Section s = tube(d_.sub_tube);
    const bool anti = d_.lacing == LacingForm::AntiType1 || d_.lacing == LacingForm::TPAntiType1;
    for (const Face& f : faces_)
      for (int k = 0; k < d_.order; ++k) {
        if (station(f.chord_a, k) == station(f.chord_b, k) || station(f.chord_a, k + 1) == station(f.chord_b, k + 1)) continue;
        const bool rises = anti ? (d_.order - 1 - k) % 2 == 1 : k % 2 == 0;
        const int from = station(f.chord_a, rises ? k : k + 1), to = station(f.chord_b, rises ? k + 1 : k);
        g_.members.push_back({from, to, TrussMemberRole::Sub, s, f.normal});
      }
  }

  const TrussDescription& d_;
  TrussGeometry g_;
  int first_internal_ = 0;
  std::vector<Face> faces_;
};

}  // namespace

TrussGeometry buildTrussGeometry(const TrussDescription& description) {
  validate(description);
  return Builder(description).build();
}

}  // namespace cranesim
