// Unit tests of the ROS-free saliency core on synthetic scenes with known answers.
#include <cmath>
#include <tuple>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "biovision_saliency/blob_filter_bank.hpp"
#include "biovision_saliency/inhibition_of_return.hpp"
#include "biovision_saliency/saliency_pipeline.hpp"

using namespace biovision_saliency;

namespace
{
const cv::Size kFull(640, 480);

cv::Mat greyScene()
{
  return cv::Mat(kFull, CV_8UC3, cv::Scalar(128, 128, 128));
}

// A mildly textured grey background (real scenes are never flat), seeded.
cv::Mat texturedScene(unsigned seed)
{
  cv::RNG rng(seed);
  cv::Mat small(kFull.height / 16, kFull.width / 16, CV_8UC3);
  rng.fill(small, cv::RNG::UNIFORM, 110, 146);
  cv::Mat img;
  cv::resize(small, img, kFull, 0, 0, cv::INTER_CUBIC);
  return img;
}

bool contains(const cv::Rect& box, cv::Point p)
{
  return box.contains(p);
}

HeadDirection head(double pan = 0.0)
{
  HeadDirection h;
  h.pan = pan;
  return h;  // focal from the default field of view
}
}  // namespace

// Brute-force reference of the blob filter: two full-resolution Gaussian blurs per scale, rectified DoG.
static void referenceBlobs(const cv::Mat& map, const std::vector<double>& sigmas, cv::Mat& on, cv::Mat& off)
{
  on = cv::Mat::zeros(map.size(), CV_32F);
  off = cv::Mat::zeros(map.size(), CV_32F);
  for (double s : sigmas)
  {
    cv::Mat c, r;
    cv::GaussianBlur(map, c, cv::Size(), s, s, cv::BORDER_REPLICATE);
    cv::GaussianBlur(map, r, cv::Size(), 2 * s, 2 * s, cv::BORDER_REPLICATE);
    on += cv::max(c - r, 0.0);
    off += cv::max(r - c, 0.0);
  }
}

TEST(BlobFilterBank, SharedBlursEqualTheReferenceAndThePyramidStaysClose)
{
  cv::RNG rng(7);
  cv::Mat coarse(15, 20, CV_32F), map;
  rng.fill(coarse, cv::RNG::UNIFORM, -1.0, 1.0);
  cv::resize(coarse, map, cv::Size(160, 120), 0, 0, cv::INTER_CUBIC);
  cv::circle(map, cv::Point(50, 60), 8, cv::Scalar(2.0), -1);
  const std::vector<double> sigmas{1.25, 2.5, 5.0};
  cv::Mat ref_on, ref_off, on, off;
  referenceBlobs(map, sigmas, ref_on, ref_off);
  // Exact mode: the surround of one scale reused as the next one's centre changes nothing.
  BlobFilterBank(sigmas, 0.0).positiveAndNegative(map, on, off);
  EXPECT_EQ(cv::norm(on, ref_on, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(off, ref_off, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(BlobFilterBank(sigmas, 0.0).positive(map), ref_on, cv::NORM_INF), 0.0);
  // Pyramid mode (the default 2.5 px): the wide blurs on coarser levels; close to the reference,
  // and the blob's response stays where it is.
  BlobFilterBank(sigmas, 2.5).positiveAndNegative(map, on, off);
  double ref_max = 0;
  cv::minMaxLoc(ref_on, nullptr, &ref_max);
  EXPECT_LT(cv::norm(on, ref_on, cv::NORM_L2) / cv::norm(ref_on, cv::NORM_L2), 0.1);
  EXPECT_LT(cv::norm(off, ref_off, cv::NORM_L2) / cv::norm(ref_off, cv::NORM_L2), 0.1);
  EXPECT_LT(cv::norm(on, ref_on, cv::NORM_INF), 0.1 * ref_max);
  cv::Point peak, ref_peak;
  cv::minMaxLoc(on, nullptr, nullptr, nullptr, &peak);
  cv::minMaxLoc(ref_on, nullptr, nullptr, nullptr, &ref_peak);
  EXPECT_LE(cv::norm(peak - ref_peak), 2.0);
}

TEST(SaliencyPipeline, RedDiscOnGreyIsTheTopRegion)
{
  cv::Mat img = greyScene();
  cv::circle(img, {450, 200}, 30, cv::Scalar(0, 0, 220), cv::FILLED);
  cv::circle(img, {150, 350}, 30, cv::Scalar(110, 110, 110), cv::FILLED);  // faint grey disc
  SaliencyPipeline pipeline{SaliencyParameters()};
  const SaliencyResult r = pipeline.process(img, cv::Mat(), head(), 0.0);
  ASSERT_FALSE(r.regions.empty());
  EXPECT_TRUE(contains(r.regions[0].box, {450, 200})) << r.regions[0].box;
  EXPECT_NEAR(r.regions[0].peak, 1.0, 1e-6);
  // Box grown by the margin around the disc, in full-resolution pixels.
  EXPECT_LE(r.regions[0].box.x, 450 - 30 - 10);
  EXPECT_GE(r.regions[0].box.br().x, 450 + 30 + 10);
}

TEST(SaliencyPrior, CentreAndHorizonPeakWhereTheySay)
{
  SaliencyParameters p;
  HeadDirection h;
  h.focal = 500.0;
  h.principal = cv::Point2d(319.5, 239.5);
  const cv::Size working(160, 120);  // scale 4
  auto peakOf = [&](PriorMode mode, double tilt) {
    p.prior = mode;
    h.tilt = tilt;
    const cv::Mat prior = SaliencyPipeline(p).priorMap(working, 4.0, h);
    cv::Point at;
    double lo = 0, hi = 0;
    cv::minMaxLoc(prior, &lo, &hi, nullptr, &at);
    return std::make_tuple(at, lo, hi, prior);
  };
  const auto [none_at, none_lo, none_hi, none_map] = peakOf(PriorMode::none, 0.0);
  EXPECT_EQ(none_lo, 1.0);
  EXPECT_EQ(none_hi, 1.0);
  const auto [centre_at, centre_lo, centre_hi, centre_map] = peakOf(PriorMode::centre, 0.3);
  EXPECT_NEAR(centre_at.x, 79.5, 1.0);  // the tilt does not move the centre prior
  EXPECT_NEAR(centre_at.y, 59.5, 1.0);
  EXPECT_LT(centre_lo, 0.5);
  // Horizon: tilting down by 0.2 rad raises the horizon by f tan(0.2) = 101 px (25 working px).
  const auto [level_at, level_lo, level_hi, level_map] = peakOf(PriorMode::horizon, 0.0);
  const auto [down_at, down_lo, down_hi, down_map] = peakOf(PriorMode::horizon, 0.2);
  EXPECT_NEAR(level_at.y, 59.5, 1.0);
  EXPECT_NEAR(down_at.y, (239.5 - 500.0 * std::tan(0.2)) / 4.0 - 0.5, 1.0);
  // A band: constant along a row.
  EXPECT_FLOAT_EQ(level_map.at<float>(30, 0), level_map.at<float>(30, 159));
}

TEST(SaliencyPrior, HorizonPriorPrefersTheDiscAtEyeLevel)
{
  // Two identical red discs, one on the horizon row, one near the top: only the prior tells them apart.
  cv::Mat img = greyScene();
  cv::circle(img, {200, 240}, 30, cv::Scalar(0, 0, 220), cv::FILLED);
  cv::circle(img, {440, 60}, 30, cv::Scalar(0, 0, 220), cv::FILLED);
  SaliencyParameters p;
  p.prior = PriorMode::horizon;
  p.prior_weight = 0.5;
  SaliencyPipeline with(p);
  const SaliencyResult r = with.process(img, cv::Mat(), head(), 0.0);
  ASSERT_FALSE(r.regions.empty());
  EXPECT_TRUE(contains(r.regions[0].box, {200, 240})) << r.regions[0].box;
  p.prior = PriorMode::none;
  SaliencyPipeline without(p);
  const SaliencyResult n = without.process(img, cv::Mat(), head(), 0.0);
  ASSERT_GE(n.regions.size(), 2u);
  EXPECT_NEAR(n.regions[0].peak, n.regions[1].peak, 0.05);  // without the prior: a tie
}

TEST(SaliencyPipeline, BlankAndSaturatedImagesGiveNoRegion)
{
  SaliencyPipeline pipeline{SaliencyParameters()};
  for (int v : {0, 128, 255})
  {
    const cv::Mat img(kFull, CV_8UC3, cv::Scalar::all(v));
    const SaliencyResult r = pipeline.process(img, cv::Mat(), head(), 0.0);
    EXPECT_TRUE(r.regions.empty()) << "value " << v;
    EXPECT_TRUE(cv::checkRange(r.map));
  }
}

TEST(SaliencyPipeline, NearBoxWinsOverAFarOne)
{
  // One colour everywhere, so that disparity alone decides: a near box (disparity 40) and a far box
  // (disparity 8) on a background at 4.
  const cv::Mat img = greyScene();
  cv::Mat d(kFull, CV_32F, cv::Scalar(4.f));
  d(cv::Rect(80, 150, 120, 120)).setTo(8.f);
  d(cv::Rect(420, 150, 120, 120)).setTo(40.f);
  d(cv::Rect(0, 0, 40, 40)).setTo(-1.f);  // invalid pixels
  d.at<float>(300, 300) = NAN;
  SaliencyPipeline pipeline{SaliencyParameters()};
  const SaliencyResult r = pipeline.process(img, d, head(), 0.0);
  ASSERT_FALSE(r.regions.empty());
  EXPECT_TRUE(contains(r.regions[0].box, {480, 210})) << r.regions[0].box;
  for (const auto& region : r.regions)
    EXPECT_FALSE(contains(region.box, {140, 210}) && region.priority > 0.9f * r.regions[0].priority);
  // Disparity given at half resolution works the same.
  cv::Mat half;
  cv::resize(d, half, cv::Size(), 0.5, 0.5, cv::INTER_NEAREST);
  half *= 0.5;
  pipeline.reset();
  const SaliencyResult r2 = pipeline.process(img, half, head(), 0.0);
  ASSERT_FALSE(r2.regions.empty());
  EXPECT_TRUE(contains(r2.regions[0].box, {480, 210}));
}

TEST(SaliencyPipeline, MovingPatchIsSalientGlobalShiftIsNot)
{
  const cv::Mat base = texturedScene(7);
  cv::Mat patch_src = texturedScene(8)(cv::Rect(0, 0, 100, 100)).clone();
  SaliencyParameters p;
  p.colour_weight = 0.0;  // look at motion alone
  SaliencyPipeline pipeline(p);
  // A patch moving 12 px/frame to the right over a static background.
  cv::Mat f0 = base.clone(), f1 = base.clone();
  patch_src.copyTo(f0(cv::Rect(300, 200, 100, 100)));
  patch_src.copyTo(f1(cv::Rect(312, 200, 100, 100)));
  pipeline.process(f0, cv::Mat(), head(), 0.0);
  const SaliencyResult moving = pipeline.process(f1, cv::Mat(), head(), 0.1);
  ASSERT_FALSE(moving.regions.empty());
  EXPECT_TRUE(contains(moving.regions[0].box, {360, 250})) << moving.regions[0].box;
  double mx = 0;
  cv::minMaxLoc(moving.motion, nullptr, &mx);
  EXPECT_GT(mx, 0.5);

  // The whole image shifted by 12 px (ego-motion): compensated, no salient motion anywhere.
  pipeline.reset();
  const cv::Mat wide = texturedScene(9);
  cv::Mat g0, g1;
  cv::copyMakeBorder(wide, g0, 0, 0, 16, 16, cv::BORDER_REFLECT);
  const cv::Mat s0 = g0(cv::Rect(16, 0, kFull.width, kFull.height)).clone();
  const cv::Mat s1 = g0(cv::Rect(4, 0, kFull.width, kFull.height)).clone();
  pipeline.process(s0, cv::Mat(), head(), 0.0);
  const SaliencyResult shifted = pipeline.process(s1, cv::Mat(), head(), 0.1);
  double shifted_max = 0;
  cv::minMaxLoc(shifted.motion, nullptr, &shifted_max);
  EXPECT_LT(shifted_max, 0.5) << "global shift left motion saliency behind";
  EXPECT_NEAR(shifted.global_flow.x, 12.0 * p.working_width / kFull.width, 0.6);
  EXPECT_TRUE(shifted.regions.empty());
}

TEST(SaliencyPipeline, HeadPanPredictionExplainsTheImageShift)
{
  // The head pans left between frames and the image shifts right by what the pan predicts: the
  // prediction absorbs it and the compensated motion channel stays quiet.
  SaliencyParameters p;
  p.colour_weight = 0.0;
  SaliencyPipeline pipeline(p);
  const cv::Mat wide = texturedScene(11);
  cv::Mat g;
  cv::copyMakeBorder(wide, g, 0, 0, 16, 16, cv::BORDER_REFLECT);
  const double f = 0.5 * kFull.width / std::tan(0.5 * p.horizontal_fov);
  const int shift = 8;  // full-resolution px
  const cv::Mat s0 = g(cv::Rect(16, 0, kFull.width, kFull.height)).clone();
  const cv::Mat s1 = g(cv::Rect(16 - shift, 0, kFull.width, kFull.height)).clone();  // content moves right
  pipeline.process(s0, cv::Mat(), head(0.0), 0.0);
  const SaliencyResult r = pipeline.process(s1, cv::Mat(), head(shift / f), 0.1);
  double mx = 0;
  cv::minMaxLoc(r.motion, nullptr, &mx);
  EXPECT_LT(mx, 0.5);
  EXPECT_NEAR(r.global_flow.x, shift * double(p.working_width) / kFull.width, 0.6);
}

TEST(SaliencyPipeline, FirstFrameHasNoMotionChannel)
{
  SaliencyPipeline pipeline{SaliencyParameters()};
  const SaliencyResult r = pipeline.process(texturedScene(1), cv::Mat(), head(), 0.0);
  EXPECT_TRUE(r.motion.empty());
  EXPECT_FALSE(r.colour.empty());
}

TEST(InhibitionOfReturn, SecondRegionComesFirstThenTheFirstIsReleased)
{
  cv::Mat img = greyScene();
  cv::circle(img, {450, 200}, 30, cv::Scalar(0, 0, 230), cv::FILLED);    // strongest
  cv::circle(img, {180, 300}, 30, cv::Scalar(200, 90, 40), cv::FILLED);  // blue, peak ~0.7 of the red
  SaliencyParameters p;
  p.threshold = 0.5;
  p.attend_period = 0.5;
  p.ior_decay_time = 2.0;
  SaliencyPipeline pipeline(p);
  const auto first = pipeline.process(img, cv::Mat(), head(), 0.0);
  ASSERT_GE(first.regions.size(), 2u);
  ASSERT_TRUE(contains(first.regions[0].box, {450, 200}));
  // Next frame: the attended red disc is inhibited, the blue one comes first.
  const auto next = pipeline.process(img, cv::Mat(), head(), 0.1);
  ASSERT_GE(next.regions.size(), 2u);
  EXPECT_TRUE(contains(next.regions[0].box, {180, 300})) << next.regions[0].box;
  EXPECT_GT(next.regions[1].inhibition, 0.9f);
  // After the decay time both memories have run out: the red disc is first again.
  const auto later = pipeline.process(img, cv::Mat(), head(), 10.0);
  ASSERT_FALSE(later.regions.empty());
  EXPECT_TRUE(contains(later.regions[0].box, {450, 200}));
  EXPECT_FLOAT_EQ(later.regions[0].inhibition, 0.f);
}

TEST(InhibitionOfReturn, FollowsAPanRotation)
{
  // Attend an object at the image centre with the head at pan 0; turn the head 10 deg left: the object
  // now appears right of centre, and is still inhibited; an object now at the centre is not.
  InhibitionOfReturn ior(0.1, 3.0);
  HeadDirection h0;
  h0.focal = 500;
  h0.principal = {320, 240};
  const cv::Point2d attended = h0.directionOf({320, 240});
  ior.attend(attended, 0.0);
  HeadDirection h1 = h0;
  h1.pan = 10 * M_PI / 180;
  const double u = 320 + 500 * std::tan(10 * M_PI / 180);  // where the same object is now
  EXPECT_GT(ior.inhibition(h1.directionOf({static_cast<float>(u), 240}), 0.5), 0.8);
  EXPECT_EQ(ior.inhibition(h1.directionOf({320, 240}), 0.5), 0.0);
  // Linear decay and release.
  EXPECT_NEAR(ior.inhibition(attended, 1.5), 0.5, 1e-9);
  EXPECT_EQ(ior.inhibition(attended, 3.0), 0.0);
  ior.attend({1.0, 0.0}, 3.5);
  EXPECT_EQ(ior.size(3.5), 1u);
}

TEST(SaliencyPipeline, RejectsBadInputClearly)
{
  SaliencyPipeline pipeline{SaliencyParameters()};
  EXPECT_THROW(pipeline.process(cv::Mat(), cv::Mat(), head(), 0), std::invalid_argument);
  EXPECT_THROW(pipeline.process(cv::Mat(100, 100, CV_16UC3), cv::Mat(), head(), 0), std::invalid_argument);
  EXPECT_THROW(pipeline.process(cv::Mat(8, 8, CV_8UC3), cv::Mat(), head(), 0), std::invalid_argument);
  // Disparity of another aspect (stale or mismatched stereo output).
  EXPECT_THROW(pipeline.process(greyScene(), cv::Mat(100, 100, CV_32F, cv::Scalar(1)), head(), 0),
               std::invalid_argument);
  EXPECT_THROW(pipeline.process(greyScene(), cv::Mat(480, 640, CV_16U), head(), 0), std::invalid_argument);
  SaliencyParameters bad;
  bad.threshold = 1.5;
  EXPECT_THROW(SaliencyPipeline{bad}, std::invalid_argument);
  // Grey input is accepted.
  cv::Mat grey(kFull, CV_8U, cv::Scalar(100));
  EXPECT_NO_THROW(pipeline.process(grey, cv::Mat(), head(), 0));
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
