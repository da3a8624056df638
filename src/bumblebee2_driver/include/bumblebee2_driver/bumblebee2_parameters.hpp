#pragma once

#include <string>

namespace bumblebee2_driver
{
/// Parameters of the Bumblebee-2 driver. Defaults: the thesis's BB2-08S2C-60 (1024×768, L415) in Format7
/// mode 3 RAW16, the frame rate the sensor sustains at that size, automatic exposure.
struct Bumblebee2Parameters
{
  std::string guid;                    ///< camera GUID in hex ("" = the first camera found)
  int width = 1024;                    ///< [px] of each sensor, [16, 1600], even
  int height = 768;                    ///< [px], [16, 1200], even
  double frame_rate = 15.0;            ///< [Hz], (0, 30] (BB2-08S2C: ≤ 20 at 1024×768)
  int exposure = -1;                   ///< raw EXPOSURE feature value, −1 = automatic, else [0, 4095]
  int shutter = -1;                    ///< raw SHUTTER feature value, −1 = automatic, else [0, 4095]
  int gain = -1;                       ///< raw GAIN feature value, −1 = automatic, else [0, 4095]
  std::string bayer_pattern = "auto";  ///< "auto" = register 0x1040, else rggb | gbrg | grbg | bggr | mono
  bool swap_left_right = false;        ///< the even bytes are the right sensor (see docs/robot.md for the check)
  bool debayer = false;                ///< publish bgr8 instead of the raw mosaic (bayer_*8, debayered downstream)
  std::string left_frame_id = "stereo_left_optical";
  std::string right_frame_id = "stereo_right_optical";
  std::string left_camera_info_url;  ///< camera_info_manager URL (file:///…, package://…); "" = uncalibrated
  std::string right_camera_info_url;
  double retry_period = 2.0;  ///< [s] between attempts to open a missing camera, [0.1, 60]
  std::string frame_file;     ///< raw RAW16 frame (width × height × 2 bytes) published instead of a
                              ///< camera: tests and runs without the camera

  /// Throws std::invalid_argument naming the field and its range.
  void validate() const;
};

template <typename Read>
void visitParameters(Bumblebee2Parameters& p, Read&& read)
{
  read("guid", p.guid);
  read("width", p.width);
  read("height", p.height);
  read("frame_rate", p.frame_rate);
  read("exposure", p.exposure);
  read("shutter", p.shutter);
  read("gain", p.gain);
  read("bayer_pattern", p.bayer_pattern);
  read("swap_left_right", p.swap_left_right);
  read("debayer", p.debayer);
  read("left_frame_id", p.left_frame_id);
  read("right_frame_id", p.right_frame_id);
  read("left_camera_info_url", p.left_camera_info_url);
  read("right_camera_info_url", p.right_camera_info_url);
  read("retry_period", p.retry_period);
  read("frame_file", p.frame_file);
}
}  // namespace bumblebee2_driver
