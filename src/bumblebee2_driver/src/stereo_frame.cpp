#include "bumblebee2_driver/stereo_frame.hpp"

#include <algorithm>
#include <cctype>
#include <sstream>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace bumblebee2_driver
{
BayerPattern bayerPatternFromRegister(uint32_t value)
{
  switch (value)
  {
    case 0x52474742:
      return BayerPattern::kRggb;
    case 0x47425247:
      return BayerPattern::kGbrg;
    case 0x47524247:
      return BayerPattern::kGrbg;
    case 0x42474752:
      return BayerPattern::kBggr;
    case 0x59595959:
      return BayerPattern::kMono;
    default:
    {
      std::ostringstream s;
      s << "bayerPatternFromRegister: register 0x1040 = 0x" << std::hex << value
        << " is none of RGGB, GBRG, GRBG, BGGR, YYYY";
      throw std::invalid_argument(s.str());
    }
  }
}

BayerPattern bayerPatternFromName(const std::string& name)
{
  std::string n = name;
  std::transform(n.begin(), n.end(), n.begin(), [](unsigned char c) { return std::tolower(c); });
  for (BayerPattern p :
       {BayerPattern::kRggb, BayerPattern::kGbrg, BayerPattern::kGrbg, BayerPattern::kBggr, BayerPattern::kMono})
    if (n == bayerPatternName(p))
      return p;
  throw std::invalid_argument("bayer pattern \"" + name + "\" is none of rggb, gbrg, grbg, bggr, mono");
}

std::string bayerPatternName(BayerPattern pattern)
{
  switch (pattern)
  {
    case BayerPattern::kRggb:
      return "rggb";
    case BayerPattern::kGbrg:
      return "gbrg";
    case BayerPattern::kGrbg:
      return "grbg";
    case BayerPattern::kBggr:
      return "bggr";
    case BayerPattern::kMono:
      return "mono";
  }
  return "mono";
}

std::string rosEncoding(BayerPattern pattern)
{
  return pattern == BayerPattern::kMono ? "mono8" : "bayer_" + bayerPatternName(pattern) + "8";
}

StereoRaw deinterleave(const uint8_t* data, int width, int height, bool swap_left_right)
{
  if (data == nullptr || width <= 0 || height <= 0)
    throw std::invalid_argument("deinterleave: no data or a non-positive size " + std::to_string(width) + "x" +
                                std::to_string(height));
  StereoRaw out{cv::Mat(height, width, CV_8UC1), cv::Mat(height, width, CV_8UC1)};
  cv::Mat& even = swap_left_right ? out.right : out.left;
  cv::Mat& odd = swap_left_right ? out.left : out.right;
  for (int y = 0; y < height; ++y)
  {
    const uint8_t* src = data + static_cast<size_t>(y) * width * 2;
    uint8_t* e = even.ptr<uint8_t>(y);
    uint8_t* o = odd.ptr<uint8_t>(y);
    for (int x = 0; x < width; ++x)
    {
      e[x] = src[2 * x];
      o[x] = src[2 * x + 1];
    }
  }
  return out;
}

cv::Mat debayer(const cv::Mat& raw, BayerPattern pattern)
{
  if (raw.empty() || raw.type() != CV_8UC1)
    throw std::invalid_argument("debayer: the raw image must be a non-empty 8-bit single-channel image");
  if (pattern == BayerPattern::kMono)
    return raw.clone();
  // OpenCV names a pattern by the second row's second and third pixels, so its codes are shifted against
  // the sensor's (the same table as cv_bridge's bayer_* conversions).
  int code = cv::COLOR_BayerBG2BGR_EA;
  switch (pattern)
  {
    case BayerPattern::kRggb:
      code = cv::COLOR_BayerBG2BGR_EA;
      break;
    case BayerPattern::kBggr:
      code = cv::COLOR_BayerRG2BGR_EA;
      break;
    case BayerPattern::kGbrg:
      code = cv::COLOR_BayerGR2BGR_EA;
      break;
    case BayerPattern::kGrbg:
      code = cv::COLOR_BayerGB2BGR_EA;
      break;
    case BayerPattern::kMono:
      break;
  }
  cv::Mat bgr;
  cv::cvtColor(raw, bgr, code);
  return bgr;
}

double horizontalDisparity(const cv::Mat& left, const cv::Mat& right)
{
  if (left.empty() || left.size() != right.size())
    throw std::invalid_argument("horizontalDisparity: empty images or different sizes");
  auto grey = [](const cv::Mat& m) {
    cv::Mat g;
    if (m.channels() == 3)
      cv::cvtColor(m, g, cv::COLOR_BGR2GRAY);
    else
      g = m;
    cv::Mat f;
    g.convertTo(f, CV_32F);
    return f;
  };
  const cv::Rect centre(left.cols / 8, left.rows / 8, left.cols * 3 / 4, left.rows * 3 / 4);
  cv::Mat window;
  cv::createHanningWindow(window, centre.size(), CV_32F);
  // phaseCorrelate(a, b) gives the shift of a against b: the left view against the right one.
  const cv::Point2d shift = cv::phaseCorrelate(grey(left)(centre), grey(right)(centre), window);
  return shift.x;
}

bool looksSwapped(const cv::Mat& left, const cv::Mat& right, double min_shift)
{
  return horizontalDisparity(left, right) < -min_shift;
}
}  // namespace bumblebee2_driver
