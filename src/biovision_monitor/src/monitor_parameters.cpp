#include "biovision_monitor/monitor_parameters.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace biovision_monitor
{
namespace
{
void require(bool ok, const std::string& field, const std::string& range, double value)
{
  if (ok)
    return;
  std::ostringstream s;
  s << "MonitorParameters: " << field << " = " << value << " outside " << range;
  throw std::invalid_argument(s.str());
}
}  // namespace

void MonitorParameters::validate() const
{
  require(rate > 0 && rate <= 60, "rate", "(0, 60] Hz", rate);
  require(columns >= 1 && columns <= 8, "columns", "[1, 8]", columns);
  require(tile_width >= 64 && tile_width <= 1920, "tile_width", "[64, 1920] px", tile_width);
  require(tile_height >= 48 && tile_height <= 1080, "tile_height", "[48, 1080] px", tile_height);
  require(stale_after > 0, "stale_after", "> 0 s", stale_after);
  require(saliency_threshold >= 0 && saliency_threshold <= 1, "saliency_threshold", "[0, 1]", saliency_threshold);
  for (const auto& [name, field] : namedDoubles())
  {
    const double v = this->*field;
    require(std::isfinite(v), name, "finite values", v);
    if (name.rfind("head_", 0) == 0 || name.rfind("base_", 0) == 0)
    {
      const bool width_or_gain = name.find("epsilon") != std::string::npos || name.find("gain") != std::string::npos;
      require(width_or_gain ? v > 0 : v >= 0, name, width_or_gain ? "> 0" : ">= 0", v);
    }
  }
}

AttractorModel MonitorParameters::model(const std::string& controller) const
{
  if (controller == "base")
    return {base_alpha_attraction, 1.0, base_alpha_repulsion, base_epsilon_repulsion, base_gain, true};
  return {
      head_alpha_attraction, head_epsilon_attraction, head_alpha_repulsion, head_epsilon_repulsion, head_gain, false};
}

const std::vector<std::pair<std::string, double MonitorParameters::*>>& MonitorParameters::namedDoubles()
{
  using P = MonitorParameters;
  static const std::vector<std::pair<std::string, double P::*>> names = {
      {"rate", &P::rate},
      {"stale_after", &P::stale_after},
      {"saliency_threshold", &P::saliency_threshold},
      {"head_alpha_attraction", &P::head_alpha_attraction},
      {"head_epsilon_attraction", &P::head_epsilon_attraction},
      {"head_alpha_repulsion", &P::head_alpha_repulsion},
      {"head_epsilon_repulsion", &P::head_epsilon_repulsion},
      {"head_gain", &P::head_gain},
      {"base_alpha_attraction", &P::base_alpha_attraction},
      {"base_alpha_repulsion", &P::base_alpha_repulsion},
      {"base_epsilon_repulsion", &P::base_epsilon_repulsion},
      {"base_gain", &P::base_gain},
  };
  return names;
}

const std::vector<std::pair<std::string, int MonitorParameters::*>>& MonitorParameters::namedInts()
{
  using P = MonitorParameters;
  static const std::vector<std::pair<std::string, int P::*>> names = {
      {"columns", &P::columns}, {"tile_width", &P::tile_width}, {"tile_height", &P::tile_height}};
  return names;
}
}  // namespace biovision_monitor
