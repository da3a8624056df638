#pragma once

#include <functional>
#include <string>

#include <opencv2/core.hpp>

namespace biovision_v1
{
/// 2-D discrete Fourier transforms of single-precision images through FFTW3 (Frigo & Johnson 2005,
/// Debian's libfftw3): the transforms of SimpleCellBank, the V1 front end of every module. Why not
/// cv::dft: on this project's 2-core machines FFTW's estimated plans ran the bank's sizes 2-4x faster
/// (480x400 complex: 1.7 ms vs 3.5 ms; 240x200: 0.18 vs 0.66 ms), and the bank is a fifth to a half of
/// the perception loop's CPU.
///
/// Conventions are cv::dft's: forward() gives the full complex spectrum, neither transform scales (the
/// caller folds 1/N into a kernel spectrum, where it costs nothing). Plans are made per size and kind and
/// shared by every thread of the process; executing them is thread-safe, making them is serialised here.
/// A new size gets an FFTW_ESTIMATE plan (no timing runs, about 1 ms); once a size has run kMeasureAfter
/// times (a camera stream's size, not a test's odd one) it is planned again with FFTW_MEASURE (100-300 ms
/// once, about kMeasureTimeLimit at most, while other threads keep running the plans they have; one that
/// needs a new plan waits; at most kMaxMeasuredPlans since the last setMeasurePolicy()): 1.3-3.6x faster
/// transforms here (fftw 3.3.10, AMD EPYC: 480x640 complex 2.4 -> 0.67 ms, 400x480 0.80 -> 0.45 ms, 240x320
/// 0.18 -> 0.13 ms). A measured plan is chosen by timing, so its rounding may differ from one process to
/// the next by about 1e-7 of the spectrum's peak. The least recently used plans are dropped beyond
/// kMaxPlans, so a consumer of ever-changing sizes keeps a bounded cache.
class FourierTransform
{
public:
  static constexpr int kMaxPlans = 512;
  /// Executions of one size and kind after which its plan is measured (the environment variable
  /// BIOVISION_FFT_MEASURE_AFTER, read once per process, and setMeasurePolicy() override it).
  static constexpr int kMeasureAfter = 16;
  /// Plans measured per process at most: a camera stream's few sizes, not every size of the crops a
  /// recognition stage transforms (measuring each of those cost more than it saved).
  static constexpr int kMaxMeasuredPlans = 24;
  /// FFTW's planning time limit for a measured plan [s].
  static constexpr double kMeasureTimeLimit = 1.0;

  /// spectrum = DFT(src), the full H x W spectrum (CV_32FC2) of a CV_32FC1 (real) or CV_32FC2 (complex)
  /// image; for a real image the half FFTW does not compute is filled by Hermitian symmetry. spectrum may
  /// be src itself when src is complex. spectrum's buffer is reused when it has the size and no other
  /// cv::Mat shares it (releaseIfShared). Throws std::invalid_argument on an empty image or another type.
  static void forward(const cv::Mat& src, cv::Mat& spectrum);

  /// dst = N * IDFT(spectrum), N = H * W (unscaled, as cv::idft without DFT_SCALE): CV_32FC2 in and out;
  /// dst may be spectrum itself. Throws std::invalid_argument on an empty or non-CV_32FC2 input.
  static void inverseUnscaled(const cv::Mat& spectrum, cv::Mat& dst);

  /// product = a * b element-wise (complex, CV_32FC2, equal sizes), exactly as cv::mulSpectrums(a, b,
  /// product, 0) rounds it (each element's real and imaginary part formed in double, rounded once; only the
  /// sign bit of a NaN, e.g. from 0 * inf, can differ in the vectorised loop), at
  /// 2-4x its speed (vectorised; 486x432: 0.19 vs 0.36 ms). product may be a or b; otherwise it is
  /// (re)allocated continuous and aligned for FFTW, so an in-place inverseUnscaled() needs no copy.
  /// Throws std::invalid_argument on another type or size.
  static void multiplySpectra(const cv::Mat& a, const cv::Mat& b, cv::Mat& product);

  /// Lets go of m's buffer when another cv::Mat shares it (an atomic read of OpenCV's reference count), so
  /// that an output buffer kept between calls is written again only once every view of it is gone.
  static void releaseIfShared(cv::Mat& m);

  /// "fftw3f <version>" (for benchmark reports).
  static std::string backend();
  /// Plans made so far in this process (for tests: a second transform of one size makes none), measured
  /// ones included.
  static long plansMade();
  /// FFTW_MEASURE plans made so far in this process.
  static long plansMeasured();
  /// Executions after which a size's plan is measured and how many plans may be measured from now on,
  /// for the whole process; after_executions <= 0: never (estimated plans only, e.g. for bit-reproducible
  /// runs).
  static void setMeasurePolicy(int after_executions, int max_measured_plans = kMaxMeasuredPlans);

  /// Benchmarks' warm-up: calls `run` until every plan a call used is a measured one (so that plans are
  /// measured before the timed runs, not in them), at most max_runs times; returns the calls made.
  static int warmUp(const std::function<void()>& run, int max_runs = 2 * kMeasureAfter);
};
}  // namespace biovision_v1
