#include "yaml_field.hpp"

#include "cranesim/model/closest_name.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>

namespace cranesim {
namespace {

std::string typeName(const YAML::Node& n) {
  switch (n.Type()) {
    case YAML::NodeType::Map: return "a mapping";
    case YAML::NodeType::Sequence: return "a list";
    case YAML::NodeType::Scalar: return fmt::format("'{}'", n.Scalar());
    case YAML::NodeType::Null: return "nothing";
    default: return "an undefined value";
  }
}

}  // namespace

SourceLocation YamlField::where() const {
  const YAML::Mark mark = node_.Mark();
  return {path_, mark.line >= 0 ? mark.line + 1 : 0, mark.column >= 0 ? mark.column + 1 : 0};
}

void YamlField::fail(const std::string& message) const { throw SceneError(where(), message); }

bool YamlField::has(const std::string& key) const { return node_.IsMap() && node_[key]; }

YamlField YamlField::at(const std::string& key) const {
  if (!node_.IsMap()) fail(fmt::format("expected a mapping with field '{}', found {}", key, typeName(node_)));
  const YAML::Node child = node_[key];
  if (!child) fail(fmt::format("missing field '{}'", key));
  return YamlField(child, path_.empty() ? key : path_ + "." + key);
}

std::optional<YamlField> YamlField::find(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return at(key);
}

namespace {
/// A key as an error message shows it: control characters (a NUL cut the message short) as \xNN.
std::string displayed(const std::string& key) {
  std::string out;
  for (const unsigned char c : key)
    out += c < 0x20 || c == 0x7f ? fmt::format("\\x{:02x}", c) : std::string(1, static_cast<char>(c));
  return out;
}

/// Where a key of this mapping is: a key set by a composing scene (base + its own keys or `modify`)
/// is a new node without a place in any file; its value keeps the place where the composing scene
/// wrote it.
SourceLocation keyLocation(const std::string& path, const std::string& key, const YAML::Node& key_node,
                           const YAML::Node& value) {
  const YAML::Mark mark = key_node.Mark().is_null() ? value.Mark() : key_node.Mark();
  return {path.empty() ? key : path + "." + key, mark.line + 1, mark.column + 1};
}
}  // namespace

void YamlField::rejectDuplicateKeys() const {
  if (!node_.IsMap()) fail(fmt::format("expected a mapping, found {}", typeName(node_)));
  std::vector<std::string> seen;
  for (const auto& kv : node_) {
    const std::string key = displayed(kv.first.as<std::string>());
    if (std::find(seen.begin(), seen.end(), key) != seen.end())
      throw SceneError(keyLocation(path_, key, kv.first, kv.second), fmt::format("duplicate key '{}'", key));
    seen.push_back(key);
  }
}

void YamlField::allowKeys(const std::vector<const char*>& allowed) const {
  rejectDuplicateKeys();
  for (const auto& kv : node_) {
    const std::string key = displayed(kv.first.as<std::string>());
    if (std::any_of(allowed.begin(), allowed.end(), [&](const char* a) { return key == a; })) continue;
    const std::string best = closestName(key, std::vector<std::string>(allowed.begin(), allowed.end()));
    std::string allowed_list;
    for (const char* a : allowed) allowed_list += (allowed_list.empty() ? "" : ", ") + std::string(a);
    throw SceneError(keyLocation(path_, key, kv.first, kv.second),
                     best.empty() ? fmt::format("unknown key '{}' (allowed: {})", key, allowed_list)
                                  : fmt::format("unknown key '{}'; did you mean '{}'?", key, best));
  }
}

double YamlField::number() const {
  if (!node_.IsScalar()) fail(fmt::format("expected a number, found {}", typeName(node_)));
  double value = 0.0;
  if (!YAML::convert<double>::decode(node_, value) || !std::isfinite(value))
    fail(fmt::format("expected a finite number, found {}", typeName(node_)));
  return value;
}

double YamlField::positive() const {
  const double x = number();
  if (!(x > 0.0)) fail(fmt::format("must be positive, found {}", x));
  return x;
}

double YamlField::nonNegative() const {
  const double x = number();
  if (x < 0.0) fail(fmt::format("must not be negative, found {}", x));
  return x;
}

std::uint64_t YamlField::seed() const {
  const double x = number();
  if (x < 0.0 || x != std::floor(x) || x > 9.0e15) fail(fmt::format("expected a whole number ≥ 0, found {:g}", x));
  return static_cast<std::uint64_t>(x);
}

int YamlField::integer() const {
  const double x = number();
  if (x != std::floor(x)) fail(fmt::format("expected an integer, found {}", x));
  if (std::abs(x) > std::numeric_limits<int>::max()) fail(fmt::format("expected an integer below 2³¹, found {:g}", x));
  return static_cast<int>(x);
}

bool YamlField::boolean() const {
  bool value = false;
  if (!node_.IsScalar() || !YAML::convert<bool>::decode(node_, value))
    fail(fmt::format("expected true or false, found {}", typeName(node_)));
  return value;
}

std::string YamlField::text() const {
  if (!node_.IsScalar()) fail(fmt::format("expected a string, found {}", typeName(node_)));
  return node_.Scalar();
}

std::string YamlField::identifier() const {
  const std::string name = text();
  const bool valid = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
  });
  if (!valid) fail(fmt::format("'{}' is not a valid name: use letters, digits, '_' and '-'", name));
  return name;
}

std::vector<double> YamlField::numbers() const {
  std::vector<double> out;
  for (const YamlField& item : items()) out.push_back(item.number());
  return out;
}

Vec3 YamlField::vec3() const {
  if (!node_.IsSequence() || node_.size() != 3)
    fail(fmt::format("expected a list of 3 numbers, found {}", typeName(node_)));
  const std::vector<double> v = numbers();
  return {v[0], v[1], v[2]};
}

std::array<Vec3, 2> YamlField::tippingLine() const {
  const std::vector<YamlField> points = items();
  if (points.size() != 2) fail(fmt::format("a tipping line is two points [[x, y, z], [x, y, z]], found {}", points.size()));
  const std::array<Vec3, 2> line{points[0].vec3(), points[1].vec3()};
  if (!((line[1] - line[0]).norm() > 1e-9)) fail("the tipping line's two points coincide");
  return line;
}

Vec3 YamlField::position() const {
  const Vec3 p = vec3();
  if (p.cwiseAbs().maxCoeff() > kMaxCoordinate)
    fail(fmt::format("a point {:g} m from the origin: scene geometry must lie within {:g} m of it",
                     p.cwiseAbs().maxCoeff(), kMaxCoordinate));
  return p;
}

double YamlField::within(double low, double high, const char* unit) const {
  const double x = positive();
  if (x < low || x > high) fail(fmt::format("{:g} {} lies outside [{:g}, {:g}] {}", x, unit, low, high, unit));
  return x;
}

std::vector<YamlField> YamlField::items() const {
  if (!node_.IsSequence()) fail(fmt::format("expected a list, found {}", typeName(node_)));
  std::vector<YamlField> out;
  for (std::size_t k = 0; k < node_.size(); ++k) out.emplace_back(node_[k], fmt::format("{}[{}]", path_, k));
  return out;
}

std::vector<std::string> YamlField::keys() const {
  if (!node_.IsMap()) fail(fmt::format("expected a mapping, found {}", typeName(node_)));
  rejectDuplicateKeys();
  std::vector<std::string> out;
  for (const auto& entry : node_) {
    if (!entry.first.IsScalar()) fail("a key must be a name");
    out.push_back(entry.first.Scalar());
  }
  return out;
}

std::string YamlField::choice(std::initializer_list<const char*> choices) const {
  const std::string value = text();
  std::string list;
  for (const char* c : choices) {
    if (value == c) return value;
    list += (list.empty() ? "" : ", ") + std::string(c);
  }
  fail(fmt::format("'{}' is not one of: {}", value, list));
}

double YamlField::number(const std::string& key, double fallback) const {
  const auto f = find(key);
  return f ? f->number() : fallback;
}

double YamlField::positive(const std::string& key, double fallback) const {
  const auto f = find(key);
  return f ? f->positive() : fallback;
}

Vec3 YamlField::position(const std::string& key, const Vec3& fallback) const {
  const auto f = find(key);
  return f ? f->position() : fallback;
}

Vec3 YamlField::vec3(const std::string& key, const Vec3& fallback) const {
  const auto f = find(key);
  return f ? f->vec3() : fallback;
}

void applyMergeKeys(YAML::Node node, const std::string& path) {
  if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i) applyMergeKeys(node[i], fmt::format("{}[{}]", path, i));
    return;
  }
  if (!node.IsMap()) return;
  const std::string child_prefix = path.empty() ? "" : path + ".";
  if (const YAML::Node merge = node["<<"]) {
    std::vector<YAML::Node> sources;
    if (merge.IsMap()) sources.push_back(merge);
    if (merge.IsSequence())
      for (const YAML::Node& item : merge) sources.push_back(item);
    if (sources.empty() || std::any_of(sources.begin(), sources.end(), [](const YAML::Node& n) { return !n.IsMap(); }))
      YamlField(merge, child_prefix + "<<").fail("a merge key '<<' takes a mapping (*anchor) or a list of mappings");
    node.remove("<<");
    for (const YAML::Node& source : sources)
      for (const auto& kv : source)
        if (!node[kv.first.as<std::string>()]) node[kv.first.as<std::string>()] = kv.second;
  }
  for (const auto& kv : node) applyMergeKeys(kv.second, child_prefix + kv.first.as<std::string>());
}

}  // namespace cranesim
