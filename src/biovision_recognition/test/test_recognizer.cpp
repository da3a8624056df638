#include <gtest/gtest.h>

#include <random>

#include <opencv2/imgproc.hpp>

#include "biovision_common/synthetic_images.hpp"
#include "biovision_recognition/geometric_verifier.hpp"
#include "biovision_recognition/object_recognizer.hpp"

using namespace biovision_recognition;

namespace
{
/// A distinctive synthetic "object": random filled shapes and lines of random grey levels.
cv::Mat objectImage(int size, unsigned seed)
{
  return biovision_common::SyntheticImages::randomShapes(size, seed);
}

cv::Mat background(int w, int h, unsigned seed)
{
  return biovision_common::SyntheticImages::smoothNoise({w, h}, seed);
}

std::shared_ptr<const V1Descriptor> trainedDescriptor()
{
  static auto d = std::make_shared<const V1Descriptor>(DescriptorModel::load(
      std::string(BIOVISION_RECOGNITION_MODELS) + "/" + biovision_recognition::kDefaultModelFile));
  return d;
}
}  // namespace

TEST(GeometricVerifier, AcceptsASimilarityWithOutliersRejectsAScrambledSet)
{
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(0.f, 100.f);
  const double angle = 0.3, scale = 1.4;
  const cv::Matx23d t(scale * std::cos(angle), -scale * std::sin(angle), 20, scale * std::sin(angle),
                      scale * std::cos(angle), -5);
  std::vector<cv::Point2f> from, to;
  for (int i = 0; i < 30; ++i)
  {
    const cv::Point2f p(u(rng), u(rng));
    from.push_back(p);
    to.emplace_back(static_cast<float>(t(0, 0) * p.x + t(0, 1) * p.y + t(0, 2)),
                    static_cast<float>(t(1, 0) * p.x + t(1, 1) * p.y + t(1, 2)));
  }
  for (int i = 0; i < 10; ++i)  // outliers
  {
    from.emplace_back(u(rng), u(rng));
    to.emplace_back(u(rng) * 2, u(rng) * 2);
  }
  const GeometricVerifier verifier;
  const auto ok = verifier.verify(from, to);
  EXPECT_TRUE(ok.accepted);
  EXPECT_GE(ok.inliers, 30);
  EXPECT_LE(ok.inliers, 32);
  EXPECT_NEAR(ok.transform(0, 2), 20.0, 0.5);
  // The same points with the correspondences shuffled: no consensus.
  std::vector<cv::Point2f> scrambled = to;
  std::shuffle(scrambled.begin(), scrambled.end(), rng);
  EXPECT_FALSE(verifier.verify(from, scrambled).accepted);
  EXPECT_FALSE(verifier.verify({}, {}).accepted);
  EXPECT_THROW(verifier.verify(from, {}), std::invalid_argument);
}

TEST(GeometricVerifier, RefusesAConsensusTurnedFurtherThanUprightCodesAllow)
{
  // A perfect consensus turned by 90 degrees: upright codes cannot match that, so it is a chance
  // alignment of look-alike texture, not the object. The same set turned by 20 degrees is accepted.
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.f, 100.f);
  auto turned = [&](double degrees, std::vector<cv::Point2f>& from, std::vector<cv::Point2f>& to) {
    const double a = degrees * CV_PI / 180.0;
    for (int i = 0; i < 12; ++i)
    {
      const cv::Point2f p(u(rng), u(rng));
      from.push_back(p);
      to.emplace_back(static_cast<float>(std::cos(a) * p.x - std::sin(a) * p.y + 50),
                      static_cast<float>(std::sin(a) * p.x + std::cos(a) * p.y + 10));
    }
  };
  std::vector<cv::Point2f> f90, t90, f20, t20;
  turned(90.0, f90, t90);
  turned(-20.0, f20, t20);
  const GeometricVerifier verifier;
  const auto r90 = verifier.verify(f90, t90);
  EXPECT_EQ(r90.inliers, 12);  // the consensus is found ...
  EXPECT_FALSE(r90.accepted);  // ... and refused
  EXPECT_TRUE(verifier.verify(f20, t20).accepted);
  GeometricVerifier::Parameters any_rotation;
  any_rotation.max_rotation_degrees = 180.0;
  EXPECT_TRUE(GeometricVerifier(any_rotation).verify(f90, t90).accepted);
}

TEST(ObjectRecognizer, FindsALearnedObjectInAScenePutsTheBoxOnItAndStaysSilentWithoutIt)
{
  ObjectRecognizer recognizer(trainedDescriptor(), ObjectRecognizer::Parameters());
  ObjectMemory memory(128, trainedDescriptor()->model().id());
  const cv::Mat cup = objectImage(96, 11), book = objectImage(96, 12);
  memory.addView(recognizer.describe(cup, cv::Rect(), "cup"));
  memory.addView(recognizer.describe(book, cv::Rect(), "book"));
  ASSERT_GT(memory.keypointCount("cup"), 30u);

  cv::Mat scene = background(320, 240, 3);
  cup.copyTo(scene(cv::Rect(180, 90, 96, 96)));
  const auto found = recognizer.recognize(scene, {{cv::Rect(160, 70, 140, 140), 0}}, memory);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].label, "cup");
  EXPECT_GE(found[0].matches, 5);
  EXPECT_GT(found[0].score, 0.0);
  EXPECT_LE(found[0].score, 1.0);
  const cv::Rect truth(180, 90, 96, 96);
  EXPECT_GT((found[0].box & truth).area(), 0.7 * truth.area());
  // The verified matches, which ObjectLocator takes the depth at, lie on the object.
  ASSERT_EQ(static_cast<int>(found[0].match_points.size()), found[0].matches);
  for (const cv::Point2f& m : found[0].match_points)
    EXPECT_TRUE(cv::Rect2f(176, 86, 104, 104).contains(m)) << m;

  // Whole image when no region is given; a region elsewhere sees nothing.
  const auto whole = recognizer.recognize(scene, {}, memory);
  ASSERT_EQ(whole.size(), 1u);
  EXPECT_EQ(whole[0].label, "cup");
  EXPECT_TRUE(recognizer.recognize(scene, {{cv::Rect(0, 0, 150, 150), 1}}, memory).empty());
  // A scene with neither object: no label.
  const cv::Mat other = background(320, 240, 4);
  cv::Mat third = other.clone();
  objectImage(96, 13).copyTo(third(cv::Rect(100, 60, 96, 96)));
  EXPECT_TRUE(recognizer.recognize(third, {}, memory).empty());
}

TEST(ObjectRecognizer, AViewWithTooFewKeypointsIsNotLearnable)
{
  ObjectRecognizer recognizer(trainedDescriptor(), ObjectRecognizer::Parameters());
  const ObjectView rich = recognizer.describe(objectImage(96, 11), cv::Rect(), "cup");
  ASSERT_GE(rich.keypoints.size(), 25u);
  EXPECT_EQ(recognizer.learnProblem(rich), "");
  // The same view cut to 11 keypoints: one short of the default.
  ObjectView small = rich;
  small.keypoints.resize(11);
  const std::string why = recognizer.learnProblem(small);
  EXPECT_NE(why.find("only 11 keypoints"), std::string::npos) << why;
  EXPECT_NE(why.find("12 needed"), std::string::npos) << why;
  // min_matches above min_view_keypoints raises the need with it: a view must be able to verify at all.
  ObjectRecognizer::Parameters p = recognizer.parameters();
  p.min_view_keypoints = 5;
  p.verifier.min_inliers = 25;
  recognizer.setParameters(p);
  EXPECT_NE(recognizer.learnProblem(small).find("25 needed"), std::string::npos);
  p.verifier.min_inliers = 5;
  recognizer.setParameters(p);
  EXPECT_EQ(recognizer.learnProblem(small), "");
}

TEST(ObjectRecognizer, CoarseDftSizesRebuildFewerKernelSpectraForGrowingRegionsAndFindTheSameObject)
{
  ObjectRecognizer::Parameters dense_parameters;
  dense_parameters.coarse_dft_sizes = false;
  ObjectRecognizer coarse(trainedDescriptor(), ObjectRecognizer::Parameters());
  ObjectRecognizer dense(trainedDescriptor(), dense_parameters);
  ObjectMemory memory(128, trainedDescriptor()->model().id());
  const cv::Mat cup = objectImage(96, 11);
  memory.addView(coarse.describe(cup, cv::Rect(), "cup"));
  cv::Mat scene = background(320, 240, 3);
  cup.copyTo(scene(cv::Rect(180, 90, 96, 96)));
  // A region that grows by 2 px a frame, as a salient region around a fixated object does.
  long built_coarse = 0, built_dense = 0;
  for (int k = 0; k < 12; ++k)
  {
    const cv::Rect box(170 - k, 80 - k, 116 + 2 * k, 116 + 2 * k);
    ObjectRecognizer::Statistics sc, sd;
    const auto a = coarse.recognize(scene, {{box, 0}}, memory, &sc);
    const auto b = dense.recognize(scene, {{box, 0}}, memory, &sd);
    ASSERT_EQ(a.size(), 1u) << k;
    ASSERT_EQ(b.size(), 1u) << k;
    EXPECT_EQ(a[0].label, "cup");
    EXPECT_EQ(b[0].label, "cup");
    built_coarse += sc.kernel_spectra_built;
    built_dense += sd.kernel_spectra_built;
  }
  EXPECT_GT(built_dense, 0);
  // Measured: 9 sets coarse, 18 dense.
  EXPECT_LE(10 * built_coarse, 6 * built_dense) << "coarse " << built_coarse << ", dense " << built_dense;
  // Switching the sizes through setParameters() rebuilds the pyramid: its cache starts empty.
  ObjectRecognizer::Parameters p = coarse.parameters();
  p.coarse_dft_sizes = false;
  coarse.setParameters(p);
  ObjectRecognizer::Statistics after;
  coarse.recognize(scene, {{cv::Rect(170, 80, 116, 116), 0}}, memory, &after);
  EXPECT_GT(after.kernel_spectra_built, 0);
}

TEST(ObjectRecognizer, DefinedBehaviourForOddRegionsAndEmptyMemory)
{
  ObjectRecognizer recognizer(trainedDescriptor(), ObjectRecognizer::Parameters());
  ObjectMemory memory(128, trainedDescriptor()->model().id());
  const cv::Mat scene = background(160, 120, 5);
  ObjectRecognizer::Statistics stats;
  EXPECT_TRUE(recognizer.recognize(scene, {}, memory, &stats).empty());  // empty memory
  memory.addView(recognizer.describe(objectImage(96, 11), cv::Rect(), "cup"));
  const std::vector<SearchRegion> odd{{cv::Rect(500, 500, 50, 50), 0},     // outside
                                      {cv::Rect(10, 10, 0, 0), 1},         // empty
                                      {cv::Rect(10, 10, 5, 5), 2},         // tiny
                                      {cv::Rect(-50, -50, 400, 400), 3}};  // larger than the image
  EXPECT_NO_THROW(recognizer.recognize(scene, odd, memory, &stats));
  EXPECT_EQ(stats.regions_skipped, 3);
  EXPECT_EQ(stats.regions_processed, 1);
  EXPECT_THROW(recognizer.describe(scene, cv::Rect(400, 400, 20, 20), "x"), std::invalid_argument);
}
