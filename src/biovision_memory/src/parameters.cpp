#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "biovision_memory/disparity_camera.hpp"
#include "biovision_memory/short_term_memory_parameters.hpp"
#include "biovision_memory/view_scan_parameters.hpp"

namespace biovision_memory
{
namespace
{
void requireRange(const char* owner, const char* field, double value, double lo, double hi, bool lo_open = false)
{
  const bool ok = std::isfinite(value) && (lo_open ? value > lo : value >= lo) && value <= hi;
  if (!ok)
  {
    std::ostringstream m;
    m << owner << "." << field << " = " << value << " is outside " << (lo_open ? "(" : "[") << lo << ", " << hi << "]";
    throw std::invalid_argument(m.str());
  }
}
}  // namespace

void DisparityCamera::validate() const
{
  requireRange("DisparityCamera", "fx", fx, 0.0, 1e6, true);
  requireRange("DisparityCamera", "fy", fy, 0.0, 1e6, true);
  requireRange("DisparityCamera", "cx", cx, -1e6, 1e6);
  requireRange("DisparityCamera", "cy", cy, -1e6, 1e6);
  requireRange("DisparityCamera", "baseline", baseline, 0.0, 100.0, true);
}

void ViewScanParameters::validate() const
{
  const char* o = "ViewScanParameters";
  requireRange(o, "max_range", max_range, 0.3, 20.0, true);
  requireRange(o, "min_obstacle_height", min_obstacle_height, 0.0, 1.0);
  if (min_obstacle_height >= 1.0)
    throw std::invalid_argument("ViewScanParameters.min_obstacle_height must be < 1");
  requireRange(o, "max_obstacle_height", max_obstacle_height, min_obstacle_height, 5.0, true);
  requireRange(o, "strips", strips, 1, 15);
  requireRange(o, "min_obstacle_pixels", min_obstacle_pixels, 1, 1000);
  requireRange(o, "min_valid_fraction", min_valid_fraction, 0.0, 1.0);
  requireRange(o, "bin_width", bin_width, 0.002, 0.2);
  requireRange(o, "pixel_step", pixel_step, 1, 8);
}

void ShortTermMemoryParameters::validate() const
{
  scan.validate();
  const char* o = "ShortTermMemoryParameters";
  requireRange(o, "sectors", sectors, 1, 36);
  requireRange(o, "sector_width", sector_width, 0.0, 2.0 * M_PI / sectors + 1e-9, true);
  requireRange(o, "obstacle_horizon_time", obstacle_horizon_time, 0.0, 600.0, true);
  requireRange(o, "free_horizon_time", free_horizon_time, 0.0, 600.0, true);
  requireRange(o, "horizon_distance", horizon_distance, 0.0, 100.0, true);
  requireRange(o, "map_completion_radius", map_completion_radius, 0.0, 10.0);
}
}  // namespace biovision_memory
