// Unit tests of the ROS-free V1 core on synthetic images with known answers.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "biovision_v1/direct_gabor_bank.hpp"
#include "biovision_v1/end_stopped_cells.hpp"
#include "biovision_v1/fourier_transform.hpp"
#include "biovision_v1/gabor_kernel.hpp"
#include "biovision_v1/input_image.hpp"
#include "biovision_v1/line_edge_detector.hpp"
#include "biovision_v1/simple_cell_bank.hpp"
#include "biovision_v1/v1_pipeline.hpp"

using namespace biovision_v1;

namespace
{
constexpr float kBackground = 0.2f, kForeground = 0.8f;

cv::Mat canvas(int w = 160, int h = 120)
{
  return cv::Mat(h, w, CV_32F, cv::Scalar(kBackground));
}

// Textured image for comparing the fast bank with the direct convolution.
cv::Mat texture(int w, int h, unsigned seed)
{
  cv::RNG rng(seed);
  cv::Mat noise(h / 4, w / 4, CV_32F);
  rng.fill(noise, cv::RNG::UNIFORM, 0.0, 1.0);
  cv::Mat img;
  cv::resize(noise, img, cv::Size(w, h), 0, 0, cv::INTER_CUBIC);
  cv::line(img, {w / 5, h / 3}, {4 * w / 5, 2 * h / 3}, cv::Scalar(1.0), 2);
  return img;
}

double distanceToNearest(const std::vector<Keypoint>& kps, cv::Point2f p, double max_wavelength = 1e9)
{
  double best = std::numeric_limits<double>::infinity();
  for (const auto& k : kps)
    if (k.wavelength <= max_wavelength)
      best = std::min(best, static_cast<double>(std::hypot(k.x - p.x, k.y - p.y)));
  return best;
}

V1Pipeline::Parameters singleScale(double wavelength)
{
  V1Pipeline::Parameters p;
  p.gabor.wavelengths = {wavelength};
  return p;
}
}  // namespace

TEST(GaborKernel, EvenIsDcFreeOddIsAntisymmetric)
{
  GaborParameters p;
  for (double lambda : {4.0, 8.0, 16.0})
    for (int i = 0; i < p.orientations; ++i)
    {
      GaborKernel k(lambda, p.theta(i), p);
      EXPECT_NEAR(cv::sum(k.even())[0], 0.0, 1e-5);
      cv::Mat flipped;
      cv::flip(k.odd(), flipped, -1);
      EXPECT_LT(cv::norm(k.odd() + flipped, cv::NORM_INF), 1e-6);
      EXPECT_EQ(k.even().rows, 2 * p.radius(lambda) + 1);
    }
}

TEST(GaborParameters, RejectsBadValues)
{
  const GaborParameters good;
  EXPECT_NO_THROW(good.validate());
  GaborParameters p = good;
  p.orientations = 3;
  EXPECT_THROW(p.validate(), std::invalid_argument);
  p = good;
  p.wavelengths = {8, 4};
  EXPECT_THROW(p.validate(), std::invalid_argument);
  p = good;
  p.wavelengths.clear();
  EXPECT_THROW(p.validate(), std::invalid_argument);
}

// FourierTransform against cv::dft (the reference it replaces), relative to the spectrum's peak.
double spectrumError(const cv::Mat& ours, const cv::Mat& ref)
{
  double peak = 0.0;
  cv::minMaxLoc(cv::abs(ref.reshape(1)), nullptr, &peak);
  return cv::norm(ours, ref, cv::NORM_INF) / std::max(peak, 1e-12);
}

TEST(FourierTransform, EqualsOpenCvsDftOnRealAndComplexImagesOfOddAndEvenSizes)
{
  for (const cv::Size size : {cv::Size(1, 1), cv::Size(7, 5), cv::Size(13, 1), cv::Size(1, 9), cv::Size(64, 48),
                              cv::Size(75, 81), cv::Size(173, 131)})
  {
    cv::Mat real(size, CV_32F), complex(size, CV_32FC2), ref, ours;
    cv::randu(real, -1.0, 1.0);
    cv::randu(complex, -1.0, 1.0);
    cv::dft(real, ref, cv::DFT_COMPLEX_OUTPUT);
    FourierTransform::forward(real, ours);
    ASSERT_EQ(ours.size(), size);
    ASSERT_EQ(ours.type(), CV_32FC2);
    EXPECT_LT(spectrumError(ours, ref), 1e-5) << "real " << size;
    cv::dft(complex, ref, cv::DFT_COMPLEX_OUTPUT);
    FourierTransform::forward(complex, ours);
    EXPECT_LT(spectrumError(ours, ref), 1e-5) << "complex " << size;
    cv::idft(complex, ref, cv::DFT_COMPLEX_OUTPUT);  // unscaled, like inverseUnscaled
    FourierTransform::inverseUnscaled(complex, ours);
    EXPECT_LT(spectrumError(ours, ref), 1e-5) << "inverse " << size;
  }
}

TEST(FourierTransform, InPlaceAndOnARegionOfInterest)
{
  cv::Mat big(90, 120, CV_32FC2);
  cv::randu(big, -1.0, 1.0);
  const cv::Mat roi = big(cv::Rect(3, 5, 61, 47));  // neither continuous nor aligned
  cv::Mat ref, ours;
  cv::dft(roi, ref, cv::DFT_COMPLEX_OUTPUT);
  FourierTransform::forward(roi, ours);
  EXPECT_LT(spectrumError(ours, ref), 1e-5);
  // In place: the spectrum replaces the image; the inverse gives N times the image back.
  cv::Mat x = roi.clone(), original = x.clone();
  const uchar* buffer = x.data;
  FourierTransform::forward(x, x);
  EXPECT_EQ(x.data, buffer);
  EXPECT_LT(spectrumError(x, ref), 1e-5);
  FourierTransform::inverseUnscaled(x, x);
  EXPECT_LT(cv::norm(x / double(x.total()), original, cv::NORM_INF), 1e-5);
}

TEST(FourierTransform, MultipliesSpectraExactlyAsOpenCvsMulSpectrums)
{
  cv::RNG rng(17);
  for (const cv::Size size : {cv::Size(1, 1), cv::Size(7, 3), cv::Size(150, 128), cv::Size(61, 47)})
  {
    cv::Mat a(size, CV_32FC2), b(size, CV_32FC2), ref, ours;
    rng.fill(a, cv::RNG::UNIFORM, -1e3, 1e3);
    rng.fill(b, cv::RNG::UNIFORM, -1.0, 1.0);
    cv::mulSpectrums(a, b, ref, 0);
    FourierTransform::multiplySpectra(a, b, ours);
    EXPECT_EQ(cv::norm(ours, ref, cv::NORM_INF), 0.0) << size;  // bit for bit: the same roundings
    // In place over either operand, and on a region of interest (not continuous).
    cv::Mat a2 = a.clone();
    FourierTransform::multiplySpectra(a2, b, a2);
    EXPECT_EQ(cv::norm(a2, ref, cv::NORM_INF), 0.0);
  }
  cv::Mat big(40, 50, CV_32FC2), ref, ours;
  rng.fill(big, cv::RNG::UNIFORM, -1.0, 1.0);
  const cv::Mat roi = big(cv::Rect(3, 2, 31, 17));
  cv::mulSpectrums(roi, roi, ref, 0);
  FourierTransform::multiplySpectra(roi, roi, ours);
  EXPECT_EQ(cv::norm(ours, ref, cv::NORM_INF), 0.0);
  cv::Mat wrong(17, 31, CV_32FC1);
  EXPECT_THROW(FourierTransform::multiplySpectra(roi, wrong, ours), std::invalid_argument);
  EXPECT_THROW(FourierTransform::multiplySpectra(roi, big, ours), std::invalid_argument);
}

TEST(FourierTransform, ReusesAnUnsharedSpectrumAndNeverWritesIntoAViewHeldElsewhere)
{
  cv::Mat image(40, 50, CV_32FC1), other(40, 50, CV_32FC1);
  cv::randu(image, 0.0, 1.0);
  cv::randu(other, 0.0, 1.0);
  cv::Mat ref;
  cv::dft(image, ref, cv::DFT_COMPLEX_OUTPUT);
  cv::Mat spectrum;
  FourierTransform::forward(other, spectrum);
  const uchar* buffer = spectrum.data;
  FourierTransform::forward(image, spectrum);  // the only holder of its buffer: written again
  EXPECT_EQ(spectrum.data, buffer);
  EXPECT_LT(spectrumError(spectrum, ref), 1e-5);
  const cv::Mat kept = spectrum;  // a view the caller still reads
  const cv::Mat kept_copy = kept.clone();
  FourierTransform::forward(other, spectrum);
  EXPECT_NE(spectrum.data, kept.data);
  EXPECT_EQ(cv::norm(kept, kept_copy, cv::NORM_INF), 0.0);
}

TEST(SimpleCellBank, BatchOfImagesEqualsOneCallPerImageBitForBit)
{
  GaborParameters p;
  p.min_grid_wavelength = 0.0;
  p.wavelengths = {4.0, 8.0};             // two scales: the per-image, per-scale buffers and the shared spectrum source
  FourierTransform::setMeasurePolicy(0);  // estimated plans throughout: a measured one may round differently
  const cv::Mat a = texture(70, 61, 5), b = texture(70, 61, 6);
  SimpleCellBank single(p), batch(p);
  const auto ref_a = single.computeOddPairs(a);
  const auto ref_b = single.computeOddPairs(b);
  for (int round = 0; round < 2; ++round)  // the second round reuses the batch's buffers
  {
    const auto both = batch.computeOddPairsBatch({a, b});
    ASSERT_EQ(both.size(), 2u);
    for (size_t s = 0; s < ref_a.size(); ++s)
      for (size_t k = 0; k < ref_a[s].size(); ++k)
      {
        EXPECT_EQ(cv::norm(both[0][s][k], ref_a[s][k], cv::NORM_INF), 0.0) << s << " " << k;
        EXPECT_EQ(cv::norm(both[1][s][k], ref_b[s][k], cv::NORM_INF), 0.0) << s << " " << k;
        EXPECT_NE(both[0][s][k].data, both[1][s][k].data);
      }
  }
  // A single image through the same bank afterwards: the batch's larger buffers do not confuse it.
  EXPECT_EQ(cv::norm(batch.computeOddPairs(b)[1][3], ref_b[1][3], cv::NORM_INF), 0.0);
  EXPECT_THROW(batch.computeOddPairsBatch({}), std::invalid_argument);
  EXPECT_THROW(batch.computeOddPairsBatch({a, texture(70, 60, 6)}), std::invalid_argument);
  cv::Mat a8;
  a.convertTo(a8, CV_8U, 255.0);
  EXPECT_THROW(batch.computeOddPairsBatch({a, a8}), std::invalid_argument);
  const int dims3[3] = {2, 3, 4};
  EXPECT_THROW(batch.computeOddPairsBatch({cv::Mat(3, dims3, CV_32F, cv::Scalar(0))}), std::invalid_argument);
  FourierTransform::setMeasurePolicy(FourierTransform::kMeasureAfter);
}

TEST(SimpleCellBank, RepeatedCallsLeaveEarlierResultsHeldByTheCallerIntact)
{
  GaborParameters p;
  p.min_grid_wavelength = 0.0;
  SimpleCellBank bank(p);
  const cv::Mat a = texture(70, 60, 5), b = texture(70, 60, 6);
  const auto first = bank.computeOddPairs(a);
  const cv::Mat first_copy = first[0][1].clone();
  const auto ref_b = bank.computeOddPairs(b);  // same size: the bank's buffers are reused where free
  EXPECT_EQ(cv::norm(first[0][1], first_copy, cv::NORM_INF), 0.0);
  SimpleCellBank fresh(p);
  const auto again = fresh.computeOddPairs(b);
  EXPECT_LT(cv::norm(ref_b[0][1], again[0][1], cv::NORM_INF), 1e-5);
  // The same for the quadrature responses: a held result stays, a released one's buffers are reused.
  const auto held = bank.compute(a);
  const cv::Mat held_copy = held[0].even[2].clone();
  const uchar* held_data = held[0].even[2].data;
  const auto next = bank.compute(b);
  EXPECT_EQ(cv::norm(held[0].even[2], held_copy, cv::NORM_INF), 0.0);
  EXPECT_NE(next[0].even[2].data, held_data);
  const uchar* next_data = next[0].odd[5].data;
  const auto ref = fresh.compute(a);
  {
    const auto dropped = bank.compute(b);  // `next` still holds its buffers: new ones
    EXPECT_NE(dropped[0].odd[5].data, next_data);
  }
  const auto reused = bank.compute(a);  // `dropped` let go: its buffers are written again
  EXPECT_LT(cv::norm(reused[0].odd[5], ref[0].odd[5], cv::NORM_INF), 1e-5);
}

TEST(FourierTransform, MakesOnePlanPerSizeAndRefusesOtherTypes)
{
  cv::Mat a(37, 41, CV_32F, cv::Scalar(1)), out;
  FourierTransform::forward(a, out);
  const long made = FourierTransform::plansMade();
  FourierTransform::forward(a, out);
  FourierTransform::forward(a + 1, out);
  EXPECT_EQ(FourierTransform::plansMade(), made);
  EXPECT_NEAR(out.at<cv::Vec2f>(0, 0)[0], 2.0 * 37 * 41, 1e-2);  // DC of a constant 2
  EXPECT_THROW(FourierTransform::forward(cv::Mat(), out), std::invalid_argument);
  EXPECT_THROW(FourierTransform::forward(cv::Mat(4, 4, CV_8U), out), std::invalid_argument);
  EXPECT_THROW(FourierTransform::inverseUnscaled(cv::Mat(4, 4, CV_32F), out), std::invalid_argument);
  EXPECT_NE(FourierTransform::backend().find("fftw"), std::string::npos);
}

TEST(FourierTransform, MeasuresThePlanOfASizeRunOftenAndStaysExact)
{
  // A size no other test uses: estimated for its first kMeasureAfter - 1 runs, then measured once (the
  // measured plan is kept: later runs make none), and every run still equals cv::dft.
  FourierTransform::setMeasurePolicy(FourierTransform::kMeasureAfter);  // the budget, whatever ran before
  cv::Mat complex(53, 61, CV_32FC2), ref, out;
  cv::randu(complex, -1.0, 1.0);
  cv::dft(complex, ref, cv::DFT_INVERSE);
  const long measured = FourierTransform::plansMeasured();
  for (int i = 1; i < FourierTransform::kMeasureAfter; ++i)
    FourierTransform::inverseUnscaled(complex, out);
  EXPECT_EQ(FourierTransform::plansMeasured(), measured);
  EXPECT_LT(spectrumError(out, ref), 1e-5);
  FourierTransform::inverseUnscaled(complex, out);
  EXPECT_EQ(FourierTransform::plansMeasured(), measured + 1);
  const long made = FourierTransform::plansMade();
  for (int i = 0; i < 3; ++i)
    FourierTransform::inverseUnscaled(complex, out);
  EXPECT_EQ(FourierTransform::plansMade(), made);
  EXPECT_EQ(FourierTransform::plansMeasured(), measured + 1);
  EXPECT_LT(spectrumError(out, ref), 1e-5);
}

TEST(FourierTransform, WarmUpRunsUntilEveryPlanItUsesIsMeasured)
{
  // Per call, 10 inverse transforms of one new size and 3 forward ones of another: the inverse plan is
  // measured in call 2, the forward one in call 6 (its 16th run), and call 6 ends the warm-up.
  FourierTransform::setMeasurePolicy(FourierTransform::kMeasureAfter);
  cv::Mat a(41, 47, CV_32FC2, cv::Scalar::all(1)), b(43, 37, CV_32FC2, cv::Scalar::all(1)), out;
  const auto run = [&] {
    for (int i = 0; i < 10; ++i)
      FourierTransform::inverseUnscaled(a, out);
    for (int i = 0; i < 3; ++i)
      FourierTransform::forward(b, out);
  };
  const long measured = FourierTransform::plansMeasured();
  EXPECT_EQ(FourierTransform::warmUp(run), 6);
  EXPECT_EQ(FourierTransform::plansMeasured(), measured + 2);
  EXPECT_EQ(FourierTransform::warmUp(run), 1);
  EXPECT_EQ(FourierTransform::warmUp([] {}, 5), 1);
  EXPECT_EQ(FourierTransform::warmUp(run, 0), 0);
}

TEST(FourierTransform, MeasuresNoMorePlansThanItsBudget)
{
  // Budget 1: of two sizes run 16 times each, only the first is measured; warmUp does not wait for the
  // second (it will never be measured).
  FourierTransform::setMeasurePolicy(FourierTransform::kMeasureAfter, 1);
  cv::Mat a(29, 31, CV_32FC2, cv::Scalar::all(1)), b(31, 29, CV_32FC2, cv::Scalar::all(1)), out;
  const long measured = FourierTransform::plansMeasured();
  const auto run = [&] {
    FourierTransform::inverseUnscaled(a, out);
    FourierTransform::inverseUnscaled(b, out);
  };
  EXPECT_EQ(FourierTransform::warmUp(run, 100), FourierTransform::kMeasureAfter);
  EXPECT_EQ(FourierTransform::plansMeasured(), measured + 1);
  for (int i = 0; i < 20; ++i)
    run();
  EXPECT_EQ(FourierTransform::plansMeasured(), measured + 1);
  FourierTransform::setMeasurePolicy(FourierTransform::kMeasureAfter);
}

TEST(FourierTransform, ManyThreadsManySizesWhilePlansAreMeasuredAndEvicted)
{
  // 4 threads transform kMaxPlans + 88 small sizes (so the cache evicts) in different orders, every size
  // 3 times, with plans measured after 2 runs (budget 6): every result still equals cv::dft.
  FourierTransform::setMeasurePolicy(2, 6);
  const long measured = FourierTransform::plansMeasured(), made = FourierTransform::plansMade();
  std::vector<cv::Size> sizes;
  for (int i = 0; sizes.size() < size_t(FourierTransform::kMaxPlans + 88); ++i)
    sizes.emplace_back(3 + i % 29, 200 + i / 29);  // distinct, never another test's sizes
  std::atomic<int> wrong{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      cv::RNG rng(t);
      for (int round = 0; round < 3; ++round)
        for (size_t i = 0; i < sizes.size(); ++i)
        {
          const cv::Size size = sizes[(i * (2 * t + 1) + round * 7) % sizes.size()];
          cv::Mat x(size, CV_32FC2), ref, ours;
          rng.fill(x, cv::RNG::UNIFORM, -1.0, 1.0);
          cv::dft(x, ref, cv::DFT_INVERSE);
          FourierTransform::inverseUnscaled(x, ours);
          if (spectrumError(ours, ref) > 1e-5)
            ++wrong;
        }
    });
  for (std::thread& th : threads)
    th.join();
  EXPECT_EQ(wrong.load(), 0);
  EXPECT_EQ(FourierTransform::plansMeasured(), measured + 6);
  // Evicted sizes were planned again: more plans than sizes (+ the 6 measured ones).
  EXPECT_GT(FourierTransform::plansMade(), made + long(sizes.size()) + 6);
  FourierTransform::setMeasurePolicy(FourierTransform::kMeasureAfter);
}

TEST(EndStoppedCells, ShiftedIsExactBilinearWithReplicatedEdges)
{
  cv::Mat src(23, 31, CV_32F);
  cv::randu(src, 0.0, 1.0);
  const auto at = [&src](double x, double y) {  // replicated edges
    return double(src.at<float>(std::clamp(int(y), 0, src.rows - 1), std::clamp(int(x), 0, src.cols - 1)));
  };
  for (const cv::Point2f o : {cv::Point2f(0, 0), cv::Point2f(2.4f, -1.7f), cv::Point2f(-0.3f, 0.8f),
                              cv::Point2f(-3.5f, -2.25f), cv::Point2f(40.f, -30.5f), cv::Point2f(1.f, 0.f)})
  {
    const cv::Mat ours = EndStoppedCells::shifted(src, o);
    ASSERT_EQ(ours.size(), src.size());
    double worst = 0.0;
    for (int y = 0; y < src.rows; ++y)
      for (int x = 0; x < src.cols; ++x)
      {
        const double sx = x + o.x, sy = y + o.y, x0 = std::floor(sx), y0 = std::floor(sy);
        const double fx = sx - x0, fy = sy - y0;
        const double ref = (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
                           fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
        worst = std::max(worst, std::abs(ours.at<float>(y, x) - ref));
      }
    EXPECT_LT(worst, 1e-5) << o;
  }
}

TEST(SimpleCellBank, EqualsDirectConvolutionAtEveryGrid)
{
  const cv::Mat img = texture(173, 131, 7);  // odd sizes exercise padding and cropping
  for (double min_grid : {0.0, 2.0, 4.0})
  {
    GaborParameters p;
    p.wavelengths = {4, 6, 8, 12, 16, 24, 32};
    p.min_grid_wavelength = min_grid;
    SimpleCellBank bank(p);
    const auto ours = bank.compute(img);
    const auto ref = DirectGaborBank(p).compute(img);
    // Stated tolerance: 1e-4 of the largest response (measured ~2e-6, float rounding).
    EXPECT_LT(DirectGaborBank::maxRelativeError(ours, ref), 1e-4) << "min_grid_wavelength " << min_grid;
    // Decimation follows lambda / d >= min_grid.
    if (min_grid == 2.0)
    {
      EXPECT_EQ(ours[0].decimation, 2);   // lambda 4
      EXPECT_EQ(ours[6].decimation, 16);  // lambda 32
      EXPECT_EQ(ours[0].gridSize(), cv::Size(87, 66));
    }
  }
}

TEST(SimpleCellBank, ReplansWhenTheImageSizeChanges)
{
  GaborParameters p;
  SimpleCellBank bank(p);
  const auto ref_small = DirectGaborBank(p).compute(texture(64, 48, 1));
  const auto ref_large = DirectGaborBank(p).compute(texture(96, 80, 2));
  EXPECT_LT(DirectGaborBank::maxRelativeError(bank.compute(texture(96, 80, 2)), ref_large), 1e-4);
  EXPECT_LT(DirectGaborBank::maxRelativeError(bank.compute(texture(64, 48, 1)), ref_small), 1e-4);
}

TEST(SimpleCellBank, ReusesCachedKernelSpectraAcrossSizesOfOneDftSize)
{
  GaborParameters p;
  p.wavelengths = {4, 8};
  p.min_grid_wavelength = 0.0;
  SimpleCellBank bank(p);
  // 62 and 63 px (plus padding) round up to the same DFT sizes: the second size builds nothing, and its
  // responses (and odd cells) still equal the direct convolution of its own size.
  const cv::Mat a = texture(62, 50, 3), b = texture(63, 51, 4);
  bank.compute(a);
  EXPECT_EQ(bank.plansBuilt(), 1);
  const auto ours = bank.compute(b);
  EXPECT_EQ(bank.plansBuilt(), 1);
  const auto ref = DirectGaborBank(p).compute(b);
  EXPECT_LT(DirectGaborBank::maxRelativeError(ours, ref), 1e-4);
  const auto odd = bank.computeOdd(b);  // adds the odd pairs to the cached set
  EXPECT_EQ(bank.plansBuilt(), 1);
  for (size_t s = 0; s < ref.size(); ++s)
    for (int i = 0; i < p.orientations; ++i)
    {
      double peak = 0.0;
      cv::minMaxLoc(cv::abs(ref[s].odd[i]), nullptr, &peak);
      EXPECT_LT(cv::norm(odd[s][i], ref[s].odd[i], cv::NORM_INF), 1e-4 * std::max(peak, 1e-6)) << s << " " << i;
    }
  // The cache keeps kPlanCacheSize sets: as many more distinct sizes evict the first, which is rebuilt.
  // Widths 64 px apart always round up to distinct DFT sizes (5-smooth numbers below 2000 are < 64 apart).
  for (int k = 0; k < SimpleCellBank::kPlanCacheSize; ++k)
    bank.compute(texture(100 + 64 * k, 40, k));
  EXPECT_EQ(bank.plansBuilt(), 1 + SimpleCellBank::kPlanCacheSize);
  EXPECT_LT(DirectGaborBank::maxRelativeError(bank.compute(a), DirectGaborBank(p).compute(a)), 1e-4);
  EXPECT_EQ(bank.plansBuilt(), 2 + SimpleCellBank::kPlanCacheSize);
}

TEST(SimpleCellBank, CoarseDftSizesCollapseChangingSizesAndKeepTheResponses)
{
  // The lengths: 2^a * {8, 10, 12, 15}, at least n, and the smallest such.
  for (int n = 1; n <= 2000; ++n)
  {
    const int len = SimpleCellBank::dftLength(n, true);
    ASSERT_GE(len, n);
    int smallest = 1 << 30;  // brute force over the set
    for (int a = 0; a < 12; ++a)
      for (int m : {8, 10, 12, 15})
        if ((m << a) >= n)
          smallest = std::min(smallest, m << a);
    if (n > 8)
    {
      ASSERT_EQ(len, smallest) << n;
    }
    if (n > 8)
    {
      int m = len;
      while (m % 2 == 0 && m > 15)
        m /= 2;
      ASSERT_TRUE(m == 8 || m == 10 || m == 12 || m == 15) << n << " -> " << len;
      ASSERT_LE(len, n * 1.25 + 1) << n;  // four lengths per octave
    }
    ASSERT_EQ(SimpleCellBank::dftLength(n, false), cv::getOptimalDFTSize(n));
  }
  GaborParameters p;
  p.wavelengths = {4, 8};
  SimpleCellBank exact(p), coarse(p);
  coarse.setCoarseDftSizes(true);
  EXPECT_FALSE(exact.coarseDftSizes());
  // Crops of 20 sizes between 70 and 89 px (a salient region that grows): the default bank rebuilds its
  // kernel spectra for most of them, the coarse one for a few, with the same responses.
  for (int k = 0; k < 20; ++k)
  {
    const cv::Mat crop = texture(70 + k, 89 - k, 10 + k);
    const auto a = exact.compute(crop);
    const auto b = coarse.compute(crop);
    if (k % 5 == 0)  // against the direct convolution, as the default bank is
    {
      const auto ref = DirectGaborBank(p).compute(crop);
      ASSERT_LT(DirectGaborBank::maxRelativeError(a, ref), 1e-4) << k;
      ASSERT_LT(DirectGaborBank::maxRelativeError(b, ref), 1e-4) << k;
    }
  }
  EXPECT_LE(coarse.plansBuilt(), 4);
  EXPECT_GE(exact.plansBuilt(), 2 * coarse.plansBuilt());
}

TEST(SimpleCellBank, OddPairBuffersAreReusedOnlyOnceTheCallerLetsGo)
{
  GaborParameters p;
  p.wavelengths = {4};
  p.min_grid_wavelength = 0.0;
  SimpleCellBank bank(p);
  const cv::Mat a = texture(70, 50, 5), b = texture(70, 50, 6);
  const auto held = bank.computeOddPairs(a);
  const cv::Mat held_copy = held[0][0].clone();
  // The views of a are still held: b's responses go to new buffers and a's stay as they were.
  auto from_b = bank.computeOddPairs(b);
  EXPECT_NE(from_b[0][0].data, held[0][0].data);
  EXPECT_EQ(cv::norm(held[0][0], held_copy, cv::NORM_INF), 0.0);
  // Let go of b's views: the next call writes into b's buffers, with b's responses of a fresh bank.
  const uchar* b_data = from_b[0][0].data;
  const cv::Mat b_copy = from_b[0][0].clone();
  from_b.clear();
  const auto again = bank.computeOddPairs(b);
  EXPECT_EQ(again[0][0].data, b_data);
  // Within rounding: the transform's plan may have been measured between the calls (FourierTransform).
  double peak = 0.0;
  cv::minMaxLoc(cv::abs(b_copy), nullptr, &peak);
  EXPECT_LT(cv::norm(again[0][0], b_copy, cv::NORM_INF), 1e-5 * peak);
  EXPECT_LT(cv::norm(again[0][0], SimpleCellBank(p).computeOddPairs(b)[0][0], cv::NORM_INF), 1e-5 * peak);
}

TEST(SimpleCellBank, UniformImageGivesNoResponse)
{
  GaborParameters p;
  SimpleCellBank bank(p);
  for (const auto& scale : bank.compute(cv::Mat(60, 80, CV_32F, cv::Scalar(0.7))))
    for (int i = 0; i < scale.orientations(); ++i)
      EXPECT_LT(cv::norm(scale.complexCell(i), cv::NORM_INF), 1e-5);
}

TEST(SimpleCellBank, GratingAtPreferredFrequencyGivesHalfItsAmplitude)
{
  // A vertical sinusoidal grating of amplitude A: the theta = 0 complex cell responds ~A/2.
  cv::Mat img(96, 128, CV_32F);
  const double lambda = 8.0, amplitude = 0.4;
  for (int y = 0; y < img.rows; ++y)
    for (int x = 0; x < img.cols; ++x)
      img.at<float>(y, x) = static_cast<float>(0.5 + amplitude * std::cos(2 * M_PI * x / lambda));
  GaborParameters p;
  p.wavelengths = {lambda};
  SimpleCellBank bank(p);
  const auto r = bank.compute(img);
  const cv::Mat c = r[0].complexCell(0);
  const cv::Size g = r[0].gridSize();
  EXPECT_NEAR(c.at<float>(g.height / 2, g.width / 2), amplitude / 2, 0.02);
}

TEST(LineEdgeDetector, BarGivesPositiveLineAtItsPositionInItsChannel)
{
  // Bright vertical bar 4 px wide centred at x = 80: line+ in channel 0 (normal along x).
  cv::Mat img = canvas();
  cv::rectangle(img, cv::Rect(78, 10, 4, 100), cv::Scalar(kForeground), cv::FILLED);
  V1Pipeline pipeline(singleScale(8.0));
  const auto result = pipeline.process(img, true);
  const LineEdgeMap& le = result.line_edges[0];
  const int d = le.decimation;
  const int row = 60 / d;
  int found = -1;
  for (int x = 0; x < le.events.cols; ++x)
    if (le.events.at<uchar>(row, x) == LineEdgeMap::kLinePositive)
    {
      EXPECT_EQ(le.orientation.at<uchar>(row, x), 0);
      found = x * d;
    }
  ASSERT_GE(found, 0) << "no line event on the bar";
  EXPECT_NEAR(found, 79.5, 2.5);
  // Nothing but the bar's line on that row (no edge events beside a thin bar).
  for (int x = 0; x < le.events.cols; ++x)
  {
    if (std::abs(x * d - 79.5) > 4)
    {
      EXPECT_EQ(le.events.at<uchar>(row, x), LineEdgeMap::kNone) << "x=" << x * d;
    }
  }
}

TEST(LineEdgeDetector, DarkBarGivesNegativeLine)
{
  cv::Mat img(120, 160, CV_32F, cv::Scalar(kForeground));
  cv::rectangle(img, cv::Rect(10, 58, 140, 4), cv::Scalar(kBackground), cv::FILLED);  // horizontal
  V1Pipeline pipeline(singleScale(8.0));
  const LineEdgeMap le = pipeline.process(img, true).line_edges[0];
  const int d = le.decimation, col = 80 / d;
  int hits = 0;
  for (int y = 0; y < le.events.rows; ++y)
    if (le.events.at<uchar>(y, col) == LineEdgeMap::kLineNegative)
    {
      ++hits;
      EXPECT_EQ(le.orientation.at<uchar>(y, col), 4);  // theta = 90 deg: normal along y
      EXPECT_NEAR(y * d, 59.5, 2.5);
    }
  EXPECT_GE(hits, 1);
}

TEST(LineEdgeDetector, StepEdgeGivesEdgeEvent)
{
  // Dark left half, bright right half: dark-to-bright along +x = edge+ in channel 0 at x = 80.
  cv::Mat img = canvas();
  img(cv::Rect(80, 0, 80, 120)).setTo(kForeground);
  V1Pipeline pipeline(singleScale(8.0));
  const LineEdgeMap le = pipeline.process(img, true).line_edges[0];
  const int d = le.decimation, row = 60 / d;
  int found = -1;
  for (int x = 0; x < le.events.cols; ++x)
    if (le.events.at<uchar>(row, x) != LineEdgeMap::kNone)
    {
      EXPECT_EQ(le.events.at<uchar>(row, x), LineEdgeMap::kEdgePositive);
      EXPECT_EQ(le.orientation.at<uchar>(row, x), 0);
      found = x * d;
    }
  ASSERT_GE(found, 0);
  EXPECT_NEAR(found, 79.5, 2.5);
  // The mirrored edge is edge-.
  cv::Mat mirrored;
  cv::flip(img, mirrored, 1);
  const LineEdgeMap le2 = pipeline.process(mirrored, true).line_edges[0];
  int negatives = 0;
  for (int x = 0; x < le2.events.cols; ++x)
    negatives += le2.events.at<uchar>(row, x) == LineEdgeMap::kEdgeNegative;
  EXPECT_GE(negatives, 1);
}

TEST(LineEdgeDetector, LateralInhibitionStopsEventsPastALineEnd)
{
  // A bar ending at y = 60: well past its end (y >= 60 + lambda) there must be no event.
  cv::Mat img = canvas();
  cv::rectangle(img, cv::Rect(78, 0, 4, 60), cv::Scalar(kForeground), cv::FILLED);
  V1Pipeline pipeline(singleScale(8.0));
  const LineEdgeMap le = pipeline.process(img, true).line_edges[0];
  const int d = le.decimation;
  for (int y = (60 + 8) / d; y < le.events.rows; ++y)
    for (int x = 70 / d; x <= 90 / d; ++x)
      EXPECT_EQ(le.events.at<uchar>(y, x), LineEdgeMap::kNone) << "event at " << x * d << "," << y * d;
}

TEST(V1Pipeline, BlankImageGivesNoKeypoints)
{
  V1Pipeline pipeline{V1Pipeline::Parameters()};
  EXPECT_TRUE(pipeline.process(canvas()).keypoints.empty());
  cv::Mat noisy = canvas();
  cv::RNG rng(3);
  cv::Mat n(noisy.size(), CV_32F);
  rng.fill(n, cv::RNG::NORMAL, 0.0, 0.002);  // sensor noise far below any edge
  EXPECT_TRUE(pipeline.process(noisy + n).keypoints.empty());
}

TEST(V1Pipeline, JunctionsEndsAndBlobGiveKeypointsWithin2px)
{
  // Default multi-scale pipeline (lambda 4, 8, 16): some scale must put a keypoint on each vertex.
  V1Pipeline pipeline{V1Pipeline::Parameters()};
  struct Case
  {
    const char* name;
    cv::Mat image;
    cv::Point2f vertex;
  };
  std::vector<Case> cases;
  {  // L: solid corner of a bright square
    cv::Mat img = canvas();
    cv::rectangle(img, cv::Rect(80, 60, 80, 60), cv::Scalar(kForeground), cv::FILLED);
    cases.push_back({"L-junction", img, {79.5f, 59.5f}});
  }
  {  // T: a 2 px line ending on another
    cv::Mat img = canvas();
    cv::rectangle(img, cv::Rect(20, 40, 120, 2), cv::Scalar(kForeground), cv::FILLED);
    cv::rectangle(img, cv::Rect(79, 42, 2, 60), cv::Scalar(kForeground), cv::FILLED);
    cases.push_back({"T-junction", img, {79.5f, 41.5f}});
  }
  {  // X: two crossing 2 px lines
    cv::Mat img = canvas();
    cv::rectangle(img, cv::Rect(20, 59, 120, 2), cv::Scalar(kForeground), cv::FILLED);
    cv::rectangle(img, cv::Rect(79, 10, 2, 100), cv::Scalar(kForeground), cv::FILLED);
    cases.push_back({"X-junction", img, {79.5f, 59.5f}});
  }
  {  // X at 60 degrees, 1 px lines
    cv::Mat img = canvas();
    cv::line(img, {10, 60}, {150, 60}, cv::Scalar(kForeground), 1, cv::LINE_AA);
    cv::line(img, {52, 12}, {107, 107}, cv::Scalar(kForeground), 1, cv::LINE_AA);
    cases.push_back({"X-junction 60 deg", img, {80.f, 60.f}});
  }
  {  // blob
    cv::Mat img = canvas();
    cv::circle(img, {80, 60}, 4, cv::Scalar(kForeground), cv::FILLED, cv::LINE_AA);
    cases.push_back({"blob", img, {80.f, 60.f}});
  }
  {  // line end
    cv::Mat img = canvas();
    cv::rectangle(img, cv::Rect(20, 59, 100, 2), cv::Scalar(kForeground), cv::FILLED);
    cases.push_back({"line end", img, {119.5f, 59.5f}});
  }
  for (const auto& c : cases)
  {
    const auto kps = pipeline.process(c.image).keypoints;
    EXPECT_LE(distanceToNearest(kps, c.vertex), 2.0) << c.name << ": " << kps.size() << " keypoints";
  }
}

TEST(V1Pipeline, KeypointOrientationAndScaleAreReported)
{
  cv::Mat img = canvas();
  cv::circle(img, {80, 60}, 4, cv::Scalar(kForeground), cv::FILLED, cv::LINE_AA);
  V1Pipeline pipeline{V1Pipeline::Parameters()};
  const auto kps = pipeline.process(img).keypoints;
  ASSERT_FALSE(kps.empty());
  for (size_t k = 1; k < kps.size(); ++k)
    EXPECT_GE(kps[k - 1].strength, kps[k].strength) << "strongest first";
  for (const auto& k : kps)
  {
    EXPECT_TRUE(k.wavelength == 4.f || k.wavelength == 8.f || k.wavelength == 16.f);
    EXPECT_GE(k.orientation, 0.f);
    EXPECT_LT(k.orientation, static_cast<float>(M_PI));
  }
}

TEST(V1Pipeline, StraightEdgesAndLinesHaveNoKeypointsInTheirMiddle)
{
  V1Pipeline pipeline{V1Pipeline::Parameters()};
  cv::Mat edge = canvas();
  edge(cv::Rect(0, 0, 80, 120)).setTo(kForeground);  // spans the whole height
  for (const auto& k : pipeline.process(edge).keypoints)
    EXPECT_FALSE(std::abs(k.y - 60) < 30) << "keypoint on a straight edge at " << k.x << "," << k.y;
  cv::Mat line = canvas();
  cv::rectangle(line, cv::Rect(10, 59, 140, 2), cv::Scalar(kForeground), cv::FILLED);
  for (const auto& k : pipeline.process(line).keypoints)
    EXPECT_FALSE(std::abs(k.x - 80) < 40) << "keypoint on a straight line at " << k.x << "," << k.y;
}

TEST(V1Pipeline, Rotating45DegreesMovesTheMaximumByTwoChannels)
{
  cv::Mat img = canvas(161, 161);
  cv::rectangle(img, cv::Rect(78, 20, 5, 121), cv::Scalar(kForeground), cv::FILLED);
  GaborParameters p;
  p.wavelengths = {8.0};
  SimpleCellBank bank(p);
  auto dominant = [&](const cv::Mat& m) {
    const auto r = bank.compute(m);
    const cv::Size g = r[0].gridSize();
    int best = 0;
    float best_v = -1;
    for (int i = 0; i < r[0].orientations(); ++i)
    {
      const float v = r[0].complexCell(i).at<float>(g.height / 2, g.width / 2);
      if (v > best_v)
      {
        best_v = v;
        best = i;
      }
    }
    return best;
  };
  const int before = dominant(img);
  cv::Mat rotated;
  // +45 deg is counter-clockwise on screen; with y down that turns theta by -45 deg: two channels down.
  cv::warpAffine(img, rotated, cv::getRotationMatrix2D({80, 80}, 45, 1.0), img.size(), cv::INTER_LINEAR,
                 cv::BORDER_CONSTANT, cv::Scalar(kBackground));
  EXPECT_EQ(before, 0);
  EXPECT_EQ(dominant(rotated), (before - 2 + 8) % 8);
}

TEST(InputImage, ConvertsDepthsAndChannels)
{
  cv::Mat u8(20, 20, CV_8UC3, cv::Scalar(255, 255, 255));
  EXPECT_NEAR(InputImage(u8).gray().at<float>(5, 5), 1.0, 1e-6);
  cv::Mat u16(20, 20, CV_16U, cv::Scalar(65535 / 2));
  EXPECT_NEAR(InputImage(u16).gray().at<float>(5, 5), 0.5, 1e-4);
  cv::Mat f64(20, 20, CV_64F, cv::Scalar(0.25));
  EXPECT_NEAR(InputImage(f64).gray().at<float>(5, 5), 0.25, 1e-6);
  cv::Mat bgra(20, 20, CV_8UC4, cv::Scalar(0, 0, 0, 255));
  EXPECT_NEAR(InputImage(bgra).gray().at<float>(5, 5), 0.0, 1e-6);
}

TEST(InputImage, RejectsBadInputClearly)
{
  EXPECT_THROW(InputImage(cv::Mat()), std::invalid_argument);
  EXPECT_THROW(InputImage(cv::Mat(1, 1, CV_8U)), std::invalid_argument);
  EXPECT_THROW(InputImage(cv::Mat(20, 20, CV_32S)), std::invalid_argument);
  EXPECT_THROW(InputImage(cv::Mat(20, 20, CV_8UC2)), std::invalid_argument);
  try
  {
    InputImage(cv::Mat(4, 30, CV_8U));
    FAIL();
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("30x4"), std::string::npos) << e.what();
  }
}

TEST(V1Pipeline, NonFinitePixelsAreReplacedAndCounted)
{
  cv::Mat img = canvas();
  cv::rectangle(img, cv::Rect(80, 60, 80, 60), cv::Scalar(kForeground), cv::FILLED);
  img.at<float>(10, 10) = std::numeric_limits<float>::quiet_NaN();
  img.at<float>(20, 30) = std::numeric_limits<float>::infinity();
  V1Pipeline pipeline{V1Pipeline::Parameters()};
  const auto r = pipeline.process(img);
  EXPECT_EQ(r.nonfinite_pixels, 2);
  for (const auto& k : r.keypoints)
  {
    EXPECT_TRUE(std::isfinite(k.x) && std::isfinite(k.y) && std::isfinite(k.strength));
  }
}

TEST(V1Pipeline, ImageSmallerThanTheFilterSupportIsDefined)
{
  // 12x10 is smaller than every kernel (lambda 16 has radius 63): responses exist, coarse scales
  // give no keypoints, nothing is NaN.
  cv::Mat img(10, 12, CV_8U, cv::Scalar(50));
  img(cv::Rect(6, 0, 6, 10)).setTo(200);
  V1Pipeline pipeline{V1Pipeline::Parameters()};
  const auto r = pipeline.process(img, true);
  ASSERT_EQ(r.responses.size(), 3u);
  for (const auto& s : r.responses)
    for (int i = 0; i < s.orientations(); ++i)
      EXPECT_TRUE(cv::checkRange(s.even[i]) && cv::checkRange(s.odd[i]));
  for (const auto& k : r.keypoints)
    EXPECT_LE(k.wavelength, 5.0);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
