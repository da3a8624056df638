#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include <opencv2/imgproc.hpp>

#include "biovision_ros_common/image_message_converter.hpp"

using namespace biovision_ros_common;
using Depth = ImageMessageConverter::Depth;

namespace
{
/// A message holding `mat`'s pixels with `padding` extra bytes per row, in the requested byte order.
sensor_msgs::Image message(const cv::Mat& mat, const std::string& encoding, size_t padding = 0, bool big_endian = false)
{
  sensor_msgs::Image m;
  m.width = mat.cols;
  m.height = mat.rows;
  m.encoding = encoding;
  m.is_bigendian = big_endian;
  const size_t row = mat.cols * mat.elemSize();
  m.step = static_cast<uint32_t>(row + padding);
  m.data.assign(size_t(m.step) * mat.rows, 0xAB);  // padding filled with garbage that must be skipped
  for (int y = 0; y < mat.rows; ++y)
  {
    std::memcpy(&m.data[y * m.step], mat.ptr(y), row);
    if (big_endian && mat.elemSize1() > 1)
      for (size_t i = 0; i < row; i += mat.elemSize1())
        std::reverse(&m.data[y * m.step + i], &m.data[y * m.step + i + mat.elemSize1()]);
  }
  return m;
}

cv::Mat colourBars()
{
  cv::Mat bgr(8, 12, CV_8UC3);
  bgr(cv::Rect(0, 0, 4, 8)).setTo(cv::Scalar(255, 0, 0));  // blue
  bgr(cv::Rect(4, 0, 4, 8)).setTo(cv::Scalar(0, 255, 0));  // green
  bgr(cv::Rect(8, 0, 4, 8)).setTo(cv::Scalar(0, 0, 255));  // red
  return bgr;
}

double maxDifference(const cv::Mat& a, const cv::Mat& b)
{
  return cv::norm(a, b, cv::NORM_INF);
}

void expectErrorMentions(const sensor_msgs::Image& m, const std::string& words)
{
  try
  {
    ImageMessageConverter::toCv(m);
    ADD_FAILURE() << "no error for " << m.encoding;
  }
  catch (const ImageConversionError& e)
  {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}
}  // namespace

TEST(ImageMessageConverter, EveryColourEncodingGivesTheSameBgrPicture)
{
  const cv::Mat bgr = colourBars();
  cv::Mat rgb, bgra, rgba, bgr16, rgb16, bgra16, rgba16;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  cv::cvtColor(bgr, bgra, cv::COLOR_BGR2BGRA);
  cv::cvtColor(bgr, rgba, cv::COLOR_BGR2RGBA);
  bgr.convertTo(bgr16, CV_16U, 257);
  rgb.convertTo(rgb16, CV_16U, 257);
  bgra.convertTo(bgra16, CV_16U, 257);
  rgba.convertTo(rgba16, CV_16U, 257);
  const std::vector<std::pair<std::string, cv::Mat>> cases = {{"bgr8", bgr},    {"8UC3", bgr},      {"rgb8", rgb},
                                                              {"bgra8", bgra},  {"rgba8", rgba},    {"bgr16", bgr16},
                                                              {"rgb16", rgb16}, {"bgra16", bgra16}, {"rgba16", rgba16}};
  for (const auto& [encoding, mat] : cases)
    for (bool big_endian : {false, true})
    {
      const sensor_msgs::Image m = message(mat, encoding, 0, big_endian);  // outlives `out`, which may share it
      const cv::Mat out = ImageMessageConverter::toCv(m);
      ASSERT_EQ(out.type(), CV_8UC3) << encoding;
      EXPECT_EQ(maxDifference(out, bgr), 0) << encoding << (big_endian ? " big endian" : "");
    }
}

TEST(ImageMessageConverter, SixteenBitBigEndianGreyKeepsItsValues)
{
  cv::Mat grey16(6, 10, CV_16U);
  cv::randu(grey16, 0, 65535);
  for (const char* encoding : {"mono16", "16UC1"})
  {
    const cv::Mat kept = ImageMessageConverter::toCv(message(grey16, encoding, 6, true), Depth::Keep);
    ASSERT_EQ(kept.type(), CV_16UC1);
    EXPECT_EQ(maxDifference(kept, grey16), 0) << encoding;
    cv::Mat expected8;
    grey16.convertTo(expected8, CV_8U, 1.0 / 257.0);
    EXPECT_EQ(maxDifference(ImageMessageConverter::toCv(message(grey16, encoding, 0, true)), expected8), 0);
    EXPECT_EQ(maxDifference(ImageMessageConverter::toFloat32(message(grey16, encoding, 2, true)),
                            [&] {
                              cv::Mat f;
                              grey16.convertTo(f, CV_32F);
                              return f;
                            }()),
              0);
  }
}

TEST(ImageMessageConverter, PaddedRowsAreSkippedAndUnpaddedOnesShareTheMessage)
{
  cv::Mat grey(5, 7, CV_8U);
  cv::randu(grey, 0, 255);
  const sensor_msgs::Image padded = message(grey, "mono8", 9);
  const cv::Mat out = ImageMessageConverter::toCv(padded);
  EXPECT_EQ(maxDifference(out, grey), 0);
  EXPECT_EQ(out.data, padded.data.data()) << "mono8 needs no copy";
  const sensor_msgs::Image padded_bgr = message(colourBars(), "bgr8", 3);
  const cv::Mat bgr = ImageMessageConverter::toCv(padded_bgr);
  EXPECT_EQ(maxDifference(bgr, colourBars()), 0);
}

TEST(ImageMessageConverter, BayerPatternsAreDemosaicedToTheRightColours)
{
  // Mosaic a uniform colour in each ROS pattern: the debayered centre must be that colour.
  const cv::Vec3b colour(40, 120, 220);                       // B, G, R
  const std::map<std::string, std::array<int, 4>> patterns = {// channel (0 B, 1 G, 2 R) of (0,0) (0,1) (1,0) (1,1)
                                                              {"bayer_rggb8", {2, 1, 1, 0}},
                                                              {"bayer_bggr8", {0, 1, 1, 2}},
                                                              {"bayer_gbrg8", {1, 0, 2, 1}},
                                                              {"bayer_grbg8", {1, 2, 0, 1}}};
  for (const auto& [encoding, channel] : patterns)
  {
    cv::Mat raw(16, 16, CV_8U);
    for (int y = 0; y < raw.rows; ++y)
      for (int x = 0; x < raw.cols; ++x)
        raw.at<uint8_t>(y, x) = colour[channel[(y % 2) * 2 + x % 2]];
    const cv::Mat out = ImageMessageConverter::toCv(message(raw, encoding));
    ASSERT_EQ(out.type(), CV_8UC3);
    const cv::Vec3b centre = out.at<cv::Vec3b>(8, 8);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(centre[c], colour[c], 2) << encoding << " channel " << c;
    cv::Mat raw16;
    raw.convertTo(raw16, CV_16U, 257);
    std::string encoding16 = encoding;
    encoding16.replace(encoding16.size() - 1, 1, "16");
    const cv::Vec3b centre16 = ImageMessageConverter::toCv(message(raw16, encoding16, 0, true)).at<cv::Vec3b>(8, 8);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(centre16[c], colour[c], 2) << encoding16 << " channel " << c;
  }
}

TEST(ImageMessageConverter, BrokenMessagesAreRefusedNamingTheProblem)
{
  cv::Mat grey(4, 6, CV_8U, cv::Scalar(1));
  sensor_msgs::Image m = message(grey, "mono8");
  m.encoding = "jpeg";
  expectErrorMentions(m, "unsupported image encoding 'jpeg'");
  m = message(grey, "mono8");
  m.data.resize(m.data.size() - 1);
  expectErrorMentions(m, "data holds 23 bytes, step x height needs 24");
  m = message(grey, "mono8");
  m.step = 5;
  expectErrorMentions(m, "step 5 is less than");
  m = message(grey, "mono8");
  m.width = m.height = 0;
  m.data.clear();
  expectErrorMentions(m, "empty 0x0");
  m = message(grey, "mono8");
  m.width = 100000;
  m.height = 100000;
  expectErrorMentions(m, "Mpx");
  m = message(cv::Mat(4, 6, CV_32F, cv::Scalar(1.f)), "32FC1");
  expectErrorMentions(m, "measurement");
  EXPECT_EQ(ImageMessageConverter::toCv(m, Depth::Keep).type(), CV_32FC1);
  EXPECT_THROW(ImageMessageConverter::toFloat32(message(colourBars(), "bgr8")), ImageConversionError);
  // A step that is not a whole number of channels: cv::Mat would throw a bare cv::Exception.
  m = message(cv::Mat(4, 6, CV_16U, cv::Scalar(1)), "mono16", 1);
  expectErrorMentions(m, "step 13 is not a multiple of the 2-byte channel size");
  m = message(cv::Mat(4, 6, CV_16UC3, cv::Scalar(1, 2, 3)), "bgr16", 3);
  expectErrorMentions(m, "step 39 is not a multiple of the 2-byte channel size");
  m = message(cv::Mat(4, 6, CV_32F, cv::Scalar(1.f)), "32FC1", 2);
  EXPECT_THROW(ImageMessageConverter::toFloat32(m), ImageConversionError);
  // yuv422 pixel pairs share chroma: an odd width is a broken message, not a picture with an unset column.
  m = message(cv::Mat(4, 7, CV_8UC2, cv::Scalar(128, 200)), "yuv422");
  expectErrorMentions(m, "yuv422 needs an even width");
}

TEST(ImageMessageConverter, YuvAndTheEncodingListAgree)
{
  cv::Mat uyvy(4, 8, CV_8UC2, cv::Scalar(128, 200));  // U/V 128 = grey, Y 200
  const cv::Mat out = ImageMessageConverter::toCv(message(uyvy, "yuv422"));
  ASSERT_EQ(out.type(), CV_8UC3);
  EXPECT_NEAR(out.at<cv::Vec3b>(2, 2)[0], out.at<cv::Vec3b>(2, 2)[2], 2);
  for (const auto& e : ImageMessageConverter::encodings())
    EXPECT_FALSE(e.empty());
  EXPECT_GE(ImageMessageConverter::encodings().size(), 21u);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}

TEST(ImageMessageConverter, FramesAboveTheInputLimitAreRefusedBeforeAnyPixelIsRead)
{
  cv::Mat grey(30, 40, CV_8UC1, cv::Scalar(7));
  const sensor_msgs::Image m = message(grey, "mono8");
  EXPECT_EQ(ImageMessageConverter::toCv(m, Depth::Eight, 1200).cols, 40);  // exactly at the limit
  try
  {
    ImageMessageConverter::toCv(m, Depth::Eight, 1199);
    ADD_FAILURE() << "a frame above max_pixels was converted";
  }
  catch (const ImageConversionError& e)
  {
    EXPECT_NE(std::string(e.what()).find("max_input_pixels"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ImageMessageConverter::toFloat32(m, 100), ImageConversionError);
}

TEST(ImageMessageConverter, FloatPicturesWithNanOrInfAreRefusedNamingTheCount)
{
  cv::Mat f(4, 5, CV_32FC1, cv::Scalar(0.5f));
  EXPECT_NO_THROW(ImageMessageConverter::toCv(message(f, "32FC1"), Depth::Keep));
  f.at<float>(1, 2) = std::numeric_limits<float>::quiet_NaN();
  f.at<float>(3, 4) = std::numeric_limits<float>::infinity();
  f.at<float>(0, 0) = -std::numeric_limits<float>::infinity();
  for (bool big_endian : {false, true})
  {
    try
    {
      ImageMessageConverter::toCv(message(f, "32FC1", 0, big_endian), Depth::Keep);
      ADD_FAILURE() << "NaN/Inf pixels converted silently";
    }
    catch (const ImageConversionError& e)
    {
      EXPECT_NE(std::string(e.what()).find("3 of 20 pixels"), std::string::npos) << e.what();
    }
  }
  // A measurement image keeps its NaN ("no value").
  EXPECT_TRUE(std::isnan(ImageMessageConverter::toFloat32(message(f, "32FC1")).at<float>(1, 2)));
}

TEST(ImageMessageConverter, BigEndianSixteenBitAndFloatDecodeLikeLittleEndian)
{
  cv::Mat grey16(6, 7, CV_16UC1), grey32(6, 7, CV_32FC1);
  cv::randu(grey16, 0, 65535);
  cv::randu(grey32, -1000.f, 1000.f);
  for (const char* encoding : {"mono16", "16UC1"})
    EXPECT_EQ(maxDifference(ImageMessageConverter::toCv(message(grey16, encoding, 0, true), Depth::Keep),
                            ImageMessageConverter::toCv(message(grey16, encoding, 0, false), Depth::Keep)),
              0.0)
        << encoding;
  EXPECT_EQ(maxDifference(ImageMessageConverter::toCv(message(grey32, "32FC1", 4, true), Depth::Keep), grey32), 0.0);
  EXPECT_EQ(maxDifference(ImageMessageConverter::toFloat32(message(grey32, "32FC1", 0, true)), grey32), 0.0);
}
