#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "biovision_common/stored_file.hpp"
#include "biovision_common/synthetic_images.hpp"
#include "biovision_hri/gesture_recognizer.hpp"

using namespace biovision_hri;

namespace
{
using biovision_common::SyntheticImages;

/// A synthetic "hand posture": random shapes (distinct per seed).
cv::Mat posture(int size, unsigned seed)
{
  return SyntheticImages::randomShapes(size, seed);
}

/// The posture rotated by `degrees` and scaled by `scale` about its centre, pasted at `at` into a scene.
cv::Mat scene(const cv::Mat& object, double degrees, double scale, cv::Point at, cv::Rect* where)
{
  return SyntheticImages::paste(object, SyntheticImages::smoothNoise({320, 240}, 99), degrees, scale, at,
                                cv::BORDER_CONSTANT, where);
}

std::shared_ptr<const biovision_recognition::V1Descriptor> descriptor()
{
  static auto d = std::make_shared<const biovision_recognition::V1Descriptor>(
      biovision_recognition::DescriptorModel::load(std::string(BIOVISION_RECOGNITION_MODELS) + "/" +
                                                   biovision_recognition::kDefaultModelFile));
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
  // An empty or 8-bit image is refused, not read as "no gesture".
  EXPECT_THROW(recognizer.recognize(cv::Mat(), {box}), std::invalid_argument);
  EXPECT_THROW(recognizer.recognize(cv::Mat(240, 320, CV_8UC1, cv::Scalar(0)), {box}), std::invalid_argument);
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
