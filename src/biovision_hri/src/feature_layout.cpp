#include "biovision_hri/feature_layout.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "biovision_common/payload_reader.hpp"
#include "biovision_common/payload_writer.hpp"

namespace biovision_hri
{
namespace
{
void check(bool ok, const std::string& message)
{
  if (!ok)
    throw std::invalid_argument("FeatureLayout: " + message);
}
}  // namespace

void FeatureLayout::validate() const
{
  check(std::isfinite(wavelength) && wavelength >= 2.0 && wavelength <= 16.0,
        "wavelength must be in [2, 16] px, got " + std::to_string(wavelength));
  check(orientations >= 4 && orientations <= 12,
        "orientations must be in [4, 12], got " + std::to_string(orientations));
  check(std::isfinite(aspect_ratio) && aspect_ratio > 0.0 && aspect_ratio <= 1.0,
        "aspect_ratio must be in (0, 1], got " + std::to_string(aspect_ratio));
  check(cell_size >= 3 && cell_size <= 16, "cell_size must be in [3, 16] px, got " + std::to_string(cell_size));
  check(block_cells >= 1 && block_cells <= 4, "block_cells must be in [1, 4], got " + std::to_string(block_cells));
  check(window_blocks >= 1 && window_blocks <= 12,
        "window_blocks must be in [1, 12], got " + std::to_string(window_blocks));
  check(std::isfinite(epsilon) && epsilon >= 0.0 && epsilon <= 1.0,
        "epsilon must be in [0, 1], got " + std::to_string(epsilon));
  check(std::isfinite(clip) && clip >= 0.0 && clip <= 1.0, "clip must be in [0, 1], got " + std::to_string(clip));
  check(grid_step == 1 || (grid_step == 2 && wavelength >= 4.0),
        "grid_step must be 1, or 2 with wavelength >= 4 px, got " + std::to_string(grid_step) + " (wavelength " +
            std::to_string(wavelength) + ")");
}

void FeatureLayout::write(biovision_common::PayloadWriter& w) const
{
  w.put<double>(wavelength);
  w.put<int32_t>(orientations);
  w.put<int32_t>(cell_size);
  w.put<int32_t>(block_cells);
  w.put<int32_t>(window_blocks);
  w.put<double>(epsilon);
  w.put<int32_t>(grid_step);
  w.put<double>(clip);
  w.put<double>(aspect_ratio);
}

FeatureLayout FeatureLayout::read(biovision_common::PayloadReader& r)
{
  FeatureLayout l;
  l.wavelength = r.get<double>();
  l.orientations = r.get<int32_t>();
  l.cell_size = r.get<int32_t>();
  l.block_cells = r.get<int32_t>();
  l.window_blocks = r.get<int32_t>();
  l.epsilon = r.get<double>();
  l.grid_step = r.get<int32_t>();
  l.clip = r.get<double>();
  l.aspect_ratio = r.get<double>();
  l.validate();
  return l;
}
}  // namespace biovision_hri
