#include <cstdio>
#include <fstream>
#include <set>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "biovision_common/stored_file.hpp"
#include "biovision_hri/linear_detector_model.hpp"
#include "biovision_hri/linear_svm_trainer.hpp"
#include "biovision_hri/non_maximum_suppression.hpp"
#include "biovision_hri/sliding_window_detector.hpp"
#include "hri_datasets.hpp"

using namespace biovision_hri;

namespace
{
cv::Mat texture(cv::Size size, uint64_t seed, double blur = 1.5)
{
  cv::Mat noise(size, CV_32F);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::UNIFORM, 0.0, 1.0);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), blur);
  cv::normalize(noise, noise, 0.0, 1.0, cv::NORM_MINMAX);
  return noise;
}

LinearDetectorModel randomModel(uint64_t seed)
{
  LinearDetectorModel m;
  m.kind = "face";
  m.weights.resize(m.layout.featureCount());
  cv::RNG rng(seed);
  for (float& w : m.weights)
    w = static_cast<float>(rng.uniform(-1.0, 1.0));
  m.bias = -0.25f;
  m.provenance = "test";
  return m;
}

Detection box(float x, float y, float side, float score)
{
  Detection d;
  d.box = cv::Rect2f(x, y, side, side);
  d.score = score;
  return d;
}

std::string tempPath(const std::string& name)
{
  return ::testing::TempDir() + "/" + name;
}

std::string sharedRoot()
{
  return hriDataRoot(BIOVISION_DEFAULT_SHARED);
}
}  // namespace

TEST(NonMaximumSuppression, KeepsTheStrongerOfTwoWindowsOverlappingByHalfOrMore)
{
  // IoU of two 10x10 boxes shifted by 2 px: 80 / 120 = 0.67.
  const auto kept = nonMaximumSuppression({box(0, 0, 10, 1.0f), box(2, 0, 10, 2.0f)}, 0.5);
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_FLOAT_EQ(kept[0].score, 2.0f);
}

TEST(NonMaximumSuppression, KeepsWindowsOverlappingLessThanTheLimit)
{
  // Shifted by 5 px: IoU 50 / 150 = 0.33 < 0.5; a third far away.
  const auto kept = nonMaximumSuppression({box(0, 0, 10, 1.0f), box(5, 0, 10, 3.0f), box(50, 50, 10, 2.0f)}, 0.5);
  ASSERT_EQ(kept.size(), 3u);
  EXPECT_FLOAT_EQ(kept[0].score, 3.0f);  // strongest first
  EXPECT_FLOAT_EQ(kept[1].score, 2.0f);
  EXPECT_FLOAT_EQ(kept[2].score, 1.0f);
}

TEST(NonMaximumSuppression, ASuppressedWindowDoesNotSuppressOthers)
{
  // b overlaps a (kept) and c; c overlaps only b. b is dropped, so c stays.
  const auto kept = nonMaximumSuppression({box(0, 0, 10, 3.0f), box(3, 0, 10, 2.0f), box(6, 0, 10, 1.0f)}, 0.5);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_FLOAT_EQ(kept[1].score, 1.0f);
  EXPECT_THROW(nonMaximumSuppression({}, 0.0), std::invalid_argument);
  EXPECT_DOUBLE_EQ(intersectionOverUnion(cv::Rect2f(0, 0, 10, 10), cv::Rect2f(0, 0, 10, 10)), 1.0);
  EXPECT_DOUBLE_EQ(intersectionOverUnion(cv::Rect2f(0, 0, 10, 10), cv::Rect2f(20, 0, 10, 10)), 0.0);
}

TEST(SlidingWindowDetector, TheScanEqualsABruteForceDotProductPerWindow)
{
  const LinearDetectorModel model = randomModel(7);
  SlidingWindowDetector detector(model, SlidingWindowDetector::Parameters());
  ComplexCellFeatures features(model.layout);
  const cv::Mat image = texture(cv::Size(100, 80), 8);
  const std::vector<cv::Mat> cells = features.complexCells(image);
  std::vector<float> x(model.layout.featureCount());
  for (const int cell : {6, 7})
    for (const int stride : {1, 3})
    {
      const BlockMap map = features.blockMap(cells, cell);
      const cv::Mat scores = detector.scoreMap(map, stride);
      const int side = model.layout.windowSide(cell);
      ASSERT_EQ(scores.cols, (100 - side) / stride + 1);
      ASSERT_EQ(scores.rows, (80 - side) / stride + 1);
      double worst = 0;
      for (int j = 0; j < scores.rows; ++j)
        for (int i = 0; i < scores.cols; ++i)
        {
          features.window(map, i * stride, j * stride, x.data());
          double reference = model.bias;
          for (size_t k = 0; k < x.size(); ++k)
            reference += static_cast<double>(model.weights[k]) * x[k];
          worst = std::max(worst, std::abs(reference - scores.at<float>(j, i)));
        }
      EXPECT_LT(worst, 1e-3) << "cell " << cell << " stride " << stride;
    }
}

TEST(SlidingWindowDetector, ADetectionsDenseFeaturesGiveItsScore)
{
  // Hard-negative mining reads a detection's features from the last scan's block maps: w . x + b must be
  // the score the scan gave it, at every level and cell size.
  const LinearDetectorModel model = randomModel(9);
  SlidingWindowDetector::Parameters p;
  p.threshold = -5.0;
  p.max_size = 150.0;
  p.max_detections = 1000;
  p.nms_overlap = 0.3;
  SlidingWindowDetector detector(model, p);
  const std::vector<Detection> found = detector.detect(texture(cv::Size(160, 120), 10));
  ASSERT_GT(found.size(), 10u);
  std::set<int> levels;
  std::vector<float> x(model.layout.featureCount());
  for (const Detection& d : found)
  {
    detector.lastFeatures(d, x.data());
    EXPECT_NEAR(model.score(x.data()), d.score, 1e-3) << "level " << d.level << " cell " << d.cell_size;
    levels.insert(d.level);
  }
  EXPECT_GE(levels.size(), 2u) << "detections from more than one pyramid level";
  Detection stranger = found.front();
  stranger.level = 40;
  EXPECT_THROW(detector.lastFeatures(stranger, x.data()), std::out_of_range);
}

TEST(SlidingWindowDetector, FindsATemplateWhereItWasPastedAtTwoScales)
{
  // A matched filter: w = the template's features minus the mean of background features.
  const FeatureLayout layout;
  ComplexCellFeatures features(layout);
  cv::Mat pattern(42, 42, CV_32F, cv::Scalar(0.1));
  cv::circle(pattern, {21, 21}, 15, cv::Scalar(0.9), -1);
  cv::rectangle(pattern, cv::Rect(14, 12, 5, 6), cv::Scalar(0.1), -1);
  cv::rectangle(pattern, cv::Rect(24, 12, 5, 6), cv::Scalar(0.1), -1);
  cv::line(pattern, {14, 30}, {28, 30}, cv::Scalar(0.1), 2);
  const cv::Mat t = features.patchFeatures(pattern);
  const cv::Mat background = features.patchFeatures(texture(cv::Size(42, 42), 9, 3.0));
  LinearDetectorModel model;
  model.kind = "face";
  model.weights.assign(t.ptr<float>(), t.ptr<float>() + t.cols);
  for (int k = 0; k < t.cols; ++k)
    model.weights[k] -= background.at<float>(k);
  model.bias = 0.f;
  const float self = model.score(t.ptr<float>());
  model.bias = -0.5f * self;

  SlidingWindowDetector::Parameters p;
  p.stride = 1;
  p.max_size = 120;
  SlidingWindowDetector detector(model, p);
  for (const int side : {42, 70})
  {
    cv::Mat scene = texture(cv::Size(200, 160), 10, 3.0) * 0.5 + 0.25;
    cv::Mat resized;
    cv::resize(pattern, resized, cv::Size(side, side), 0, 0, cv::INTER_LINEAR);
    const cv::Rect where(90, 50, side, side);
    resized.copyTo(scene(where));
    SlidingWindowDetector::Statistics stats;
    const auto found = detector.detect(scene, cv::Rect(), &stats);
    ASSERT_FALSE(found.empty()) << "side " << side;
    EXPECT_GT(intersectionOverUnion(found.front().box, cv::Rect2f(where)), 0.7)
        << "side " << side << ": best " << found.front().box << " score " << found.front().score;
    EXPECT_GT(stats.windows, 1000);
    // Searching only a region away from the pattern finds nothing there.
    for (const Detection& d : detector.detect(scene, cv::Rect(0, 0, 80, 160)))
      EXPECT_LE(d.box.x + d.box.width, 80.5f);
  }
}

TEST(SlidingWindowDetector, ARegionSmallerThanTheWindowGivesNothingAndHugeOnesAreRefused)
{
  SlidingWindowDetector detector(randomModel(11), SlidingWindowDetector::Parameters());
  const cv::Mat image = texture(cv::Size(120, 100), 12);
  EXPECT_TRUE(detector.detect(image, cv::Rect(10, 10, 30, 30)).empty());
  EXPECT_TRUE(detector.detect(image, cv::Rect(500, 500, 50, 50)).empty());  // outside: clipped to nothing
  EXPECT_THROW(detector.detect(cv::Mat(3000, 3000, CV_32F, cv::Scalar(0))), std::invalid_argument);
  EXPECT_THROW(detector.detect(cv::Mat(100, 100, CV_8U)), std::invalid_argument);
  SlidingWindowDetector::Parameters bad;
  bad.nms_overlap = 0.0;
  EXPECT_THROW(detector.setParameters(bad), std::invalid_argument);
}

TEST(LinearDetectorModel, RoundTripsThroughItsFile)
{
  LinearDetectorModel m = randomModel(13);
  m.layout.grid_step = 1;  // every stored layout field, not just the defaults
  m.layout.clip = 0.2;
  m.layout.epsilon = 0.002;
  m.layout.aspect_ratio = 0.8;
  const std::string path = tempPath("model.bin");
  m.save(path);
  const LinearDetectorModel back = LinearDetectorModel::load(path);
  EXPECT_EQ(back.kind, m.kind);
  EXPECT_TRUE(back.layout == m.layout);
  EXPECT_EQ(back.weights, m.weights);
  EXPECT_EQ(back.bias, m.bias);
  EXPECT_EQ(back.provenance, m.provenance);
}

TEST(LinearDetectorModel, ACorruptTruncatedOrForeignFileIsRefused)
{
  const std::string path = tempPath("corrupt.bin");
  randomModel(14).save(path);
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  auto write = [&](const std::string& content) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << content;
  };
  std::string flipped = bytes;
  flipped[bytes.size() / 2] ^= 0x10;
  write(flipped);
  EXPECT_THROW(LinearDetectorModel::load(path), biovision_common::StoredFileError);
  write(bytes.substr(0, bytes.size() - 9));
  EXPECT_THROW(LinearDetectorModel::load(path), biovision_common::StoredFileError);
  write("P5\n42 42\n255\n" + std::string(42 * 42, '\0'));
  EXPECT_THROW(LinearDetectorModel::load(path), biovision_common::StoredFileError);
  EXPECT_THROW(LinearDetectorModel::load(tempPath("missing.bin")), biovision_common::StoredFileError);

  LinearDetectorModel short_model = randomModel(15);
  short_model.weights.pop_back();
  EXPECT_THROW(short_model.save(path), std::invalid_argument);
}

TEST(LinearSvmTrainer, SeparatesTwoClustersWithTheRightSign)
{
  cv::Mat samples(200, 3, CV_32F);
  std::vector<int> labels(200);
  cv::RNG rng(16);
  for (int i = 0; i < 200; ++i)
  {
    labels[i] = i % 2 ? 1 : -1;
    for (int k = 0; k < 3; ++k)
      samples.at<float>(i, k) = static_cast<float>(rng.gaussian(0.3) + (k == 0 ? (labels[i] > 0 ? 2.0 : 0.0) : 1.0));
  }
  LinearSvmTrainer::Parameters p;
  p.C = 1.0;
  const auto r = LinearSvmTrainer::train(samples, labels, p);
  ASSERT_EQ(r.weights.size(), 3u);
  EXPECT_GT(r.weights[0], 0.f);
  int correct = 0;
  for (int i = 0; i < 200; ++i)
  {
    float s = r.bias;
    for (int k = 0; k < 3; ++k)
      s += r.weights[k] * samples.at<float>(i, k);
    correct += (s > 0) == (labels[i] > 0);
  }
  EXPECT_GE(correct, 195);
  EXPECT_THROW(LinearSvmTrainer::train(samples, std::vector<int>(200, 1), p), std::invalid_argument);
  EXPECT_THROW(LinearSvmTrainer::train(samples, std::vector<int>(10, 1), p), std::invalid_argument);
}

TEST(CommittedModels, LoadAndHaveTheThesisLayout)
{
  for (const std::string kind : {"face", "hand"})
  {
    const LinearDetectorModel m = LinearDetectorModel::load(std::string(BIOVISION_HRI_MODELS) + "/" + kind +
                                                            "_detector.bin");
    EXPECT_EQ(m.kind, kind);
    EXPECT_EQ(m.weights.size(), 1152u);
    EXPECT_NE(m.provenance.find("train_detector"), std::string::npos) << m.provenance;
  }
}

TEST(CommittedModels, TheFaceModelSeparatesHeldOutFacesFromScenePatches)
{
  // Test part of the data (never trained on): faces must mostly score above scene patches.
  const LinearDetectorModel m = LinearDetectorModel::load(std::string(BIOVISION_HRI_MODELS) + "/face_detector.bin");
  std::vector<std::string> faces = splitPart(positiveCrops(sharedRoot(), "face"), Split::Test);
  faces.resize(200);
  std::vector<cv::Mat> patches;
  for (const auto& f : faces)
    patches.push_back(readGray(f));
  const cv::Mat positive = patchFeatureRows(m.layout, patches, false);
  std::vector<cv::Mat> scenes;
  for (const auto& f : splitPart(sceneFiles(sharedRoot()), Split::Test))
    scenes.push_back(readGray(f));
  cv::RNG rng(17);
  const cv::Mat negative = patchFeatureRows(m.layout, randomScenePatches(scenes, 400, rng, 42, 200), false);
  int hits = 0, false_alarms = 0;
  for (int i = 0; i < positive.rows; ++i)
    hits += m.score(positive.ptr<float>(i)) > 0;
  for (int i = 0; i < negative.rows; ++i)
    false_alarms += m.score(negative.ptr<float>(i)) > 0;
  EXPECT_GT(hits, 0.85 * positive.rows);
  EXPECT_LT(false_alarms, 0.05 * negative.rows);
}

TEST(Training, ASmallFastTrainingOnASubsetSeparatesHeldOutCrops)
{
  // 150 faces (+ mirrors) and 600 scene patches from the training part; tested on the validation part.
  const FeatureLayout layout;
  auto crops = [&](Split split, size_t n) {
    const auto files = splitPart(positiveCrops(sharedRoot(), "face"), split);
    std::vector<cv::Mat> patches;
    for (size_t i = 0; i < n; ++i)
      patches.push_back(readGray(files[i * files.size() / n]));
    return patches;
  };
  auto scenes = [&](Split split) {
    std::vector<cv::Mat> s;
    for (const auto& f : splitPart(sceneFiles(sharedRoot()), split))
      s.push_back(readGray(f));
    return s;
  };
  cv::RNG rng(18);
  cv::Mat samples = patchFeatureRows(layout, crops(Split::Train, 150), true);
  std::vector<int> labels(samples.rows, 1);
  const cv::Mat negatives = patchFeatureRows(layout, randomScenePatches(scenes(Split::Train), 600, rng, 42, 200),
                                             false);
  samples.push_back(negatives);
  labels.insert(labels.end(), negatives.rows, -1);
  const auto r = LinearSvmTrainer::train(samples, labels, LinearSvmTrainer::Parameters());
  LinearDetectorModel m;
  m.kind = "face";
  m.weights = r.weights;
  m.bias = r.bias;
  const cv::Mat pos = patchFeatureRows(layout, crops(Split::Validation, 100), false);
  const cv::Mat neg = patchFeatureRows(layout, randomScenePatches(scenes(Split::Validation), 200, rng, 42, 200), false);
  int correct = 0;
  for (int i = 0; i < pos.rows; ++i)
    correct += m.score(pos.ptr<float>(i)) > 0;
  for (int i = 0; i < neg.rows; ++i)
    correct += m.score(neg.ptr<float>(i)) <= 0;
  EXPECT_GT(correct, 0.85 * (pos.rows + neg.rows));
}
