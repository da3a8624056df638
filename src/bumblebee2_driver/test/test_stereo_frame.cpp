#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include <opencv2/imgproc.hpp>

#include "bumblebee2_driver/bumblebee2_parameters.hpp"
#include "bumblebee2_driver/dc1394_camera.hpp"
#include "bumblebee2_driver/stereo_frame.hpp"

using namespace bumblebee2_driver;

namespace
{
/// The sensor's mosaic of a BGR image for `pattern` (the colour each photosite sees).
cv::Mat mosaic(const cv::Mat& bgr, BayerPattern pattern)
{
  // Channel index (B=0, G=1, R=2) at (row parity, column parity).
  int c[2][2];
  switch (pattern)
  {
    case BayerPattern::kRggb:
      c[0][0] = 2, c[0][1] = 1, c[1][0] = 1, c[1][1] = 0;
      break;
    case BayerPattern::kBggr:
      c[0][0] = 0, c[0][1] = 1, c[1][0] = 1, c[1][1] = 2;
      break;
    case BayerPattern::kGrbg:
      c[0][0] = 1, c[0][1] = 2, c[1][0] = 0, c[1][1] = 1;
      break;
    default:  // GBRG
      c[0][0] = 1, c[0][1] = 0, c[1][0] = 2, c[1][1] = 1;
      break;
  }
  cv::Mat m(bgr.size(), CV_8UC1);
  for (int y = 0; y < bgr.rows; ++y)
    for (int x = 0; x < bgr.cols; ++x)
      m.at<uint8_t>(y, x) = bgr.at<cv::Vec3b>(y, x)[c[y % 2][x % 2]];
  return m;
}

/// A RAW16 frame: `even` in the even bytes, `odd` in the odd ones.
std::vector<uint8_t> interleave(const cv::Mat& even, const cv::Mat& odd)
{
  std::vector<uint8_t> raw;
  for (int y = 0; y < even.rows; ++y)
    for (int x = 0; x < even.cols; ++x)
    {
      raw.push_back(even.at<uint8_t>(y, x));
      raw.push_back(odd.at<uint8_t>(y, x));
    }
  return raw;
}

/// A smooth textured scene (blurred noise), wider than `width` by `shift`.
cv::Mat scene(int width, int height, int shift)
{
  cv::Mat s(height, width + shift, CV_8UC3);
  cv::RNG rng(3);
  rng.fill(s, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(s, s, cv::Size(0, 0), 2.0);
  cv::normalize(s, s, 20, 235, cv::NORM_MINMAX);
  return s;
}
}  // namespace

TEST(BayerPattern, FromTheCameraRegisterAndByName)
{
  EXPECT_EQ(bayerPatternFromRegister(0x52474742), BayerPattern::kRggb);
  EXPECT_EQ(bayerPatternFromRegister(0x47425247), BayerPattern::kGbrg);
  EXPECT_EQ(bayerPatternFromRegister(0x47524247), BayerPattern::kGrbg);
  EXPECT_EQ(bayerPatternFromRegister(0x42474752), BayerPattern::kBggr);
  EXPECT_EQ(bayerPatternFromRegister(0x59595959), BayerPattern::kMono);
  try
  {
    bayerPatternFromRegister(0x12345678);
    FAIL();
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("12345678"), std::string::npos) << e.what();
  }
  EXPECT_EQ(bayerPatternFromName("GRBG"), BayerPattern::kGrbg);
  EXPECT_THROW(bayerPatternFromName("rgb"), std::invalid_argument);
  EXPECT_EQ(rosEncoding(BayerPattern::kGrbg), "bayer_grbg8");
  EXPECT_EQ(rosEncoding(BayerPattern::kMono), "mono8");
}

TEST(Deinterleave, EvenBytesAreLeftOddBytesRightAndSwapExchangesThem)
{
  const std::vector<uint8_t> raw{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};  // 3 × 2 pixels
  StereoRaw s = deinterleave(raw.data(), 3, 2, false);
  EXPECT_EQ(s.left.at<uint8_t>(0, 0), 1);
  EXPECT_EQ(s.right.at<uint8_t>(0, 0), 2);
  EXPECT_EQ(s.left.at<uint8_t>(1, 2), 11);
  EXPECT_EQ(s.right.at<uint8_t>(1, 2), 12);
  s = deinterleave(raw.data(), 3, 2, true);
  EXPECT_EQ(s.left.at<uint8_t>(0, 0), 2);
  EXPECT_EQ(s.right.at<uint8_t>(1, 2), 11);
  EXPECT_THROW(deinterleave(nullptr, 3, 2, false), std::invalid_argument);
  EXPECT_THROW(deinterleave(raw.data(), 0, 2, false), std::invalid_argument);
}

TEST(Debayer, AUniformColourComesBackForEveryPattern)
{
  const cv::Mat colour(16, 16, CV_8UC3, cv::Scalar(40, 120, 210));
  for (BayerPattern p : {BayerPattern::kRggb, BayerPattern::kGbrg, BayerPattern::kGrbg, BayerPattern::kBggr})
  {
    const cv::Mat bgr = debayer(mosaic(colour, p), p);
    ASSERT_EQ(bgr.type(), CV_8UC3);
    const cv::Vec3b c = bgr.at<cv::Vec3b>(8, 8);
    EXPECT_NEAR(c[0], 40, 2) << bayerPatternName(p);
    EXPECT_NEAR(c[1], 120, 2) << bayerPatternName(p);
    EXPECT_NEAR(c[2], 210, 2) << bayerPatternName(p);
  }
  // The wrong pattern swaps red and blue: the test can fail.
  const cv::Mat wrong = debayer(mosaic(colour, BayerPattern::kRggb), BayerPattern::kBggr);
  EXPECT_GT(std::abs(wrong.at<cv::Vec3b>(8, 8)[2] - 210), 100);
  EXPECT_THROW(debayer(cv::Mat(), BayerPattern::kRggb), std::invalid_argument);
}

TEST(StereoFrame, ASyntheticRaw16FrameGivesTheExpectedLeftAndRightImages)
{
  const int w = 96, h = 64, d = 5;
  const cv::Mat wide = scene(w, h, d);
  const cv::Mat left = wide(cv::Rect(d, 0, w, h)).clone();  // x_left = x_right + d
  const cv::Mat right = wide(cv::Rect(0, 0, w, h)).clone();
  const auto raw = interleave(mosaic(left, BayerPattern::kGrbg), mosaic(right, BayerPattern::kGrbg));
  const StereoRaw pair = deinterleave(raw.data(), w, h, false);
  const cv::Mat l = debayer(pair.left, BayerPattern::kGrbg), r = debayer(pair.right, BayerPattern::kGrbg);
  const cv::Rect inner(2, 2, w - 4, h - 4);
  EXPECT_LT(cv::norm(l(inner), left(inner), cv::NORM_L1) / (inner.area() * 3.0), 4.0) << "mean abs error [grey levels]";
  EXPECT_LT(cv::norm(r(inner), right(inner), cv::NORM_L1) / (inner.area() * 3.0), 4.0);
  EXPECT_NEAR(horizontalDisparity(l, r), d, 0.5);
  EXPECT_FALSE(looksSwapped(l, r));
  // The same frame read with the wrong order: the check notices.
  const StereoRaw swapped = deinterleave(raw.data(), w, h, true);
  EXPECT_TRUE(looksSwapped(debayer(swapped.left, BayerPattern::kGrbg), debayer(swapped.right, BayerPattern::kGrbg)));
}

TEST(StereoFrame, TheCommittedTestFrameHasDisparityFour)
{
  std::ifstream in(std::string(BIOVISION_TEST_DATA_DIR) + "/synthetic_64x48.raw16", std::ios::binary);
  const std::vector<uint8_t> raw((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(raw.size(), 64u * 48u * 2u);
  const StereoRaw pair = deinterleave(raw.data(), 64, 48, false);
  const double disparity = horizontalDisparity(debayer(pair.left, BayerPattern::kGrbg),
                                               debayer(pair.right, BayerPattern::kGrbg));
  EXPECT_NEAR(disparity, 4.0, 0.5);
}

TEST(Bumblebee2Parameters, DefaultsValidateAndEachBadFieldIsNamed)
{
  EXPECT_NO_THROW(Bumblebee2Parameters{}.validate());
  auto expectNamed = [](Bumblebee2Parameters p, const std::string& field) {
    try
    {
      p.validate();
      ADD_FAILURE() << field << " accepted";
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  Bumblebee2Parameters p;
  p.width = 1023;
  expectNamed(p, "width");
  p = {};
  p.height = 0;
  expectNamed(p, "height");
  p = {};
  p.height = 2;  // a 32 x 2 frame aborted the node in the first frame's left/right check
  expectNamed(p, "height");
  p = {};
  p.frame_rate = 0.0;
  expectNamed(p, "frame_rate");
  p = {};
  p.exposure = -2;
  expectNamed(p, "exposure");
  p = {};
  p.gain = 5000;
  expectNamed(p, "gain");
  p = {};
  p.bayer_pattern = "rgb";
  expectNamed(p, "bayer_pattern");
  p = {};
  p.retry_period = 0.0;
  expectNamed(p, "retry_period");
}

TEST(Dc1394Camera, AMissingCameraIsAClearErrorNotACrash)
{
  Bumblebee2Parameters p;
  p.guid = "00b09d0100deadbe";  // no such camera, here or on the robot
  Dc1394Camera camera;
  try
  {
    camera.open(p);
    FAIL() << "opened a camera that does not exist";
  }
  catch (const CameraError& e)
  {
    const std::string what = e.what();
    EXPECT_TRUE(what.find("no IEEE-1394 camera") != std::string::npos || what.find("not found") != std::string::npos ||
                what.find("cannot start") != std::string::npos)
        << what;
  }
  EXPECT_FALSE(camera.isOpen());
  EXPECT_THROW(camera.grab(), CameraError);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
