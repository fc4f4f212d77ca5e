#pragma once
// "Did you mean": the known name closest to a misspelt one, for error messages.

#include <string>
#include <vector>

namespace cranesim {

/// Levenshtein distance: the fewest single-character insertions, deletions and substitutions
/// that turn `a` into `b`.
std::size_t editDistance(const std::string& a, const std::string& b);

/// The candidate closest to `name` by edit distance, if it is close enough to be a likely typo
/// (at most 2 edits, or a quarter of the name's length for long names); empty otherwise.
std::string closestName(const std::string& name, const std::vector<std::string>& candidates);

/// "no <what> named 'x' (did you mean 'y'?); the scene's <what>s: a, b, …" (or "; the scene has
/// no <what>s"): the message for a name that is not among `names`.
std::string unknownName(const std::string& what, const std::string& name, const std::vector<std::string>& names);

/// Names for an error message: "a, b, c", or "none" when there are none.
std::string listedNames(const std::vector<std::string>& names);

/// The names of named items (joints, constraints, inputs, …), in their order: the candidates.
template <class Items> std::vector<std::string> namesOf(const Items& items) {
  std::vector<std::string> names;
  for (const auto& item : items) names.push_back(item.name);
  return names;
}

}  // namespace cranesim
