#pragma once

#include <string>
#include <vector>

#include "biovision_common/eval/stereo_scene.hpp"

namespace biovision_common
{
/// Loads Middlebury stereo scenes in the layouts found in ../shared/data/stereo and the official v3:
/// - v3:        im0.png im1.png calib.txt (ndisp=, extra whitespace tolerated) [disp0GT.pfm mask0nocc.png]
/// - v2-masks:  imL.png imR.png groundtruth.png nonocc.png info.txt (line 1 scale, line 2 max disparity)
/// - 2005-2006: view1.png view5.png disp1.png disp5.png (value / 3, 0 unknown)
/// - 2003:      imL.png imR.png disp2.png disp6.png (value / 4)
/// - tsukuba:   imL.png imR.png truedisp.pgm (value / 16) [nonocc.png]
/// - 2001:      im2.ppm (or im2.jpg) im6.ppm disp2.pgm disp6.pgm (value / 8)
/// Where no non-occlusion mask ships, it is derived as Middlebury did: a left pixel is non-occluded
/// when the right ground truth at x - d agrees with d within 1 px. max_disparity is the v3 ndisp, the
/// v2 info.txt value, or the ceiling of the largest known ground-truth disparity.
class MiddleburyDataset
{
public:
  /// `directory` is one scene or a folder of scenes (searched one level deep), in name order.
  /// Throws std::runtime_error when it holds no scene; a broken scene throws naming its file.
  static std::vector<StereoScene> load(const std::string& directory);
  /// Loads one scene folder; throws std::runtime_error when its layout is not recognised.
  static StereoScene loadScene(const std::string& directory);
  /// Reads ndisp from a v3 calib.txt (tolerates blanks around '=' and trailing whitespace).
  static int readCalibNdisp(const std::string& path);
};
}  // namespace biovision_common
