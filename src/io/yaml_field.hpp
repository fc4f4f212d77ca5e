#pragma once
// A YAML node together with its path in the document, for reading with precise errors.

#include <yaml-cpp/yaml.h>

#include <array>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include "cranesim/math/types.hpp"
#include "cranesim/model/source_location.hpp"

namespace cranesim {

class YamlField {
 public:
  YamlField(YAML::Node node, std::string path) : node_(std::move(node)), path_(std::move(path)) {}

  const std::string& path() const { return path_; }
  const YAML::Node& node() const { return node_; }
  SourceLocation where() const;
  [[noreturn]] void fail(const std::string& message) const;

  bool isMap() const { return node_.IsMap(); }
  bool isSequence() const { return node_.IsSequence(); }
  bool isScalar() const { return node_.IsScalar(); }
  bool has(const std::string& key) const;

  /// The value under `key`; fails with "missing field" when absent.
  YamlField at(const std::string& key) const;
  std::optional<YamlField> find(const std::string& key) const;
  /// Fails on any key not in `allowed`, suggesting the closest allowed key.
  void allowKeys(const std::vector<const char*>& allowed) const;
  /// Fails at the second occurrence of a key in this mapping (yaml-cpp keeps both).
  void rejectDuplicateKeys() const;

  double number() const;
  double positive() const;
  double nonNegative() const;
  /// A positive number within [low, high] of a physical `unit`: values far outside what any
  /// crane uses (a radius of 1e-308 m, a density of 1e308) become a massless or overflowing
  /// model, which no solver reports at the scene's line.
  double within(double low, double high, const char* unit) const;
  int integer() const;
  /// A random generator's seed: a whole number ≥ 0.
  std::uint64_t seed() const;
  bool boolean() const;
  std::string text() const;
  /// A name usable in joint references and HDF5 paths: letters, digits, '_' and '-'.
  std::string identifier() const;
  Vec3 vec3() const;
  /// A point of the scene's geometry, m: three numbers within kMaxCoordinate of the origin.
  Vec3 position() const;
  /// A directed line [[x, y, z], [x, y, z]] of two distinct points (a tipping edge).
  std::array<Vec3, 2> tippingLine() const;
  std::vector<double> numbers() const;
  std::vector<YamlField> items() const;
  /// The keys of a mapping (scalars, duplicates refused), in the document's order.
  std::vector<std::string> keys() const;
  /// One of `choices`; fails listing them.
  std::string choice(std::initializer_list<const char*> choices) const;

  double number(const std::string& key, double fallback) const;
  double positive(const std::string& key, double fallback) const;
  Vec3 vec3(const std::string& key, const Vec3& fallback) const;
  Vec3 position(const std::string& key, const Vec3& fallback) const;

  /// Geometry beyond this distance (m) is refused: no crane comes near it, and coordinates of
  /// 1e308 overflowed into a singular mass matrix instead of an input error (found by
  /// tests/fuzz/input_mutants.py).
  static constexpr double kMaxCoordinate = 1e5;

 private:
  YAML::Node node_;
  std::string path_;
};

/// Applies YAML merge keys (`<<: *anchor` or `<<: [*a, *b]`) in place, which yaml-cpp 0.7 parses
/// but does not apply: keys of the merged mappings that the mapping lacks are copied into it
/// (earlier sources win), and the `<<` key is removed. Fails on a `<<` that is not a mapping or
/// a list of mappings.
void applyMergeKeys(YAML::Node node, const std::string& path = "");

}  // namespace cranesim
