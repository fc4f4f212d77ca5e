#include "cranesim/study/case_row.hpp"

#include <fmt/format.h>

#include <bit>
#include <cstdint>
#include <sstream>

namespace cranesim {
namespace {

std::string bitsOf(double x) { return fmt::format("{:016x}", std::bit_cast<std::uint64_t>(x)); }

std::optional<double> doubleOf(const std::string& hex) {
  if (hex.size() != 16) return std::nullopt;
  std::uint64_t bits = 0;
  for (const char c : hex) {
    const int digit = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
    if (digit < 0) return std::nullopt;
    bits = bits << 4 | static_cast<std::uint64_t>(digit);
  }
  return std::bit_cast<double>(bits);
}

/// Messages may hold anything; on the line, '\\', tab and newline are escaped.
std::string escaped(const std::string& text) {
  std::string out;
  for (const char c : text) out += c == '\\' ? "\\\\" : c == '\t' ? "\\t" : c == '\n' ? "\\n" : std::string(1, c);
  return out;
}

std::string unescaped(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '\\' || i + 1 == text.size()) {
      out += text[i];
      continue;
    }
    const char c = text[++i];
    out += c == 't' ? '\t' : c == 'n' ? '\n' : c;
  }
  return out;
}

}  // namespace

std::string encodeRow(const CaseRow& row) {
  std::string line =
      fmt::format("{}\t{}\t{}\t{}\t{}", row.index, row.status, bitsOf(row.steps), bitsOf(row.wall_time_s), escaped(row.worker));
  for (const double f : row.figures) line += "\t" + bitsOf(f);
  line += fmt::format("\t{}\t{}\t{}", bitsOf(row.capacity), bitsOf(row.inadmissible_load), escaped(row.limited_by));
  line += fmt::format("\t{}\t{}\t{}", bitsOf(row.least_stable_angle), bitsOf(row.worst_grid_angle), bitsOf(row.least_stable_value));
  return line + "\t" + escaped(row.message);
}

std::optional<CaseRow> decodeRow(const std::string& line, std::size_t figures) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  for (std::string field; std::getline(in, field, '\t');) fields.push_back(field);
  if (!line.empty() && line.back() == '\t') fields.emplace_back();  // an empty message
  if (fields.size() != 12 + figures) return std::nullopt;
  CaseRow row;
  try {
    std::size_t used = 0;
    row.index = std::stol(fields[0], &used);
    if (used != fields[0].size() || row.index < 0) return std::nullopt;
  } catch (const std::exception&) {
    return std::nullopt;
  }
  row.status = fields[1];
  const auto steps = doubleOf(fields[2]), wall = doubleOf(fields[3]);
  if (!steps || !wall) return std::nullopt;
  row.steps = *steps;
  row.wall_time_s = *wall;
  row.worker = unescaped(fields[4]);
  for (std::size_t k = 0; k < figures; ++k) {
    const auto value = doubleOf(fields[5 + k]);
    if (!value) return std::nullopt;
    row.figures.push_back(*value);
  }
  const auto capacity = doubleOf(fields[5 + figures]), inadmissible = doubleOf(fields[6 + figures]);
  if (!capacity || !inadmissible) return std::nullopt;
  row.capacity = *capacity;
  row.inadmissible_load = *inadmissible;
  row.limited_by = unescaped(fields[7 + figures]);
  const auto angle = doubleOf(fields[8 + figures]), grid_angle = doubleOf(fields[9 + figures]), value = doubleOf(fields[10 + figures]);
  if (!angle || !grid_angle || !value) return std::nullopt;
  row.least_stable_angle = *angle;
  row.worst_grid_angle = *grid_angle;
  row.least_stable_value = *value;
  row.message = unescaped(fields.back());
  return row;
}

}  // namespace cranesim
