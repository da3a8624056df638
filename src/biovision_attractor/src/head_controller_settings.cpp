#include "biovision_attractor/head_controller_settings.hpp"

#include <cmath>
#include <stdexcept>

#include "biovision_attractor/head_attractor.hpp"

namespace biovision_attractor
{
void HeadControllerSettings::validate() const
{
  auto fail = [](const std::string& what) { throw std::invalid_argument("head controller: " + what); };
  HeadAttractor::Behaviour behaviour;
  if (!HeadAttractor::parseBehaviour(mode, behaviour))
    fail("mode '" + mode + "' is not explore, track, look_ahead or hold");
  if (pan_joint.empty() || tilt_joint.empty())
    fail("pan_joint and tilt_joint must be joint names");
  if (!(control_rate > 0 && control_rate <= 1000))
    fail("control_rate outside (0, 1000] Hz");
  if (!(joint_state_timeout > 0))
    fail("joint_state_timeout must be > 0 s");
  if (!(min_region_area >= 0))
    fail("min_region_area must be >= 0 px^2");
  if (!(horizontal_fov > 0 && horizontal_fov < M_PI))
    fail("horizontal_fov outside (0, pi) rad");
}
}  // namespace biovision_attractor
