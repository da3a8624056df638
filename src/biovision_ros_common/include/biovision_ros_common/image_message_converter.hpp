#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <ros/node_handle.h>
#include <sensor_msgs/Image.h>

namespace biovision_ros_common
{
/// Thrown when an image message cannot be converted; the message names the problem (encoding, size,
/// step, data length) so the nodelet can report it as is.
struct ImageConversionError : std::invalid_argument
{
  using std::invalid_argument::invalid_argument;
};

/// The one conversion of sensor_msgs/Image to cv::Mat that every BioVision nodelet uses (the grid_map
/// GridMapRosConverter pattern: static functions, testable without a master).
///
/// Encodings read (sensor_msgs/image_encodings names):
///   grey:   mono8, 8UC1, mono16, 16UC1                        -> 1 channel
///   colour: bgr8, rgb8, bgra8, rgba8, 8UC3, bgr16, rgb16, bgra16, rgba16 -> 3 channels, BGR order
///   raw:    bayer_{rggb,bggr,gbrg,grbg}{8,16} (debayered, edge-aware), yuv422 (UYVY) -> 3 channels, BGR
///   float:  32FC1 (only with Depth::Keep, or through toFloat32)
/// Anything else throws, listing these. Checks, in order, each throwing ImageConversionError: width or
/// height 0; more than `max_pixels` pixels (the node's ~max_input_pixels, see maxInputPixels(); at most
/// kMaxPixels) — checked before any pixel is touched, so an oversized frame costs no more memory than its
/// message; step < width × bytes per pixel; step not a whole number of channels; yuv422 of odd width; data
/// shorter than step × height. toCv() also refuses a 32FC1 picture holding NaN/Inf pixels, naming how many
/// (toFloat32() keeps them: in a measurement image NaN means "no value").
/// Rows may be padded (step > width × bytes per pixel): the padding is skipped. Multi-byte pixels with
/// is_bigendian different from this machine's are byte-swapped. When no conversion is needed the result
/// shares the message's memory (zero copy): keep the message alive while using it.
class ImageMessageConverter
{
public:
  static constexpr size_t kMaxPixels = size_t(64) << 20;  ///< 64 Mpx: larger is a damaged header
  /// Default of every image nodelet's ~max_input_pixels: 2 Mpx (1920x1080, 1600x1200 and 2048x1024 fit).
  /// Measured: one 4000x3000 frame took biobin_disparity 9.2 GB and recognition 7.3 GB (issue #23).
  static constexpr size_t kDefaultMaxInputPixels = size_t(2) << 20;

  enum class Depth
  {
    Eight,  ///< 8 bits per channel: 16-bit data scaled by 1/257 (full range to full range)
    Keep,   ///< the message's depth: CV_8U, CV_16U or CV_32F
  };

  /// A picture for the vision front ends: BGR (3 channels) or grey (1 channel).
  static cv::Mat toCv(const sensor_msgs::Image& message, Depth depth = Depth::Eight, size_t max_pixels = kMaxPixels);

  /// A single-channel measurement image (32FC1, 16UC1/mono16, 8UC1/mono8) as CV_32F of the raw values.
  static cv::Mat toFloat32(const sensor_msgs::Image& message, size_t max_pixels = kMaxPixels);

  /// Reads the node's ~max_input_pixels (int, default `default_pixels`): the largest width × height it
  /// processes; larger frames are refused with an error (bounded memory and time per frame). Throws
  /// std::invalid_argument naming the parameter unless it lies in [1, kMaxPixels].
  static size_t maxInputPixels(const ros::NodeHandle& private_nh, size_t default_pixels = kDefaultMaxInputPixels);

  /// The encodings toCv() reads, for error messages and docs.
  static const std::vector<std::string>& encodings();
};
}  // namespace biovision_ros_common
