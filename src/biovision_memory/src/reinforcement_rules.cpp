#include "biovision_memory/reinforcement_rules.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace biovision_memory
{
void ReinforcementRules::validate() const
{
  auto fail = [](const char* field, double value, const std::string& range) {
    std::ostringstream m;
    m << "ReinforcementRules." << field << " = " << value << " is outside " << range;
    throw std::invalid_argument(m.str());
  };
  if (max_strength < 1 || max_strength > 100000)
    fail("max_strength", max_strength, "[1, 100000]");
  if (initial_strength < 1 || initial_strength > max_strength)
    fail("initial_strength", initial_strength, "[1, max_strength]");
  if (reinforcement < 1 || reinforcement > max_strength)
    fail("reinforcement", reinforcement, "[1, max_strength]");
  if (penalty > -1 || penalty < -max_strength)
    fail("penalty", penalty, "[-max_strength, -1]");
  if (!std::isfinite(forget_period) || forget_period <= 0 || forget_period > 1e6)
    fail("forget_period", forget_period, "(0, 1e6]");
}

int ReinforcementRules::decay(int strength, double& last_change, double now) const
{
  if (fixed(strength) || !(now > last_change))
    return strength;
  const double periods = std::floor((now - last_change) / forget_period);
  if (periods < 1.0)
    return strength;
  last_change += periods * forget_period;
  const double s = strength + periods * penalty;
  return s < -1e9 ? -1000000000 : static_cast<int>(s);
}
}  // namespace biovision_memory
