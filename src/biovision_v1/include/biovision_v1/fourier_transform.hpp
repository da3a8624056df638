#pragma once

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
/// caller folds 1/N into a kernel spectrum, where it costs nothing). Plans (FFTW_ESTIMATE: no timing runs,
/// about 1 ms each) are made once per size and kind and shared by every thread of the process; executing
/// them is thread-safe, making them is serialised here. The least recently used plans are dropped beyond
/// kMaxPlans, so a consumer of ever-changing sizes keeps a bounded cache.
class FourierTransform
{
public:
  static constexpr int kMaxPlans = 512;

  /// spectrum = DFT(src), the full H x W spectrum (CV_32FC2) of a CV_32FC1 (real) or CV_32FC2 (complex)
  /// image; for a real image the half FFTW does not compute is filled by Hermitian symmetry. spectrum may
  /// be src itself when src is complex. Throws std::invalid_argument on an empty image or another type.
  static void forward(const cv::Mat& src, cv::Mat& spectrum);

  /// dst = N * IDFT(spectrum), N = H * W (unscaled, as cv::idft without DFT_SCALE): CV_32FC2 in and out;
  /// dst may be spectrum itself. Throws std::invalid_argument on an empty or non-CV_32FC2 input.
  static void inverseUnscaled(const cv::Mat& spectrum, cv::Mat& dst);

  /// "fftw3f <version>" (for benchmark reports).
  static std::string backend();
  /// Plans made so far in this process (for tests: a second transform of one size makes none).
  static long plansMade();
};
}  // namespace biovision_v1
