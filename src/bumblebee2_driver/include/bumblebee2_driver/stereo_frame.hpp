#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include <opencv2/core.hpp>

namespace bumblebee2_driver
{
/// Colour filter layouts of the Bumblebee-2 sensors, as its register 0x1040 names them in ASCII.
enum class BayerPattern
{
  kRggb,
  kGbrg,
  kGrbg,
  kBggr,
  kMono,
};

/// The pattern register 0x1040 holds: 0x52474742 "RGGB", 0x47425247 "GBRG", 0x47524247 "GRBG",
/// 0x42474752 "BGGR", 0x59595959 "YYYY" (mono). Throws std::invalid_argument naming the value otherwise.
BayerPattern bayerPatternFromRegister(uint32_t value);
/// "rggb", "gbrg", "grbg", "bggr", "mono" (any case). Throws std::invalid_argument naming the text.
BayerPattern bayerPatternFromName(const std::string& name);
/// "rggb" … "mono".
std::string bayerPatternName(BayerPattern pattern);
/// The sensor_msgs/image_encodings name of a raw frame with this pattern: "bayer_rggb8" … or "mono8".
std::string rosEncoding(BayerPattern pattern);

/// One stereo frame split into the two sensors' 8-bit raw (Bayer-mosaicked) images.
struct StereoRaw
{
  cv::Mat left;   ///< CV_8UC1, height × width
  cv::Mat right;  ///< CV_8UC1
};

/// Splits a Format7 mode 3 RAW16 frame of the Bumblebee-2: each 16-bit pixel holds one 8-bit sample from
/// each sensor, the even bytes (the first of each pair, what dc1394_deinterlace_stereo puts in the top
/// half) from one and the odd bytes from the other. With the camera's big-endian byte order (register
/// 0x1048 = 0x80000001, what the driver sets) the even bytes are the LEFT sensor; `swap_left_right` swaps
/// them for a camera or byte order that does it the other way (check: docs/robot.md, or
/// looksSwapped()). `data` holds width × height × 2 bytes, rows without padding. Throws
/// std::invalid_argument for a null pointer or a non-positive size.
StereoRaw deinterleave(const uint8_t* data, int width, int height, bool swap_left_right);

/// Colour from one sensor's raw mosaic: bgr8 (CV_8UC3) by OpenCV's edge-aware demosaicing; a mono sensor
/// gives the image unchanged (CV_8UC1). Throws std::invalid_argument for an empty or non-8UC1 input.
cv::Mat debayer(const cv::Mat& raw, BayerPattern pattern);

/// The horizontal shift [px] that best aligns `right` onto `left` (phase correlation on the central
/// region): positive when scene points lie further right in the left image than in the right one, as
/// they must in a correctly ordered pair (disparity = x_left − x_right ≥ 0).
double horizontalDisparity(const cv::Mat& left, const cv::Mat& right);
/// True when the pair looks swapped: a clearly negative disparity (< −`min_shift` px). Needs a textured
/// scene with depth; inconclusive scenes (|shift| ≤ min_shift) give false.
bool looksSwapped(const cv::Mat& left, const cv::Mat& right, double min_shift = 1.0);
}  // namespace bumblebee2_driver
