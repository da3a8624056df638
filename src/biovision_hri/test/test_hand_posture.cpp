#include <fstream>
#include <functional>
#include <iterator>
#include <limits>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "biovision_common/payload_reader.hpp"
#include "biovision_common/payload_writer.hpp"
#include "biovision_common/stored_file.hpp"
#include "biovision_common/synthetic_images.hpp"
#include "biovision_hri/hand_gesture_reader.hpp"
#include "biovision_hri/hand_posture_classifier.hpp"

using namespace biovision_hri;

namespace
{
/// A synthetic posture: a bright "palm" disc with `fingers` bars at fixed angles (distinct shapes).
cv::Mat posture(int size, int fingers)
{
  cv::Mat img(size, size, CV_32F, cv::Scalar(0.3));
  const cv::Point c(size / 2, size * 3 / 5);
  cv::circle(img, c, size / 5, 0.85, cv::FILLED);
  for (int f = 0; f < fingers; ++f)
  {
    const double a = (-60.0 + 120.0 * f / std::max(1, fingers - 1)) * CV_PI / 180.0;
    const cv::Point tip(c.x + static_cast<int>(size * 0.42 * std::sin(a)),
                        c.y - static_cast<int>(size * 0.5 * std::cos(a)));
    cv::line(img, c, tip, 0.85, size / 12);
  }
  cv::GaussianBlur(img, img, cv::Size(), 1.0);
  return img;
}

cv::Mat texture(int w, int h, unsigned seed)
{
  return biovision_common::SyntheticImages::smoothNoise({w, h}, seed, 0.2, 2.0, 0.1, 0.9);
}

/// The posture rotated and scaled about its centre, pasted at `at` into a 320x240 textured scene.
cv::Mat scene(const cv::Mat& object, double degrees, double scale, cv::Point at, cv::Rect* where)
{
  return biovision_common::SyntheticImages::paste(object, texture(320, 240, 7), degrees, scale, at,
                                                  cv::BORDER_REPLICATE, where);
}

HandPostureClassifier trained()
{
  HandPostureClassifier c{FeatureLayout(), HandPostureClassifier::Parameters()};
  for (int fingers : {1, 2, 5})
    for (double scale : {0.9, 1.1})
    {
      cv::Rect box;
      const cv::Mat s = scene(posture(90, fingers), 0.0, scale, {40, 40}, &box);
      c.addExample(s, box, "f" + std::to_string(fingers));
    }
  for (unsigned seed = 0; seed < 12; ++seed)
  {
    const cv::Mat t = texture(90, 90, 100 + seed);
    c.addExample(t, cv::Rect(0, 0, 90, 90), "none");
  }
  c.train();
  return c;
}
}  // namespace

TEST(HandPostureClassifier, RecognisesEachPostureRotatedScaledAndMovedAndRejectsTexture)
{
  HandPostureClassifier c = trained();
  ASSERT_EQ(c.labels(), (std::vector<std::string>{"f1", "f2", "f5", "none"}));
  // 6 regions x 3 rotations x 2 mirrors + 12 textures x 6.
  EXPECT_EQ(c.exampleCount(), 6u * 6u + 12u * 6u);
  for (int fingers : {1, 2, 5})
    for (const auto& [degrees, scale] :
         std::vector<std::pair<double, double>>{{0, 1.0}, {10, 1.0}, {-8, 1.25}, {5, 0.8}})
    {
      cv::Rect box;
      const cv::Mat s = scene(posture(90, fingers), degrees, scale, {170, 90}, &box);
      const GestureResult r = c.classify(s, {box}).front();
      EXPECT_EQ(r.label, "f" + std::to_string(fingers)) << degrees << " deg, scale " << scale;
      EXPECT_EQ(r.box, box);
      EXPECT_EQ(r.matches, 0);
    }
  const cv::Mat other = texture(320, 240, 555);
  const GestureResult r = c.classify(other, {cv::Rect(100, 60, 90, 90)}).front();
  EXPECT_EQ(r.label, "");
  EXPECT_EQ(r.best_label, "none");
}

TEST(HandPostureClassifier, MinScoreWithholdsWeakGestures)
{
  HandPostureClassifier c = trained();
  cv::Rect box;
  const cv::Mat s = scene(posture(90, 2), 0.0, 1.0, {170, 90}, &box);
  const GestureResult r = c.classify(s, {box}).front();
  ASSERT_EQ(r.label, "f2");
  auto p = c.parameters();
  p.min_score = r.score + 0.01;
  c.setParameters(p);
  const GestureResult withheld = c.classify(s, {box}).front();
  EXPECT_EQ(withheld.label, "");
  EXPECT_EQ(withheld.best_label, "f2");
  EXPECT_DOUBLE_EQ(withheld.score, r.score);
}

TEST(HandPostureClassifier, SavedModelLoadsWithTheSameScoresAndACorruptOneIsRefused)
{
  HandPostureClassifier c = trained();
  const std::string path = ::testing::TempDir() + "/posture.bin";
  c.save(path, "test");
  HandPostureClassifier loaded{FeatureLayout(), HandPostureClassifier::Parameters()};
  loaded.load(path);
  EXPECT_EQ(loaded.labels(), c.labels());
  EXPECT_EQ(loaded.layout(), c.layout());
  EXPECT_EQ(loaded.exampleCount(), 0u);
  std::vector<cv::Rect> boxes;
  cv::Rect box;
  const cv::Mat s = scene(posture(90, 5), 7.0, 1.1, {150, 60}, &box);
  boxes = {box, cv::Rect(0, 0, 60, 60), cv::Rect(400, 400, 20, 20)};
  const auto a = c.classify(s, boxes), b = loaded.classify(s, boxes);
  ASSERT_EQ(a.size(), 3u);
  for (size_t i = 0; i < a.size(); ++i)
  {
    EXPECT_EQ(a[i].label, b[i].label);
    EXPECT_EQ(a[i].best_label, b[i].best_label);
    EXPECT_FLOAT_EQ(static_cast<float>(a[i].score), static_cast<float>(b[i].score));
  }
  EXPECT_EQ(a[2].best_label, "");  // outside the image: nothing to classify

  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  for (size_t at : {size_t{30}, bytes.size() / 2, bytes.size() - 1})
  {
    std::string bad = bytes;
    bad[at] ^= 0x10;
    std::ofstream(path, std::ios::binary) << bad;
    EXPECT_THROW(loaded.load(path), biovision_common::StoredFileError) << "byte " << at;
  }
  std::ofstream(path, std::ios::binary) << bytes.substr(0, bytes.size() / 3);
  EXPECT_THROW(loaded.load(path), biovision_common::StoredFileError);
  // A refused file changes nothing.
  const auto after = loaded.classify(s, boxes);
  EXPECT_FLOAT_EQ(static_cast<float>(after[0].score), static_cast<float>(a[0].score));
  EXPECT_THROW(loaded.load(path + ".missing"), biovision_common::StoredFileError);
}

TEST(HandPostureClassifier, CommittedModelLoads)
{
  HandPostureClassifier c{FeatureLayout(), HandPostureClassifier::Parameters()};
  c.load(std::string(BIOVISION_HRI_MODELS) + "/hand_posture.bin");
  EXPECT_GE(c.labels().size(), 5u);
  EXPECT_NE(std::find(c.labels().begin(), c.labels().end(), "palm"), c.labels().end());
  EXPECT_NE(std::find(c.labels().begin(), c.labels().end(), "none"), c.labels().end());
}

TEST(HandPostureClassifier, RefusesBadInputAndParameters)
{
  HandPostureClassifier c{FeatureLayout(), HandPostureClassifier::Parameters()};
  const cv::Mat img = texture(100, 100, 1);
  EXPECT_THROW(c.classify(img, {cv::Rect(0, 0, 50, 50)}), std::logic_error);
  EXPECT_THROW(c.save(::testing::TempDir() + "/never.bin", ""), std::logic_error);
  EXPECT_THROW(c.addExample(img, cv::Rect(0, 0, 50, 50), ""), std::invalid_argument);
  EXPECT_THROW(c.addExample(img, cv::Rect(200, 200, 50, 50), "a"), std::invalid_argument);
  EXPECT_THROW(c.addExample(cv::Mat(), cv::Rect(0, 0, 50, 50), "a"), std::invalid_argument);
  EXPECT_THROW(c.addExample(cv::Mat(100, 100, CV_8UC1), cv::Rect(0, 0, 50, 50), "a"), std::invalid_argument);
  c.addExample(img, cv::Rect(0, 0, 50, 50), "none");
  EXPECT_THROW(c.train(), std::logic_error);  // one label
  c.addExample(texture(100, 100, 2), cv::Rect(0, 0, 50, 50), "none2");
  c.setParameters([] {
    auto p = HandPostureClassifier::Parameters();
    p.rejection_label = "none2";
    return p;
  }());
  EXPECT_NO_THROW(c.train());  // "none" is a gesture label here
  using Edit = std::function<void(HandPostureClassifier::Parameters&)>;
  for (const Edit& bad : std::vector<Edit>{[](HandPostureClassifier::Parameters& p) { p.C = 0; },
                                           [](HandPostureClassifier::Parameters& p) { p.rotation = 46; },
                                           [](HandPostureClassifier::Parameters& p) { p.margin = -0.1; },
                                           [](HandPostureClassifier::Parameters& p) { p.min_score = std::nan(""); }})
  {
    HandPostureClassifier::Parameters p;
    bad(p);
    EXPECT_THROW(c.setParameters(p), std::invalid_argument);
    EXPECT_THROW((HandPostureClassifier{FeatureLayout(), p}), std::invalid_argument);
  }
  EXPECT_THROW(c.classify(cv::Mat(), {cv::Rect(0, 0, 5, 5)}), std::invalid_argument);
}

TEST(FeatureLayout, WriteReadRoundTripAndRefusesAnInvalidLayout)
{
  FeatureLayout l;
  l.wavelength = 5.5;
  l.cell_size = 7;
  l.clip = 0.2;
  l.aspect_ratio = 0.75;
  biovision_common::PayloadWriter w;
  l.write(w);
  biovision_common::PayloadReader r(w.bytes());
  EXPECT_EQ(FeatureLayout::read(r), l);
  EXPECT_TRUE(r.atEnd());
  l.orientations = 99;
  biovision_common::PayloadWriter bad;
  l.write(bad);
  biovision_common::PayloadReader rb(bad.bytes());
  EXPECT_THROW(FeatureLayout::read(rb), std::invalid_argument);
}

// What a helper found trying to break it (2026-12-06).
TEST(HandPostureClassifier, RefusesWhatWouldSpoilTheModelOrNotLoadAgain)
{
  HandPostureClassifier c = trained();
  cv::Mat nan_region = texture(90, 90, 3);
  nan_region.at<float>(45, 45) = std::numeric_limits<float>::quiet_NaN();
  const size_t before = c.exampleCount();
  EXPECT_THROW(c.addExample(nan_region, cv::Rect(0, 0, 90, 90), "f1"), std::invalid_argument);
  EXPECT_EQ(c.exampleCount(), before) << "a refused example adds none of its copies";
  EXPECT_THROW(c.addExample(texture(90, 90, 3), cv::Rect(0, 0, 90, 90), std::string(257, 'x')), std::invalid_argument);
  EXPECT_THROW(c.addExample(texture(90, 90, 3), cv::Rect(0, 0, 1000000, 1000000), "f1"), std::invalid_argument);
  EXPECT_THROW(c.addExample(texture(90, 90, 3), cv::Rect(10, 10, 7, 7), "f1"), std::invalid_argument);
  // A box under 8 px holds no posture (blown up to the window it is interpolation alone).
  EXPECT_EQ(c.classify(texture(90, 90, 3), {cv::Rect(10, 10, 1, 1)}).front().best_label, "");
  EXPECT_THROW(c.save(::testing::TempDir() + "/long_provenance.bin", std::string((1u << 16) + 1, 'p')),
               std::invalid_argument);
  HandPostureClassifier::Parameters p;
  p.C = 1e-300;
  EXPECT_THROW(c.setParameters(p), std::invalid_argument);
  p = HandPostureClassifier::Parameters();
  p.rejection_label = "";
  EXPECT_THROW(c.setParameters(p), std::invalid_argument);
}

TEST(HandPostureClassifier, AModelWhoseScoresOverflowGivesNoGesture)
{
  // Finite weights load, but 1e38 in every one makes each score infinite: no gesture, no infinite score.
  biovision_common::PayloadWriter w;
  FeatureLayout().write(w);
  w.putString("none");
  w.put<uint64_t>(2);
  const std::vector<float> huge(FeatureLayout().featureCount(), 1e38f);
  for (const char* label : {"palm", "none"})
  {
    w.putString(label);
    w.putArray(huge.data(), huge.size());
    w.put<float>(0.0f);
  }
  w.putString("crafted");
  const std::string path = ::testing::TempDir() + "/overflowing_posture.bin";
  biovision_common::StoredFile::write(path, "BVHRIPOS", 1, w.bytes());
  HandPostureClassifier c{FeatureLayout(), HandPostureClassifier::Parameters()};
  ASSERT_NO_THROW(c.load(path));
  cv::Rect box;
  const cv::Mat s = scene(posture(90, 2), 0.0, 1.0, {150, 60}, &box);
  const GestureResult r = c.classify(s, {box}).front();
  EXPECT_EQ(r.label, "");
  EXPECT_EQ(r.best_label, "");
  EXPECT_TRUE(std::isfinite(r.score));
}

TEST(HandPostureClassifier, AFlatOrHugeOrNonFiniteRegionIsNoGesture)
{
  HandPostureClassifier c = trained();
  const cv::Mat flat(240, 320, CV_32F, cv::Scalar(0.5));
  cv::Mat nan_image = texture(320, 240, 4);
  nan_image.setTo(std::numeric_limits<float>::infinity());
  for (const auto& [image, box] :
       std::vector<std::pair<cv::Mat, cv::Rect>>{{flat, cv::Rect(100, 60, 90, 90)},
                                                 {cv::Mat(1, 1, CV_32F, cv::Scalar(0.2)), cv::Rect(0, 0, 1, 1)},
                                                 {texture(320, 240, 5), cv::Rect(0, 0, 1000000, 1000000)},
                                                 {texture(320, 240, 5), cv::Rect(-2000000000, 0, 2000000100, 50)},
                                                 {nan_image, cv::Rect(100, 60, 90, 90)}})
  {
    const GestureResult r = c.classify(image, {box}).front();
    EXPECT_EQ(r.label, "") << box;
    EXPECT_EQ(r.best_label, "") << box;
  }
}

TEST(HandGestureReader, KeypointsFirstThenPostureSvmsEachOnItsOwnBox)
{
  auto descriptor = std::make_shared<const biovision_recognition::V1Descriptor>(
      biovision_recognition::DescriptorModel::load(std::string(BIOVISION_RECOGNITION_MODELS) + "/" +
                                                   biovision_recognition::kDefaultModelFile));
  GestureRecognizer keypoints(descriptor, GestureRecognizer::Parameters());
  const cv::Mat shapes = biovision_common::SyntheticImages::randomShapes(100, 1);
  cv::Rect where;
  const cv::Mat learn = scene(shapes, 0.0, 1.0, {60, 50}, &where);
  ASSERT_GT(keypoints.addTemplate(learn, where, "shapes"), 10u);
  HandPostureClassifier postures = trained();

  cv::Rect shapes_box, posture_box;
  const cv::Mat shapes_scene = scene(shapes, 4.0, 1.0, {150, 70}, &shapes_box);
  const cv::Mat posture_scene = scene(posture(90, 2), 0.0, 1.0, {150, 70}, &posture_box);
  const cv::Rect none;  // an empty box: that method reads no gesture

  const HandGestureReader both(&keypoints, &postures);
  // The keypoints read it: the SVMs (which cannot say "shapes") are not asked, and the box each
  // method gets is its own.
  auto r = both.read(shapes_scene, {shapes_box}, {none});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].result.label, "shapes");
  EXPECT_EQ(r[0].method, HandGestureReader::kKeypoints);
  // The keypoints leave the posture without a gesture: the SVMs read it on their box.
  r = both.read(posture_scene, {posture_box}, {posture_box});
  EXPECT_EQ(r[0].result.label, "f2");
  EXPECT_EQ(r[0].method, HandGestureReader::kPostureSvm);
  r = both.read(posture_scene, {posture_box}, {none});
  EXPECT_EQ(r[0].result.label, "");
  EXPECT_EQ(r[0].method, HandGestureReader::kPostureSvm);
  // Several hands at once, in order.
  r = both.read(posture_scene, {none, posture_box}, {posture_box, none});
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].result.label, "f2");
  EXPECT_EQ(r[1].result.label, "");

  // Either method off.
  EXPECT_EQ(HandGestureReader(nullptr, &postures).read(posture_scene, {none}, {posture_box})[0].result.label, "f2");
  r = HandGestureReader(&keypoints, nullptr).read(posture_scene, {posture_box}, {posture_box});
  EXPECT_EQ(r[0].result.label, "");
  EXPECT_EQ(r[0].method, HandGestureReader::kKeypoints);
  r = HandGestureReader(nullptr, nullptr).read(posture_scene, {posture_box}, {posture_box});
  EXPECT_EQ(r[0].result.label, "");
  EXPECT_EQ(r[0].method, "");

  EXPECT_TRUE(both.read(posture_scene, {}, {}).empty());
  EXPECT_THROW(both.read(posture_scene, {posture_box}, {}), std::invalid_argument);
  // A bad image is refused whichever methods are on (the templates alone had read it as no gesture).
  for (const HandGestureReader& reader :
       {both, HandGestureReader(&keypoints, nullptr), HandGestureReader(nullptr, nullptr)})
  {
    EXPECT_THROW(reader.read(cv::Mat(), {posture_box}, {posture_box}), std::invalid_argument);
    EXPECT_THROW(reader.read(cv::Mat(240, 320, CV_8UC1, cv::Scalar(0)), {posture_box}, {posture_box}),
                 std::invalid_argument);
  }
}
