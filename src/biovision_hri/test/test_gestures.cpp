#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "biovision_common/stored_file.hpp"
#include "biovision_hri/gesture_recognizer.hpp"

using namespace biovision_hri;

namespace
{
/// A synthetic "hand posture": random filled shapes and lines of random grey levels (distinct per seed).
cv::Mat posture(int size, unsigned seed)
{
  cv::Mat img(size, size, CV_32F, cv::Scalar(0.5));
  cv::RNG rng(seed);
  for (int i = 0; i < 40; ++i)
  {
    const cv::Point c(rng.uniform(0, size), rng.uniform(0, size));
    const double v = rng.uniform(0.05, 0.95);
    if (i % 3 == 0)
      cv::circle(img, c, rng.uniform(3, size / 6), v, cv::FILLED);
    else if (i % 3 == 1)
      cv::rectangle(img, cv::Rect(c.x, c.y, rng.uniform(4, size / 4), rng.uniform(4, size / 4)), v, cv::FILLED);
    else
      cv::line(img, c, cv::Point(rng.uniform(0, size), rng.uniform(0, size)), v, rng.uniform(1, 4));
  }
  cv::GaussianBlur(img, img, cv::Size(), 0.8);
  return img;
}

cv::Mat background(int w, int h, unsigned seed)
{
  cv::Mat n(h, w, CV_32F);
  cv::RNG rng(seed);
  rng.fill(n, cv::RNG::NORMAL, 0.5, 0.08);
  cv::GaussianBlur(n, n, cv::Size(), 6.0);
  cv::normalize(n, n, 0.35, 0.65, cv::NORM_MINMAX);
  return n;
}

/// The posture rotated by `degrees` and scaled by `scale` about its centre, pasted at `at` into a scene.
cv::Mat scene(const cv::Mat& object, double degrees, double scale, cv::Point at, cv::Rect* where)
{
  cv::Mat out = background(320, 240, 99);
  const cv::Point2f c(object.cols / 2.f, object.rows / 2.f);
  const int side = cvRound(object.cols * scale);
  cv::Mat m = cv::getRotationMatrix2D(c, degrees, scale);
  m.at<double>(0, 2) += side / 2.0 - c.x;
  m.at<double>(1, 2) += side / 2.0 - c.y;
  cv::Mat warped;
  cv::warpAffine(object, warped, m, cv::Size(side, side), cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(0.5));
  *where = cv::Rect(at.x, at.y, side, side);
  warped.copyTo(out(*where));
  return out;
}

std::shared_ptr<const biovision_recognition::V1Descriptor> descriptor()
{
  static auto d = std::make_shared<const biovision_recognition::V1Descriptor>(
      biovision_recognition::DescriptorModel::load(BIOVISION_RECOGNITION_MODEL));
  return d;
}
}  // namespace

TEST(GestureRecognizer, ATemplateMatchesItselfUnderRotationAndScaleAndNotAnotherPosture)
{
  GestureRecognizer recognizer(descriptor(), GestureRecognizer::Parameters());
  const cv::Mat palm = posture(100, 1), fist = posture(100, 2);
  cv::Rect where;
  const cv::Mat learn = scene(palm, 0.0, 1.0, {60, 50}, &where);
  EXPECT_GT(recognizer.addTemplate(learn, where, "palm"), 10u);

  for (const auto& [degrees, scale] : std::vector<std::pair<double, double>>{{0, 1.0}, {8, 1.0}, {0, 1.3}, {-6, 0.8}})
  {
    cv::Rect box;
    const cv::Mat query = scene(palm, degrees, scale, {150, 70}, &box);
    const auto results = recognizer.recognize(query, {box});
    ASSERT_EQ(results.size(), 1u);
    EXPECT_EQ(results[0].label, "palm") << degrees << " deg, scale " << scale;
    EXPECT_GE(results[0].matches, 4);
  }
  cv::Rect box;
  const cv::Mat other = scene(fist, 0.0, 1.0, {150, 70}, &box);  // before box is read
  EXPECT_EQ(recognizer.recognize(other, {box}).front().label, "") << "another posture is not the palm";
}

TEST(GestureRecognizer, TheRejectionClassSuppressesAGesture)
{
  GestureRecognizer recognizer(descriptor(), GestureRecognizer::Parameters());
  cv::Rect where;
  EXPECT_GT(recognizer.addTemplate(scene(posture(100, 3), 0, 1, {60, 50}, &where), where, "palm"), 10u);
  EXPECT_GT(recognizer.addTemplate(scene(posture(100, 1), 0, 1, {60, 50}, &where), where, "none"), 10u);
  // The scene is made before the box is read: function arguments have no evaluation order.
  cv::Rect box;
  const cv::Mat none_query = scene(posture(100, 1), 3, 1.1, {140, 60}, &box);
  const auto rejected = recognizer.recognize(none_query, {box});
  EXPECT_EQ(rejected.front().label, "");
  EXPECT_EQ(rejected.front().best_label, "none");
  const cv::Mat palm_query = scene(posture(100, 3), 3, 1.1, {140, 60}, &box);
  EXPECT_EQ(recognizer.recognize(palm_query, {box}).front().label, "palm");
  // An empty or outside box gives no gesture, not an error.
  EXPECT_EQ(recognizer.recognize(palm_query, {cv::Rect(400, 400, 10, 10)}).front().label, "");
  EXPECT_EQ(recognizer.recognize(palm_query, {cv::Rect()}).front().label, "");
}

TEST(GestureRecognizer, TemplatesRoundTripAndForeignFilesAreRefused)
{
  GestureRecognizer recognizer(descriptor(), GestureRecognizer::Parameters());
  cv::Rect where;
  recognizer.addTemplate(scene(posture(100, 5), 0, 1, {60, 50}, &where), where, "v");
  const std::string path = ::testing::TempDir() + "/gestures.bin";
  recognizer.saveTemplates(path);
  GestureRecognizer loaded(descriptor(), GestureRecognizer::Parameters());
  loaded.loadTemplates(path);
  EXPECT_EQ(loaded.templates().labels(), std::vector<std::string>{"v"});
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << "not a template file";
  }
  EXPECT_THROW(loaded.loadTemplates(path), biovision_common::StoredFileError);
  EXPECT_EQ(loaded.templates().labels().size(), 1u) << "a refused file leaves the templates as they were";
  GestureRecognizer::Parameters bad;
  bad.min_matches = 1;
  EXPECT_THROW(loaded.setParameters(bad), std::invalid_argument);
}
