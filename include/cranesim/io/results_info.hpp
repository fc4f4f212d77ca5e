#pragma once

#include <string>

namespace cranesim {

/// A plain-text description of a results file: attributes, datasets and their shapes,
/// solver statistics. Throws std::runtime_error when the file is not a readable HDF5 file.
std::string describeResults(const std::string& path);

}  // namespace cranesim
