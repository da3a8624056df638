#include "biovision_recognition/descriptor_layout.hpp"

#include <cmath>
#include <stdexcept>

namespace biovision_recognition
{
int DescriptorLayout::gridSide(int j) const
{
  // Patch extent on level k + j: (patch_wavelengths * 4) * 2^(-j/2) level px.
  const double extent = patch_wavelengths * 4.0 * std::pow(2.0, -j / 2.0);
  if (extent <= pooling_diameter)
    return 1;
  return static_cast<int>(std::floor((extent - pooling_diameter) / pooling_step)) + 1;
}

int DescriptorLayout::featureCount() const
{
  int n = 0;
  for (int j : scales)
    n += phases * orientations * gridSide(j) * gridSide(j);
  return n;
}

void DescriptorLayout::validate() const
{
  if (scales.empty())
    throw std::invalid_argument("DescriptorLayout: scales is empty");
  for (size_t i = 0; i < scales.size(); ++i)
    if (scales[i] < 0 || scales[i] > 12 || (i > 0 && scales[i] <= scales[i - 1]))
      throw std::invalid_argument("DescriptorLayout: scales must be ascending in [0, 12]");
  if (orientations < 4 || orientations > 12)
    throw std::invalid_argument("DescriptorLayout: orientations must be in [4, 12]");
  if (!(patch_wavelengths > 0 && patch_wavelengths <= 32))
    throw std::invalid_argument("DescriptorLayout: patch_wavelengths must be in (0, 32]");
  if (pooling_diameter < 1 || pooling_diameter > 16 || pooling_step < 1 || pooling_step > 16)
    throw std::invalid_argument("DescriptorLayout: pooling diameter and step must be in [1, 16]");
  if (phases != 2 && phases != 4)
    throw std::invalid_argument("DescriptorLayout: phases must be 2 or 4");
  AffineShapeAdaptation::validate(shape);
  if (gridSide(0) > kMaxGridSide)
    throw std::invalid_argument("DescriptorLayout: more than 128 pooling fields per side");
}
}  // namespace biovision_recognition
