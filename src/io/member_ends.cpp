#include "member_ends.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "cranesim/math/rotation.hpp"

namespace cranesim {
namespace {

const TrussDescription* trussType(const Scene& scene, const MemberSpec& m) {
  for (const TrussDescription& d : scene.trusses)
    if (d.name == m.truss) return &d;
  return nullptr;
}

/// Where a member's far end is built: a truss lies along its drawn direction at its type's length.
Vec3 builtEnd(const Scene& scene, const MemberSpec& m) {
  if (m.type != MemberType::Truss) return m.end;
  return m.start + trussType(scene, m)->length * (m.end - m.start).normalized();
}

std::optional<int> indexAfter(const std::string& text, const std::string& prefix) {
  if (text.size() <= prefix.size() || text.compare(0, prefix.size(), prefix) != 0) return std::nullopt;
  const std::string digits = text.substr(prefix.size());
  if (digits.size() > 6 || !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return std::nullopt;
  return std::stoi(digits);
}

/// Resolves joint names to drawn positions; members are placed on first use.
class DrawnJoints {
 public:
  explicit DrawnJoints(Scene& scene) : scene_(scene) {
    for (std::size_t i = 0; i < scene.members.size(); ++i) member_index_[scene.members[i].name] = i;
  }

  void place(MemberSpec& m) {
    if (placed_.count(m.name)) return;
    placing_.insert(m.name);
    chain_.push_back(m.name);
    if (m.reeving) placeReeving(m);
    if (!m.start_joint.empty()) m.start = position(m.start_joint, m.where_start);
    if (!m.end_joint.empty()) m.end = position(m.end_joint, m.where_end);
    chain_.pop_back();
    placing_.erase(m.name);
    placed_.insert(m.name);
  }

 private:
  /// A reeved rope's drawn path: its ends (start: the winch, end: the dead end) and the sum of
  /// its parts' chords, each part at least as long as its sheaves' radii.
  void placeReeving(MemberSpec& m) {
    ReevingSpec& r = *m.reeving;
    std::vector<Vec3> points = {position(r.winch, r.where_winch)};
    std::vector<double> radii = {0.0};
    std::vector<SourceLocation> where = {r.where_winch};
    for (const SheaveSpec& s : r.sheaves) {
      points.push_back(position(s.joint, s.where));
      radii.push_back(s.radius);
      where.push_back(s.where);
    }
    points.push_back(position(r.dead_end, r.where_dead_end));
    radii.push_back(0.0);
    where.push_back(r.where_dead_end);
    r.drawn_length = 0.0;
    for (std::size_t k = 0; k + 1 < points.size(); ++k) {
      const double chord = (points[k + 1] - points[k]).norm();
      if (!(chord > radii[k] + radii[k + 1]))
        throw SceneError(where[k + 1], fmt::format("rope '{}': its part {} (from path point {} to {}) is {:.6g} m long in "
                                                   "the drawing, not longer than its sheaves' radii ({:g} m): the points "
                                                   "of a path must lie apart", m.name, k + 1, k, k + 1, chord,
                                                   radii[k] + radii[k + 1]));
      r.drawn_length += chord;
    }
    for (std::size_t i = 0; i < r.sheaves.size(); ++i) {
      SheaveSpec& s = r.sheaves[i];
      if (s.friction == 0.0 || s.wrap) continue;
      // a capstan's wrap: the angle the drawn path turns at its centre, between its two parts
      const Vec3 in = points[i + 1] - points[i], out = points[i + 2] - points[i + 1];
      s.wrap = std::atan2(in.cross(out).norm(), in.dot(out));
    }
    m.start = points.front();
    m.end = points.back();
  }

  Vec3 position(const std::string& name, const SourceLocation& where) {
    const std::size_t dot = name.find('.');
    if (dot == std::string::npos || dot == 0 || dot + 1 == name.size())
      throw SceneError(where, fmt::format("'{}' is neither coordinates [x, y, z] nor a joint '<part>.<joint>'", name));
    const std::string part = name.substr(0, dot), joint = name.substr(dot + 1);
    if (part == "ground") {
      for (const JointSpec& j : scene_.ground_joints)
        if (j.name == joint) return j.position;
      throw SceneError(where, fmt::format("unknown joint '{}': the ground has no joint '{}'", name, joint));
    }
    for (const RigidBodySpec& b : scene_.bodies) {
      if (b.name != part) continue;
      if (joint == "origin") return b.position;
      for (const JointSpec& j : b.joints)
        if (j.name == joint) return b.position + b.rotation * j.position;
      throw SceneError(where, fmt::format("unknown joint '{}': body '{}' has no joint '{}'", name, part, joint));
    }
    const auto found = member_index_.find(part);
    if (found == member_index_.end())
      throw SceneError(where, fmt::format("unknown joint '{}': no body or member is named '{}'", name, part));
    MemberSpec& m = scene_.members[found->second];
    if (placing_.count(m.name)) {
      std::string cycle;
      for (auto c = std::find(chain_.begin(), chain_.end(), m.name); c != chain_.end(); ++c) cycle += *c + " → ";
      throw SceneError(where, fmt::format("members' ends name each other in a cycle ({}{}); give one of them "
                                          "coordinates", cycle, m.name));
    }
    place(m);
    return memberJoint(m, joint, name, where);
  }

  Vec3 memberJoint(const MemberSpec& m, const std::string& joint, const std::string& name, const SourceLocation& where) {
    if (joint == "start") return m.start;
    if (joint == "end") return builtEnd(scene_, m);
    if (m.type == MemberType::Truss) {
      // <member>.s<section>n<node>: a node of an end section (numbered from 1).
      const TrussDescription& d = *trussType(scene_, m);
      const std::size_t n_at = joint.find('n');
      const std::optional<int> section = n_at == std::string::npos ? std::nullopt : indexAfter(joint.substr(0, n_at), "s");
      const std::optional<int> node = n_at == std::string::npos ? std::nullopt : indexAfter(joint.substr(n_at), "n");
      if (section && node && *section >= 1 && *section <= 2 && *node >= 1 &&
          *node <= static_cast<int>(d.sections[*section - 1].nodes.size())) {
        const Eigen::Vector2d yz = d.sections[*section - 1].nodes[*node - 1];
        const Vec3 local(*section == 1 ? 0.0 : d.length, yz.x(), yz.y());
        return m.start + memberFrame(m.start, m.end, m.z_axis) * local;
      }
      throw SceneError(where, fmt::format("'{}' is not a joint a member end can name: truss member '{}' offers "
                                          "start, end and its end sections' nodes s1n1 … s2n{}",
                                          name, m.name, d.sections[1].nodes.size()));
    }
    const std::optional<int> i = indexAfter(joint, "n");
    if (i && *i <= m.segments) return m.start + (static_cast<double>(*i) / m.segments) * (m.end - m.start);
    throw SceneError(where, fmt::format("'{}' is not a joint a member end can name: member '{}' offers start, end "
                                        "and its nodes n0 … n{}", name, m.name, m.segments));
  }

  Scene& scene_;
  std::map<std::string, std::size_t> member_index_;
  std::set<std::string> placed_, placing_;
  std::vector<std::string> chain_;
};

}  // namespace

void placeMemberEnds(Scene& scene) {
  DrawnJoints joints(scene);
  for (MemberSpec& m : scene.members) joints.place(m);
  for (const MemberSpec& m : scene.members) {
    if (m.reeving) continue;  // its path is checked by placeReeving
    const double distance = (m.end - m.start).norm();
    if (distance < 1e-9) throw SceneError(m.where_end, "a member needs distinct start and end points");
    if (m.type != MemberType::Truss) continue;
    const double length = trussType(scene, m)->length;
    if (std::abs(distance - length) > scene.solver.assembly_tolerance * length)
      throw SceneError(m.where_end, fmt::format("|end − start| = {:.7g} differs from the length {} of truss type '{}' "
                                                "by more than solver.assembly_tolerance = {:g} of it",
                                                distance, length, m.truss, scene.solver.assembly_tolerance));
  }
}

}  // namespace cranesim
