#include "cranesim/io/study_writer.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

#include "cranesim/version.hpp"
#include "hdf5_file.hpp"

namespace cranesim {
namespace {

const char* analysisName(StudyAnalysis analysis) {
  switch (analysis) {
    case StudyAnalysis::Static: return "static";
    case StudyAnalysis::Run: return "run";
    case StudyAnalysis::Modes: return "modes";
  }
  return "";
}

std::string describe(const Study& study, const StudyParameter& p) {
  if (p.scene_index) {
    std::string scenes = "the scene, its index in scenes:";
    for (std::size_t k = 0; k < study.scene_paths.size(); ++k) scenes += fmt::format(" {} = {}", k, study.scene_paths[k]);
    return scenes;
  }
  if (p.scales_with)
    return fmt::format("scales with {}: the factor on the base scene's value", study.parameters[*p.scales_with].path);
  if (!p.random) return "grid";
  const RandomDistribution& d = *p.random;
  switch (d.kind) {
    case RandomDistribution::Kind::Uniform: return fmt::format("uniform on [{}, {}]", d.low, d.high);
    case RandomDistribution::Kind::Normal: return fmt::format("normal, mean {}, std {}", d.mean, d.std_dev);
    case RandomDistribution::Kind::TruncatedNormal:
      return fmt::format("normal, mean {}, std {}, truncated to [{}, {}]", d.mean, d.std_dev, d.low, d.high);
  }
  return "";
}

}  // namespace

void writeStudyResults(const std::string& path, const Study& study, const std::vector<CaseRow>& rows,
                       const std::string& message, const std::string& execution) {
  const hsize_t n = rows.size();
  writeResultsFile(path, [&](Hdf5File& file) {
    file.attribute("/", "contents", std::string("study"));
    file.attribute("/", "engine_version", std::string(kVersion));
    file.attribute("/", "study_path", study.path);
    file.attribute("/", "study_text", study.text);
    file.attribute("/", "scene_path", study.scene_path);
    file.attribute("/", "scene_text", study.scene_text);
    file.attribute("/", "analysis", std::string(analysisName(study.analysis)));
    file.attribute("/", "seed", static_cast<long>(study.seed));
    file.attribute("/", "cases", static_cast<long>(n));
    file.attribute("/", "status", std::string(message.empty() ? "complete" : "incomplete"));
    file.attribute("/", "message", message);
    file.attribute("/", "execution", execution);
    std::vector<std::vector<double>> parameters(study.parameters.size(), std::vector<double>(n));
    for (std::size_t i = 0; i < n; ++i) {
      const std::vector<double> values = study.parameterValues(static_cast<long>(i));
      for (std::size_t k = 0; k < values.size(); ++k) parameters[k][i] = values[k];
    }
    for (std::size_t k = 0; k < study.parameters.size(); ++k) {
      const std::string dataset = "/parameters/" + study.parameters[k].path;
      file.writeDoubles(dataset, {n}, parameters[k].data());
      file.attribute(dataset, "values", describe(study, study.parameters[k]));
    }
    std::vector<double> column(n);
    file.ensureGroup("/parameters");
    file.ensureGroup("/figures");
    for (std::size_t k = 0; k < study.figures.size(); ++k) {
      for (std::size_t i = 0; i < n; ++i) column[i] = rows[i].figures[k];
      file.writeDoubles("/figures/" + study.figures[k].name, {n}, column.data());
    }
    if (!study.criteria.empty()) {
      std::vector<double> admissible(n, 1.0);
      for (std::size_t k = 0; k < study.criteria.size(); ++k) {
        const StudyCriterion& c = study.criteria[k];
        for (std::size_t i = 0; i < n; ++i) {
          column[i] = c.holds(rows[i].figures[c.figure]);
          admissible[i] = std::isnan(column[i]) ? column[i] : std::min(admissible[i], column[i]);
        }
        const std::string dataset = fmt::format("/criteria/{}", k);
        file.writeDoubles(dataset, {n}, column.data());
        file.attribute(dataset, "figure", study.figures[c.figure].name);
        file.attribute(dataset, "min", c.min);
        file.attribute(dataset, "max", c.max);
        file.attribute(dataset, "source", c.source);
      }
      file.writeDoubles("/cases/admissible", {n}, admissible.data());
    }
    if (study.capacity) {
      const CapacitySpec& c = *study.capacity;
      file.ensureGroup("/capacity");
      file.attribute("/capacity", "load_path", c.load);
      file.attribute("/capacity", "from", c.from);
      file.attribute("/capacity", "to", c.to);
      file.attribute("/capacity", "tolerance", c.tolerance);
      file.attribute("/capacity", "scales", fmt::format("{}", fmt::join(c.scales, ", ")));
      for (std::size_t i = 0; i < n; ++i) column[i] = rows[i].capacity;
      file.writeDoubles("/capacity/load", {n}, column.data());
      for (std::size_t i = 0; i < n; ++i) column[i] = rows[i].inadmissible_load;
      file.writeDoubles("/capacity/inadmissible_load", {n}, column.data());
      std::vector<std::string> limited_by(n);
      for (std::size_t i = 0; i < n; ++i) limited_by[i] = rows[i].limited_by;
      file.writeStrings("/capacity/limited_by", {n}, limited_by);
    }
    if (study.least_stable) {
      const LeastStableAngleSpec& search = *study.least_stable;
      file.ensureGroup("/least_stable");
      file.attribute("/least_stable", "angle_path", search.angle);
      file.attribute("/least_stable", "grid", fmt::format("{}", fmt::join(search.grid, ", ")));
      file.attribute("/least_stable", "figure", study.figures[search.figure].name);
      file.attribute("/least_stable", "worst", std::string(search.worst_is_max ? "max" : "min"));
      file.attribute("/least_stable", "tolerance", search.tolerance);
      for (std::size_t i = 0; i < n; ++i) column[i] = rows[i].least_stable_angle;
      file.writeDoubles("/least_stable/angle", {n}, column.data());
      for (std::size_t i = 0; i < n; ++i) column[i] = rows[i].worst_grid_angle;
      file.writeDoubles("/least_stable/grid_angle", {n}, column.data());
      for (std::size_t i = 0; i < n; ++i) column[i] = rows[i].least_stable_value;
      file.writeDoubles("/least_stable/value", {n}, column.data());
    }
    std::vector<std::string> status(n), messages(n), workers(n);
    for (std::size_t i = 0; i < n; ++i) status[i] = rows[i].status, messages[i] = rows[i].message, workers[i] = rows[i].worker;
    file.writeStrings("/cases/status", {n}, status);
    file.writeStrings("/cases/message", {n}, messages);
    file.writeStrings("/cases/worker", {n}, workers);
    for (std::size_t i = 0; i < n; ++i) column[i] = rows[i].steps;
    file.writeDoubles("/cases/steps", {n}, column.data());
    for (std::size_t i = 0; i < n; ++i) column[i] = rows[i].wall_time_s;
    file.writeDoubles("/cases/wall_time_s", {n}, column.data());
  });
}

}  // namespace cranesim
