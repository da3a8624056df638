#pragma once

#include <string>
#include <vector>

namespace biovision_v1
{
/// Parses a list of wavelengths as users write it in YAML or dynamic_reconfigure ("4 8 16", "4,8,16").
/// Throws std::invalid_argument quoting the text when it is not a non-empty list of numbers; range and
/// order are checked by the parameter structs that use it.
std::vector<double> parseWavelengthList(const std::string& text);
}  // namespace biovision_v1
