#include "biovision_ros_common/image_message_converter.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <map>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace biovision_ros_common
{
namespace
{
enum class Layout
{
  Grey,
  Bgr,
  Rgb,
  Bgra,
  Rgba,
  BayerRggb,
  BayerBggr,
  BayerGbrg,
  BayerGrbg,
  Uyvy,
  Float,
};

struct Format
{
  Layout layout;
  int type;  // the OpenCV type of the bytes as they are in the message
};

const std::map<std::string, Format>& formats()
{
  static const std::map<std::string, Format> table = {
      {"mono8", {Layout::Grey, CV_8UC1}},
      {"8UC1", {Layout::Grey, CV_8UC1}},
      {"mono16", {Layout::Grey, CV_16UC1}},
      {"16UC1", {Layout::Grey, CV_16UC1}},
      {"bgr8", {Layout::Bgr, CV_8UC3}},
      {"8UC3", {Layout::Bgr, CV_8UC3}},
      {"rgb8", {Layout::Rgb, CV_8UC3}},
      {"bgra8", {Layout::Bgra, CV_8UC4}},
      {"rgba8", {Layout::Rgba, CV_8UC4}},
      {"bgr16", {Layout::Bgr, CV_16UC3}},
      {"rgb16", {Layout::Rgb, CV_16UC3}},
      {"bgra16", {Layout::Bgra, CV_16UC4}},
      {"rgba16", {Layout::Rgba, CV_16UC4}},
      {"bayer_rggb8", {Layout::BayerRggb, CV_8UC1}},
      {"bayer_bggr8", {Layout::BayerBggr, CV_8UC1}},
      {"bayer_gbrg8", {Layout::BayerGbrg, CV_8UC1}},
      {"bayer_grbg8", {Layout::BayerGrbg, CV_8UC1}},
      {"bayer_rggb16", {Layout::BayerRggb, CV_16UC1}},
      {"bayer_bggr16", {Layout::BayerBggr, CV_16UC1}},
      {"bayer_gbrg16", {Layout::BayerGbrg, CV_16UC1}},
      {"bayer_grbg16", {Layout::BayerGrbg, CV_16UC1}},
      {"yuv422", {Layout::Uyvy, CV_8UC2}},
      {"32FC1", {Layout::Float, CV_32FC1}},
  };
  return table;
}

std::string encodingList()
{
  std::string s;
  for (const auto& name : ImageMessageConverter::encodings())
    s += (s.empty() ? "" : ", ") + name;
  return s;
}

bool hostIsBigEndian()
{
  const uint16_t probe = 1;
  uint8_t first;
  std::memcpy(&first, &probe, 1);
  return first == 0;
}

/// Validates the header against the data and wraps the bytes (no copy); swaps bytes when needed (copy).
cv::Mat wrap(const sensor_msgs::Image& m, const Format& f, size_t max_pixels)
{
  const std::string what = std::to_string(m.width) + "x" + std::to_string(m.height) + " '" + m.encoding + "' image";
  if (m.width == 0 || m.height == 0)
    throw ImageConversionError("empty " + what);
  if (size_t(m.width) * m.height > ImageMessageConverter::kMaxPixels)
    throw ImageConversionError(what + " exceeds " + std::to_string(ImageMessageConverter::kMaxPixels >> 20) +
                               " Mpx (damaged header?)");
  if (size_t(m.width) * m.height > max_pixels)
    throw ImageConversionError(what + " has " + std::to_string(size_t(m.width) * m.height) +
                               " pixels, more than ~max_input_pixels = " + std::to_string(max_pixels) +
                               " (downscale the camera or raise the parameter)");
  const size_t row_bytes = size_t(m.width) * CV_ELEM_SIZE(f.type);
  if (m.step < row_bytes)
    throw ImageConversionError(what + ": step " + std::to_string(m.step) + " is less than width x bytes per pixel (" +
                               std::to_string(row_bytes) + ")");
  // cv::Mat refuses such a step with a bare OpenCV assertion: say what is wrong with the message instead.
  if (m.step % CV_ELEM_SIZE1(f.type) != 0)
    throw ImageConversionError(what + ": step " + std::to_string(m.step) + " is not a multiple of the " +
                               std::to_string(CV_ELEM_SIZE1(f.type)) + "-byte channel size");
  // UYVY pixel pairs share U and V: an odd width leaves the last column without chroma (OpenCV leaves it unset).
  if (f.layout == Layout::Uyvy && m.width % 2 != 0)
    throw ImageConversionError(what + ": yuv422 needs an even width (pixel pairs share U and V)");
  if (m.data.size() < size_t(m.step) * m.height)
    throw ImageConversionError(what + ": data holds " + std::to_string(m.data.size()) + " bytes, step x height needs " +
                               std::to_string(size_t(m.step) * m.height));
  cv::Mat mat(int(m.height), int(m.width), f.type, const_cast<uint8_t*>(m.data.data()), m.step);
  const size_t channel_bytes = CV_ELEM_SIZE1(f.type);
  if (channel_bytes > 1 && bool(m.is_bigendian) != hostIsBigEndian())
  {
    cv::Mat swapped = mat.clone();
    for (int y = 0; y < swapped.rows; ++y)
    {
      uint8_t* p = swapped.ptr<uint8_t>(y);
      for (size_t i = 0; i + channel_bytes <= row_bytes; i += channel_bytes)
        std::reverse(p + i, p + i + channel_bytes);
    }
    return swapped;
  }
  return mat;
}

cv::Mat toEightBits(const cv::Mat& m)
{
  if (m.depth() == CV_8U)
    return m;
  cv::Mat out;
  m.convertTo(out, CV_8U, 1.0 / 257.0);
  return out;
}

int bayerCode(Layout l)
{
  // ROS names the 2x2 pattern from the top-left pixel; OpenCV names it from the second row's second pixel.
  switch (l)
  {
    case Layout::BayerRggb:
      return cv::COLOR_BayerBG2BGR_EA;
    case Layout::BayerBggr:
      return cv::COLOR_BayerRG2BGR_EA;
    case Layout::BayerGbrg:
      return cv::COLOR_BayerGR2BGR_EA;
    default:
      return cv::COLOR_BayerGB2BGR_EA;
  }
}
}  // namespace

const std::vector<std::string>& ImageMessageConverter::encodings()
{
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto& [name, format] : formats())
      n.push_back(name);
    return n;
  }();
  return names;
}

cv::Mat ImageMessageConverter::toCv(const sensor_msgs::Image& message, Depth depth, size_t max_pixels)
{
  const auto it = formats().find(message.encoding);
  if (it == formats().end())
    throw ImageConversionError("unsupported image encoding '" + message.encoding + "'; readable: " + encodingList());
  const Format& f = it->second;
  if (f.layout == Layout::Float && depth == Depth::Eight)
    throw ImageConversionError("a 32FC1 image is a measurement, not a picture: expected a camera encoding");
  cv::Mat m = wrap(message, f, max_pixels);
  if (f.layout == Layout::Float)
  {
    // NaN fails every comparison, Inf exceeds FLT_MAX: count what is not an ordinary number.
    const int finite = cv::countNonZero(cv::abs(m) <= std::numeric_limits<float>::max());
    if (finite != m.rows * m.cols)
      throw ImageConversionError(std::to_string(m.rows * m.cols - finite) + " of " + std::to_string(m.rows * m.cols) +
                                 " pixels of the 32FC1 image are NaN/Inf");
  }
  cv::Mat out;
  switch (f.layout)
  {
    case Layout::Grey:
    case Layout::Bgr:
    case Layout::Float:
      out = m;
      break;
    case Layout::Rgb:
      cv::cvtColor(m, out, cv::COLOR_RGB2BGR);
      break;
    case Layout::Bgra:
      cv::cvtColor(m, out, cv::COLOR_BGRA2BGR);
      break;
    case Layout::Rgba:
      cv::cvtColor(m, out, cv::COLOR_RGBA2BGR);
      break;
    case Layout::Uyvy:
      cv::cvtColor(m, out, cv::COLOR_YUV2BGR_UYVY);
      break;
    default:  // Bayer: edge-aware demosaicing works on 8 bits
      cv::cvtColor(toEightBits(m), out, bayerCode(f.layout));
      break;
  }
  return depth == Depth::Eight ? toEightBits(out) : out;
}

cv::Mat ImageMessageConverter::toFloat32(const sensor_msgs::Image& message, size_t max_pixels)
{
  const auto it = formats().find(message.encoding);
  if (it == formats().end() || (it->second.layout != Layout::Grey && it->second.layout != Layout::Float))
    throw ImageConversionError("expected a single-channel image (32FC1, 16UC1, mono16, 8UC1, mono8), got '" +
                               message.encoding + "'");
  const cv::Mat m = wrap(message, it->second, max_pixels);
  if (m.type() == CV_32FC1)
    return m;
  cv::Mat out;
  m.convertTo(out, CV_32F);
  return out;
}

size_t ImageMessageConverter::maxInputPixels(const ros::NodeHandle& private_nh, size_t default_pixels)
{
  int value = static_cast<int>(default_pixels);
  private_nh.param("max_input_pixels", value, value);
  if (value < 1 || size_t(value) > kMaxPixels)
    throw std::invalid_argument(private_nh.resolveName("max_input_pixels") + " = " + std::to_string(value) +
                                " is outside [1, " + std::to_string(kMaxPixels) +
                                "] (largest width x height processed)");
  return size_t(value);
}
}  // namespace biovision_ros_common
