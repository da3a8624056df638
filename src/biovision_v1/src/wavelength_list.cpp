#include "biovision_v1/wavelength_list.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace biovision_v1
{
std::vector<double> parseWavelengthList(const std::string& text)
{
  std::string s = text;
  std::replace(s.begin(), s.end(), ',', ' ');
  std::istringstream in(s);
  std::vector<double> values;
  double v;
  while (in >> v)
    values.push_back(v);
  if (!in.eof() || values.empty())
    throw std::invalid_argument("wavelengths '" + text + "' is not a list of numbers");
  return values;
}
}  // namespace biovision_v1
