#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/Eigenvalues>
#include <opencv2/imgproc.hpp>

#include "biovision_common/hamming_distance.hpp"
#include "biovision_recognition/lda_hash_statistics.hpp"
#include "biovision_recognition/lda_hash_trainer.hpp"
#include "biovision_recognition/pooled_cell_features.hpp"
#include "biovision_recognition/packed_projection.hpp"
#include "biovision_recognition/v1_descriptor.hpp"
#include "test_images.hpp"
#include "biovision_common/hamming_distance.hpp"

using biovision_common::hammingDistanceReference;

using namespace biovision_recognition;
using namespace test_images;

namespace
{
std::string modelPath()
{
  return std::string(BIOVISION_RECOGNITION_MODELS) + "/" + biovision_recognition::kDefaultModelFile;
}
}  // namespace

TEST(V1FeaturePyramid, HalfOctaveLevelsAndCoordinates)
{
  EXPECT_NEAR(V1FeaturePyramid::wavelengthOfLevel(0), 4.0, 1e-12);
  EXPECT_NEAR(V1FeaturePyramid::wavelengthOfLevel(1), 4.0 * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(V1FeaturePyramid::wavelengthOfLevel(6), 32.0, 1e-12);
  EXPECT_EQ(V1FeaturePyramid::levelOfWavelength(6.0), 1);  // the source's 6 is level 1 (5.66)
  EXPECT_EQ(V1FeaturePyramid::levelOfWavelength(12.0), 3);
  EXPECT_EQ(V1FeaturePyramid::levelOfWavelength(24.0), 5);
  V1FeaturePyramid pyramid;
  pyramid.build(texture(200, 150, 1));
  ASSERT_GE(pyramid.levels(), 6);
  EXPECT_EQ(pyramid.responses(2).gridSize(), cv::Size(100, 75));
  const cv::Point2f p(123.25f, 77.5f);
  for (int k = 0; k < pyramid.levels(); ++k)
  {
    const cv::Point2f back = pyramid.toImage(pyramid.toLevel(p, k), k);
    EXPECT_NEAR(back.x, p.x, 1e-3);
    EXPECT_NEAR(back.y, p.y, 1e-3);
  }
  EXPECT_THROW(pyramid.build(cv::Mat()), std::invalid_argument);
}

TEST(V1FeaturePyramid, SkippingFineLevelsLeavesTheCoarserCellsAndDescriptorsUnchanged)
{
  const V1Descriptor descriptor(DescriptorModel::load(modelPath()));
  const cv::Mat image = texture(150, 130, 5);
  V1FeaturePyramid full(descriptor.pyramidParameters()), coarse(descriptor.pyramidParameters());
  full.build(image);
  coarse.build(image, 1);
  ASSERT_EQ(coarse.levels(), full.levels());
  EXPECT_EQ(coarse.firstLevel(), 1);
  EXPECT_THROW(coarse.pooled(0), std::out_of_range);
  EXPECT_THROW(coarse.responses(0), std::out_of_range);
  EXPECT_EQ(cv::norm(coarse.image(0), full.image(0), cv::NORM_INF), 0.0);
  // Equal up to the FFT's rounding (the cached plans differ between the builds: measured after 16 uses).
  for (int k = 1; k < full.levels(); ++k)
  {
    EXPECT_LT(cv::norm(coarse.pooled(k), full.pooled(k), cv::NORM_INF), 1e-6) << "level " << k;
    EXPECT_LT(cv::norm(coarse.responses(k).odd[3], full.responses(k).odd[3], cv::NORM_INF), 1e-6) << "level " << k;
  }
  // Keypoints of level 0 are not detected; those of the levels kept are the same.
  EXPECT_TRUE(coarse.detectKeypoints({0}).empty());
  const auto a = full.detectKeypoints({1, 3});
  const auto b = coarse.detectKeypoints({1, 3});
  ASSERT_EQ(a.size(), b.size());
  ASSERT_FALSE(a.empty());
  const BinaryCodeSet codes_full = descriptor.compute(full, a), codes_coarse = descriptor.compute(coarse, b);
  ASSERT_EQ(codes_full.size(), codes_coarse.size());
  for (size_t i = 0; i < codes_full.size(); ++i)
    EXPECT_EQ(hammingDistanceReference(codes_full.code(i), codes_coarse.code(i), codes_full.words()), 0);
  // A descriptor of a level-0 keypoint needs level 0's cells.
  biovision_v1::Keypoint fine = a.front();
  fine.wavelength = static_cast<float>(V1FeaturePyramid::wavelengthOfLevel(0));
  EXPECT_THROW(descriptor.compute(coarse, {fine}), std::out_of_range);
  EXPECT_THROW(coarse.build(image, -1), std::invalid_argument);
}

TEST(V1FeaturePyramid, PooledMapsEqualMorphologicalMaxAndMinOverTheDisk)
{
  // The reference: planar cv::dilate / cv::erode with the disk (default border), negated OFF maps, merged.
  for (int d : {1, 2, 3, 4, 5, 7})
    for (int phases : {2, 4})
    {
      V1FeaturePyramid::Parameters p;
      p.pooling_diameter = d;
      p.pooling_phases = phases;
      V1FeaturePyramid pyramid(p);
      pyramid.build(texture(61, 47, d));
      const int n = p.orientations;
      for (int k = 0; k < pyramid.levels(); ++k)
      {
        const auto& r = pyramid.responses(k);
        std::vector<cv::Mat> maps(phases * n);
        for (int i = 0; i < n; ++i)
        {
          cv::dilate(r.even[i], maps[i], pyramid.poolingDisk());
          cv::dilate(r.odd[i], maps[n + i], pyramid.poolingDisk());
          if (phases == 4)
          {
            cv::erode(r.even[i], maps[2 * n + i], pyramid.poolingDisk());
            cv::erode(r.odd[i], maps[3 * n + i], pyramid.poolingDisk());
            maps[2 * n + i] *= -1.f;
            maps[3 * n + i] *= -1.f;
          }
        }
        cv::Mat reference;
        cv::merge(maps, reference);
        ASSERT_EQ(pyramid.pooled(k).type(), reference.type());
        EXPECT_EQ(cv::norm(pyramid.pooled(k), reference, cv::NORM_INF), 0.0)
            << "diameter " << d << ", phases " << phases << ", level " << k;
      }
    }
}

TEST(PooledCellFeatures, LayoutSizes)
{
  DescriptorLayout layout;
  EXPECT_EQ(layout.gridSide(0), 15);  // 32 px patch, diameter 4, step 2: the source's 15 x 15 fields
  EXPECT_EQ(layout.gridSide(2), 7);
  EXPECT_EQ(layout.gridSide(6), 1);
  EXPECT_EQ(layout.featureCount(), 32 * (225 + 100 + 49 + 16 + 9 + 1 + 1));  // 4 phases x 8 orientations
  layout.scales = {0};
  EXPECT_EQ(layout.featureCount(), 7200);
  layout.phases = 2;
  EXPECT_EQ(layout.featureCount(), 3600);
  layout.phases = 3;
  EXPECT_THROW(layout.validate(), std::invalid_argument);
  layout.phases = 2;
  layout.scales = {2, 1};
  EXPECT_THROW(layout.validate(), std::invalid_argument);
}

TEST(V1FeaturePyramid, OffPhasesPoolTheNegativeHalfWaves)
{
  V1FeaturePyramid pyramid;  // 4 phases
  pyramid.build(texture(120, 100, 3));
  const int n = pyramid.parameters().orientations;
  ASSERT_EQ(pyramid.pooled(1).channels(), 4 * n);
  for (int i = 0; i < n; ++i)
  {
    const cv::Mat& even = pyramid.responses(1).even[i];
    cv::Mat on, off;
    cv::extractChannel(pyramid.pooled(1), on, i);
    cv::extractChannel(pyramid.pooled(1), off, 2 * n + i);
    // Each pooled map bounds its own half-wave from above, and the OFF map carries what the signed
    // maximum loses: where a whole pooling field is negative, ON < 0 but OFF > 0.
    EXPECT_EQ(cv::countNonZero(on < even - 1e-6f), 0);
    EXPECT_EQ(cv::countNonZero(off < -even - 1e-6f), 0);
    EXPECT_GT(cv::countNonZero((on < 0.f) & (off > 0.f)), 0);
  }
}

TEST(PooledCellFeatures, TwoPhaseLayoutReadsTheOnPhasesOfAFourPhasePyramid)
{
  const cv::Mat image = texture(160, 160, 5);
  V1FeaturePyramid::Parameters two;
  two.pooling_phases = 2;
  V1FeaturePyramid with_two(two), with_four;
  with_two.build(image);
  with_four.build(image);
  DescriptorLayout layout;
  layout.phases = 2;
  const PooledCellFeatures features(layout);
  const std::vector<biovision_v1::Keypoint> kps{at(80, 80, 4.f), at(60, 90, 8.f)};
  // Equal within rounding: a DFT plan may be measured between the two builds (biovision_v1::FourierTransform).
  const cv::Mat from_two = features.extract(with_two, kps), from_four = features.extract(with_four, kps);
  EXPECT_LE(cv::norm(from_two, from_four, cv::NORM_INF), 1e-5 * std::max(cv::norm(from_four, cv::NORM_INF), 1e-12));
  // A 4-phase layout cannot read a 2-phase pyramid.
  EXPECT_THROW(PooledCellFeatures(DescriptorLayout()).extract(with_two, kps), std::invalid_argument);
}

TEST(PooledCellFeatures, InvariantToBrightnessOffsetAndContrastGain)
{
  const cv::Mat image = texture(160, 160, 2);
  const DescriptorLayout layout;
  const PooledCellFeatures features(layout);
  V1FeaturePyramid a, b;
  a.build(image);
  b.build(image * 0.5 + 0.3);  // half the contrast, brighter
  const std::vector<biovision_v1::Keypoint> kps{at(80, 80, 4.f), at(60, 90, 5.66f), at(100, 70, 8.f)};
  const cv::Mat xa = features.extract(a, kps), xb = features.extract(b, kps);
  ASSERT_EQ(xa.cols, layout.featureCount());
  for (int r = 0; r < xa.rows; ++r)
  {
    EXPECT_GT(cv::norm(xa.row(r)), 1.0);  // unit per scale: the vector has real content
    EXPECT_LT(cv::norm(xa.row(r) - xb.row(r)), 1e-3 * cv::norm(xa.row(r)));
  }
}

TEST(LdaHashTrainer, FindsTheKnownProjectionOnSyntheticGaussianClasses)
{
  // 8 features; class identity lives in features 0 and 1 (unit variance, tiny within-class noise); features
  // 2..7 are pure within-class noise as large as the signal. The projection must ignore 2..7.
  std::mt19937 rng(4);
  std::normal_distribution<float> g;
  const int n = 4000, d = 8;
  LdaHashTrainer::Matrix pa(n, d), pb(n, d), na(n, d), nb(n, d);
  auto sample = [&](float z0, float z1, LdaHashTrainer::Matrix& m, int row) {
    m(row, 0) = z0 + 0.05f * g(rng);
    m(row, 1) = z1 + 0.05f * g(rng);
    for (int c = 2; c < d; ++c)
      m(row, c) = g(rng);
  };
  for (int i = 0; i < n; ++i)
  {
    const float z0 = g(rng), z1 = g(rng);
    sample(z0, z1, pa, i);
    sample(z0, z1, pb, i);
    sample(z0, z1, na, i);
    sample(g(rng), g(rng), nb, i);
  }
  LdaHashTrainer::Parameters p;
  p.bits = 2;
  p.whitening_rank = 8;
  const DescriptorModel m = LdaHashTrainer(p).train(pa, pb, na, nb);
  // The entry point on one side and the differences gives the same model.
  const DescriptorModel lean = LdaHashTrainer(p).trainOnDifferences(pa, pa - pb, na, na - nb);
  EXPECT_LT((lean.projection - m.projection).cwiseAbs().maxCoeff(), 1e-5f * m.projection.cwiseAbs().maxCoeff());
  EXPECT_LT((lean.thresholds - m.thresholds).cwiseAbs().maxCoeff(), 1e-3f);
  ASSERT_EQ(m.projection.rows(), 2);
  for (int b = 0; b < 2; ++b)
  {
    const float signal = m.projection.row(b).head(2).norm(), noise = m.projection.row(b).tail(6).norm();
    EXPECT_LT(noise, 0.05f * signal) << "bit " << b;
  }
  // Both bits fire for about half the data: thresholds near the (zero) mean of the projections.
  const Eigen::VectorXf y = m.projection * pa.row(0).transpose();
  (void)y;
  for (int b = 0; b < 2; ++b)
  {
    const Eigen::VectorXf proj = pa * m.projection.row(b).transpose();
    const double ones = (proj.array() > m.thresholds(b)).cast<double>().mean();
    EXPECT_NEAR(ones, 0.5, 0.1);
  }
}

TEST(LdaHashStatistics, MomentsEqualTheDirectSumAndTheSampleIsUniformAndBounded)
{
  // Blocks of an odd size so the 2048-row folding falls inside blocks; column 0 carries the row's index.
  using Kind = LdaHashStatistics::Kind;
  const int n = 5000, d = 6, cap = 500;
  std::mt19937 rng(9);
  std::normal_distribution<float> g;
  LdaHashStatistics::Matrix a(n, d), diff(n, d);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < d; ++c)
    {
      a(i, c) = c == 0 ? static_cast<float>(i) : g(rng);
      diff(i, c) = g(rng) + 0.5f * c;
    }
  LdaHashStatistics statistics(d, cap, 3);
  for (int from = 0; from < n; from += 37)
  {
    const int rows = std::min(37, n - from);
    statistics.add(Kind::positive, a.middleRows(from, rows), diff.middleRows(from, rows));
  }
  EXPECT_EQ(statistics.pairs(Kind::positive), n);
  EXPECT_EQ(statistics.pairs(Kind::negative), 0);
  const Eigen::MatrixXd direct = (diff.transpose() * diff).cast<double>();
  EXPECT_LT((statistics.moment(Kind::positive) - direct).cwiseAbs().maxCoeff(), 1e-4 * direct.cwiseAbs().maxCoeff());
  EXPECT_EQ(statistics.moment(Kind::negative).cwiseAbs().maxCoeff(), 0.0);

  const auto sample_a = statistics.sampleA(Kind::positive);
  const auto sample_diff = statistics.sampleDifference(Kind::positive);
  ASSERT_EQ(sample_a.rows(), cap);
  std::vector<int> seen;
  double mean = 0.0;
  for (int r = 0; r < cap; ++r)
  {
    const int i = static_cast<int>(sample_a(r, 0));
    ASSERT_GE(i, 0);
    ASSERT_LT(i, n);
    EXPECT_EQ(sample_a.row(r), a.row(i));  // both sides of one pair, kept together
    EXPECT_EQ(sample_diff.row(r), diff.row(i));
    seen.push_back(i);
    mean += i / static_cast<double>(cap);
  }
  std::sort(seen.begin(), seen.end());
  EXPECT_EQ(std::unique(seen.begin(), seen.end()), seen.end()) << "a pair sampled twice";
  // Uniform over all 5000 (not the first 500): the mean index within 4 standard errors of (n - 1) / 2.
  EXPECT_NEAR(mean, (n - 1) / 2.0, 4.0 * n / std::sqrt(12.0 * cap));

  EXPECT_THROW(statistics.add(Kind::negative, a, diff.leftCols(d - 1)), std::invalid_argument);
  EXPECT_THROW(statistics.add(Kind::negative, a.topRows(3), diff), std::invalid_argument);
  EXPECT_THROW(LdaHashStatistics(0, 10), std::invalid_argument);
  EXPECT_THROW(LdaHashStatistics(4, 0), std::invalid_argument);
}

TEST(LdaHashTrainer, StreamedStatisticsGiveTheDirectSolutionAndSampledThresholdsSeparateAsWell)
{
  // 40 features with a 4-dimensional class identity, streamed in blocks through the randomised solver
  // (exact_limit below the feature count), against eq. 3.2 written out here in double with the exact solver.
  using Kind = LdaHashStatistics::Kind;
  std::mt19937 rng(5);
  std::normal_distribution<float> g;
  const int n = 6000, d = 40;
  LdaHashTrainer::Matrix pa(n, d), pb(n, d), na(n, d), nb(n, d);
  for (int i = 0; i < n; ++i)
  {
    for (int c = 0; c < d; ++c)
    {
      const float z = g(rng), noise = c < 4 ? 0.1f : 1.0f;
      pa(i, c) = z + noise * g(rng);
      pb(i, c) = z + noise * g(rng);
      na(i, c) = z + noise * g(rng);
      nb(i, c) = g(rng) + noise * g(rng);
    }
  }
  LdaHashTrainer::Parameters p;
  p.bits = 4;
  p.whitening_rank = d;  // the whole space: a truncated degenerate spectrum has no unique top-k subspace
  p.exact_limit = 10;
  const LdaHashTrainer trainer(p);
  const DescriptorModel in_memory = trainer.train(pa, pb, na, nb);  // thresholds on all pairs
  LdaHashStatistics statistics(d, 1000);
  for (int from = 0; from < n; from += 250)
  {
    statistics.add(Kind::positive, pa.middleRows(from, 250), pa.middleRows(from, 250) - pb.middleRows(from, 250));
    statistics.add(Kind::negative, na.middleRows(from, 250), na.middleRows(from, 250) - nb.middleRows(from, 250));
  }
  const DescriptorModel streamed = trainer.train(statistics);
  ASSERT_EQ(streamed.projection.rows(), 4);

  const Eigen::MatrixXd dp = (pa - pb).cast<double>(), dn = (na - nb).cast<double>();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> negative(dn.transpose() * dn / n);
  const Eigen::VectorXd lambda = negative.eigenvalues();  // all d kept
  const Eigen::MatrixXd w = (lambda.array() + p.ridge * lambda.maxCoeff()).rsqrt().matrix().asDiagonal() *
                            negative.eigenvectors().transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> positive(w * (dp.transpose() * dp / n) * w.transpose());
  const Eigen::MatrixXd reference = positive.eigenvalues().head(4).array().rsqrt().matrix().asDiagonal() *
                                    positive.eigenvectors().leftCols(4).transpose() * w;
  // P^T P: blind to each bit's sign and to rotations among bits of equal eigenvalue, which any solver may pick.
  const Eigen::MatrixXd ps = streamed.projection.cast<double>();
  const Eigen::MatrixXd gram = ps.transpose() * ps, gram_reference = reference.transpose() * reference;
  EXPECT_LT((gram - gram_reference).cwiseAbs().maxCoeff(), 1e-3 * gram_reference.cwiseAbs().maxCoeff());

  // The best threshold is a flat optimum (many thresholds separate about as many pairs), so compare what it
  // achieves on all 6000 pairs of each kind: the 1000-pair sample's within 3 points of the full set's (the
  // sample's own error is ~1/sqrt(2000) = 2.2 points).
  auto correct = [&](int b, float t) {
    const Eigen::VectorXf w = in_memory.projection.row(b).transpose();
    const auto ya = ((pa * w).array() > t), yb = ((pb * w).array() > t);
    const auto za = ((na * w).array() > t), zb = ((nb * w).array() > t);
    return ((ya == yb).cast<double>().sum() + (za != zb).cast<double>().sum()) / (2.0 * n);
  };
  for (int b = 0; b < 4; ++b)
  {
    EXPECT_GT(correct(b, streamed.thresholds(b)), correct(b, in_memory.thresholds(b)) - 0.03) << "bit " << b;
    EXPECT_GT(correct(b, in_memory.thresholds(b)), 0.55) << "bit " << b;  // chance: 0.5
  }
  // Too few pairs is an error, not a model.
  LdaHashStatistics few(d, 10);
  few.add(Kind::positive, pa.topRows(7), pa.topRows(7) - pb.topRows(7));
  few.add(Kind::negative, na.topRows(7), na.topRows(7) - nb.topRows(7));
  EXPECT_THROW(trainer.train(few), std::invalid_argument);
}

TEST(LdaHashTrainer, ThresholdsSeparateWhatTheyShould)
{
  // One dimension: matching pairs sit together on either side of 1.0, non-matching pairs straddle it.
  LdaHashTrainer::Parameters p;
  p.threshold_candidates = 1001;
  const int n = 200;
  LdaHashTrainer::Matrix ya(n, 1), yb(n, 1), za(n, 1), zb(n, 1);
  for (int i = 0; i < n; ++i)
  {
    const float side = (i % 2) ? 2.0f : 0.0f;
    ya(i, 0) = side + 0.01f * (i % 7);
    yb(i, 0) = side + 0.02f * (i % 5);
    za(i, 0) = 0.1f * (i % 3);
    zb(i, 0) = 1.9f + 0.05f * (i % 4);
  }
  const float t = LdaHashTrainer(p).thresholds(ya, yb, za, zb)(0);
  EXPECT_GT(t, 0.2f);
  EXPECT_LT(t, 1.9f);
}

class TrainedDescriptor : public testing::Test
{
protected:
  void SetUp() override { descriptor_ = std::make_unique<V1Descriptor>(DescriptorModel::load(modelPath())); }
  std::unique_ptr<V1Descriptor> descriptor_;
};

TEST_F(TrainedDescriptor, ShiftedAndSlightlyRotatedCopiesMatchADifferentPatchDoesNot)
{
  ASSERT_EQ(descriptor_->model().bits(), 128);
  const cv::Mat image = texture(240, 240, 5);
  // Shift by (7, -5) px and rotate by 5 degrees about the centre.
  cv::Mat shifted, rotated;
  const cv::Matx23d shift(1, 0, 7, 0, 1, -5);
  cv::warpAffine(image, shifted, shift, image.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  const cv::Mat rot = cv::getRotationMatrix2D(cv::Point2f(120, 120), 5.0, 1.0);
  cv::warpAffine(image, rotated, rot, image.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  V1FeaturePyramid p0(descriptor_->pyramidParameters()), p1 = p0, p2 = p0;
  p0.build(image);
  p1.build(shifted);
  p2.build(rotated);
  int matched_shift = 0, matched_rot = 0, rejected_other = 0, total = 0;
  for (float lambda : {5.66f, 8.f, 11.31f})
    for (int i = 0; i < 5; ++i)
    {
      const cv::Point2f p(90.f + 15 * i, 100.f + 9 * i);
      const cv::Point2f ps(p.x + 7, p.y - 5);
      const cv::Point2f pr(
          static_cast<float>(rot.at<double>(0, 0) * p.x + rot.at<double>(0, 1) * p.y + rot.at<double>(0, 2)),
          static_cast<float>(rot.at<double>(1, 0) * p.x + rot.at<double>(1, 1) * p.y + rot.at<double>(1, 2)));
      const auto c0 = descriptor_->compute(p0, {at(p.x, p.y, lambda)});
      const auto c1 = descriptor_->compute(p1, {at(ps.x, ps.y, lambda)});
      const auto c2 = descriptor_->compute(p2, {at(pr.x, pr.y, lambda)});
      // A different place of the same texture, 50 px away.
      const auto c3 = descriptor_->compute(p0, {at(p.x + 50, p.y - 40, lambda)});
      matched_shift += hammingDistanceReference(c0.code(0), c1.code(0), 2) <= 24;
      matched_rot += hammingDistanceReference(c0.code(0), c2.code(0), 2) <= 24;
      rejected_other += hammingDistanceReference(c0.code(0), c3.code(0), 2) > 24;
      ++total;
    }
  EXPECT_GE(matched_shift, total * 9 / 10);
  EXPECT_GE(matched_rot, total * 7 / 10);
  EXPECT_GE(rejected_other, total * 9 / 10);
}

TEST_F(TrainedDescriptor, CodeIsInvariantToBrightnessAndContrast)
{
  const cv::Mat image = texture(200, 200, 6);
  V1FeaturePyramid a(descriptor_->pyramidParameters()), b = a;
  a.build(image);
  b.build(image * 0.6 + 0.25);
  std::vector<biovision_v1::Keypoint> kps;
  for (int i = 0; i < 20; ++i)
    kps.push_back(at(40.f + 6 * i, 60.f + 4 * i, i % 2 ? 5.66f : 8.f));
  const auto ca = descriptor_->compute(a, kps), cb = descriptor_->compute(b, kps);
  for (size_t i = 0; i < kps.size(); ++i)
    EXPECT_LE(hammingDistanceReference(ca.code(i), cb.code(i), 2), 2) << "keypoint " << i;
}

TEST_F(TrainedDescriptor, ProvenanceRecordsTheTrainingCommand)
{
  EXPECT_NE(descriptor_->model().provenance.find("train_descriptor"), std::string::npos);
}

TEST(PackedProjection, EveryPathEqualsADoublePrecisionReference)
{
  std::mt19937 rng(8);
  std::normal_distribution<float> g;
  // Odd sizes: rows not a multiple of the row group (6) or the task (48), more than one input chunk (256),
  // outputs below, at and above the 64-column padding.
  for (size_t outputs : {size_t(13), size_t(64), size_t(128), size_t(130)})
    for (size_t rows : {size_t(1), size_t(5), size_t(7), size_t(53)})
    {
      const size_t inputs = 600;
      std::vector<float> x(rows * inputs), p(outputs * inputs);
      for (auto& v : x)
        v = g(rng);
      for (auto& v : p)
        v = g(rng);
      const PackedProjection projection(p.data(), outputs, inputs);
      for (ProjectionPath path : availableProjectionPaths())
      {
        std::vector<float> y(rows * outputs + 1, -7.f);  // one guard value past the end
        projection.project(x.data(), rows, y.data(), path);
        EXPECT_EQ(y.back(), -7.f) << toString(path) << " wrote past the end";
        double worst = 0.0;
        for (size_t i = 0; i < rows; ++i)
          for (size_t b = 0; b < outputs; ++b)
          {
            double ref = 0.0;
            for (size_t k = 0; k < inputs; ++k)
              ref += double(x[i * inputs + k]) * p[b * inputs + k];
            worst = std::max(worst, std::abs(y[i * outputs + b] - ref));
          }
        EXPECT_LT(worst, 1e-3 * std::sqrt(double(inputs)))
            << toString(path) << ", " << rows << " rows x " << outputs << " outputs";
      }
    }
  EXPECT_EQ(availableProjectionPaths().front(), ProjectionPath::Generic);
  EXPECT_EQ(bestProjectionPath(), availableProjectionPaths().back());
  EXPECT_THROW(PackedProjection(nullptr, 0, 10), std::invalid_argument);
}

TEST_F(TrainedDescriptor, ProjectionsAgreeOnEveryPath)
{
  const cv::Mat x = [&] {
    cv::Mat m(37, static_cast<int>(descriptor_->model().projection.cols()), CV_32F);
    cv::randn(m, 0.0, 1.0);
    return m;
  }();
  const cv::Mat reference = descriptor_->project(x, ProjectionPath::Generic);
  const double scale = cv::norm(reference, cv::NORM_INF);
  ASSERT_GT(scale, 0.0);
  for (ProjectionPath path : availableProjectionPaths())  // float sums in another order: rounding only
    EXPECT_LT(cv::norm(descriptor_->project(x, path), reference, cv::NORM_INF), 1e-5 * scale) << toString(path);
}
