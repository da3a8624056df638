#include "bumblebee2_driver/bumblebee2_parameters.hpp"

#include <stdexcept>

#include "bumblebee2_driver/stereo_frame.hpp"

namespace bumblebee2_driver
{
void Bumblebee2Parameters::validate() const
{
  auto fail = [](const std::string& what) { throw std::invalid_argument("Bumblebee2Parameters: " + what); };
  // At least 16 px: the Bayer 2 x 2 cells and the first frame's left/right check (a phase correlation)
  // need some image (2 x 2 frames aborted the node).
  if (width < 16 || width > 1600 || width % 2 != 0)
    fail("width = " + std::to_string(width) + " is not an even number in [16, 1600]");
  if (height < 16 || height > 1200 || height % 2 != 0)
    fail("height = " + std::to_string(height) + " is not an even number in [16, 1200]");
  if (!(frame_rate > 0.0 && frame_rate <= 30.0))
    fail("frame_rate = " + std::to_string(frame_rate) + " outside (0, 30] Hz");
  auto feature = [&](const char* name, int v) {
    if (v != -1 && (v < 0 || v > 4095))
      fail(std::string(name) + " = " + std::to_string(v) + " is neither -1 (automatic) nor in [0, 4095]");
  };
  feature("exposure", exposure);
  feature("shutter", shutter);
  feature("gain", gain);
  if (bayer_pattern != "auto")
  {
    try
    {
      bayerPatternFromName(bayer_pattern);
    }
    catch (const std::invalid_argument&)
    {
      fail("bayer_pattern = \"" + bayer_pattern + "\" is none of auto, rggb, gbrg, grbg, bggr, mono");
    }
  }
  if (left_frame_id.empty() || right_frame_id.empty())
    fail("left_frame_id and right_frame_id must be set");
  if (!(retry_period >= 0.1 && retry_period <= 60.0))
    fail("retry_period = " + std::to_string(retry_period) + " outside [0.1, 60] s");
}
}  // namespace bumblebee2_driver
