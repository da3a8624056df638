#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "biovision_v1/gabor_parameters.hpp"
#include "biovision_v1/scale_responses.hpp"

namespace biovision_v1
{
/// Even and odd simple cells for every scale and orientation, computed in the frequency domain.
///
/// Why it is fast and still exact:
/// - even + i*odd is one complex kernel, so one complex inverse DFT gives R^E (real part) and R^O
///   (imaginary part) of an orientation at once;
/// - the image spectrum is computed once per scale and shared by all orientations;
/// - a coarse scale is sampled on a coarser grid by folding the product spectrum (the spectrum of the
///   full convolution sampled every d pixels is the sum of its d x d aliases), so the inverse DFT is
///   d^2 times smaller and the result is the full-resolution convolution at those samples, up to the
///   kernel's spectral leakage beyond the coarse Nyquist frequency. A quadrature (complex) response has a
///   one-sided spectrum, so its grid only needs lambda / d >= 2, not 4 as a real band-pass would;
/// - the product is only formed where the kernel's spectrum is not negligible (the Gabor lobe covers
///   about a tenth of the spectrum), fused with the folding;
/// - the image is padded by the kernel radius with BORDER_REFLECT_101, so the circular convolution
///   equals cv::filter2D's border handling.
/// Kernel spectra are cached per DFT size, for the kPlanCacheSize sizes used last: a consumer whose
/// image size changes from call to call (recognition's region crops) reuses them whenever two sizes
/// round up to the same DFT size, instead of rebuilding 2 x orientations kernel DFTs per call.
class SimpleCellBank
{
public:
  explicit SimpleCellBank(const GaborParameters& parameters);

  /// gray: CV_32FC1 (see InputImage). Returns one ScaleResponses per wavelength, in order.
  std::vector<ScaleResponses> compute(const cv::Mat& gray);

  /// Odd simple cells R^O only, for consumers that need nothing else (the stereo descriptor). Each
  /// R^O is real, so two orientations share one complex inverse DFT (R_i + i R_j): half the work of
  /// compute(). Requires decimation 1 at every scale (min_grid_wavelength 0): a real response needs
  /// four samples per wavelength, not two. Returns per scale one CV_32F map per orientation.
  std::vector<std::vector<cv::Mat>> computeOdd(const cv::Mat& gray);

  /// computeOdd() without its final split: per scale one CV_32FC2 map per orientation pair, R^O of
  /// orientation 2i in channel 0 and of 2i+1 in channel 1 (an odd count's last pair has 0 in channel 1).
  /// The maps are views into the padded inverse DFTs (not continuous): one pass over the data fewer. The
  /// bank reuses those buffers in its next call once every cv::Mat view of them is released (held cv::Mat
  /// views stay valid; a raw pointer into them does not).
  std::vector<std::vector<cv::Mat>> computeOddPairs(const cv::Mat& gray);

  /// computeOddPairs() of several images of one size at once (BioBin's stereo pair), result [image][scale]
  /// [pair]: first every image's forward DFT, then every image's inverse DFTs, each as one parallel loop,
  /// so that the images' transforms run side by side (one image's single forward DFT would keep the other
  /// threads idle). The same values as one call per image, bit for bit. Memory: every image's padded copy,
  /// spectrum and four pair inverse DFTs are alive at once and kept for the next call (one call per image
  /// reuses one set): 44 bytes per padded pixel and scale for each image beyond the first (~95 MB for a
  /// second 1920x1080 image, ~9 MB at 450x375). Throws std::invalid_argument on no image, an empty, non-2-D
  /// or non-CV_32FC1 one, or images of different sizes.
  std::vector<std::vector<std::vector<cv::Mat>>> computeOddPairsBatch(const std::vector<cv::Mat>& grays);

  const GaborParameters& parameters() const { return parameters_; }

  /// Kernel spectra sets kept (one per distinct set of DFT sizes), least recently used dropped first.
  static constexpr int kPlanCacheSize = 24;
  /// Kernel spectra sets built so far (for tests and benchmarks: a cache hit builds none).
  long plansBuilt() const { return plans_built_; }

  /// Coarse DFT sizes: each padded dimension rounds up to the next of 2^a * {8, 10, 12, 15} (four per
  /// octave, all FFT-friendly) instead of cv::getOptimalDFTSize's next 5-smooth number. For a consumer
  /// whose image size changes from call to call (recognition's region crops): far fewer distinct sizes, so
  /// the kernel spectra are rebuilt far less often (loop_bench: 2.5 sets built per region before), at up
  /// to 25% more DFT length per dimension. The responses are the same up to float rounding (the padding
  /// beyond the kernel radius never reaches the image). Off by default: fixed-size consumers lose by it.
  void setCoarseDftSizes(bool coarse) { coarse_dft_sizes_ = coarse; }
  bool coarseDftSizes() const { return coarse_dft_sizes_; }
  /// The DFT length a padded dimension of n samples gets (coarse: see setCoarseDftSizes()).
  static int dftLength(int n, bool coarse);

private:
  struct SpectrumRun
  {
    int row, col;              // first entry in the full-resolution spectrum
    int grid_row, grid_col;    // where it folds to on the grid
    std::vector<cv::Vec2f> h;  // kernel spectrum values along the row
  };

  struct ScalePlan
  {
    double wavelength = 0.0;
    int decimation = 1;
    int padding = 0;          // image padding [px], a multiple of decimation
    cv::Size padded;          // DFT size at full resolution, a multiple of decimation
    int spectrum_source = 0;  // index of the scale whose image spectrum this scale reads
    // Per orientation: the kernel spectrum (DFT of the flipped complex kernel, / d^2) where it is not
    // negligible, as runs along spectrum rows, each already mapped onto the folded grid.
    std::vector<std::vector<SpectrumRun>> runs;
    // Per orientation pair (i, i+1): spectrum of odd_i + j odd_{i+1} (both real kernels), for computeOdd
    // only (built on its first call: compute() never reads them).
    std::vector<cv::Mat> odd_pair_spectra;
  };

  struct PlanSet
  {
    std::vector<cv::Size> key;  // per scale: the padded DFT size, all the spectra depend on
    std::vector<ScalePlan> plans;
    bool odd_pairs = false;  // odd_pair_spectra built
    long last_use = 0;
  };

  /// Makes plans_ point at the kernel spectra for image_size (from the cache, or built and cached).
  void plan(const cv::Size& image_size, bool odd_pairs);
  void buildSpectra(ScalePlan& p, bool odd_pairs) const;
  const std::vector<ScalePlan>& current() const { return cache_.at(current_).plans; }
  std::vector<cv::Mat> imageSpectra(const cv::Mat& gray) const;
  /// The scales whose padding an image spectrum is taken at (each distinct spectrum_source once, in order).
  std::vector<int> spectrumSources() const;
  /// gray padded by p.padding with BORDER_REFLECT_101 to p.padded, into `padded` (reused when unshared).
  static void padImage(const cv::Mat& gray, const ScalePlan& p, cv::Mat& padded);
  static std::vector<SpectrumRun> supportRuns(const cv::Mat& spectrum, const cv::Size& grid);

  GaborParameters parameters_;
  std::vector<PlanSet> cache_;
  int current_ = -1;                    // the cache_ entry plan() chose last
  std::vector<cv::Mat> pair_products_;  // computeOddPairs' inverse DFTs, reused once the caller let go
  // compute()'s folded spectra and even/odd responses per (scale, orientation), reused once the caller
  // let go of the responses.
  std::vector<cv::Mat> folded_, kept_responses_;
  // imageSpectra()'s padded images and spectra per scale (computeOddPairs(): per image and scale), reused
  // between calls (one caller at a time).
  mutable std::vector<cv::Mat> padded_images_, image_spectra_;
  long uses_ = 0, plans_built_ = 0;
  bool coarse_dft_sizes_ = false;
};
}  // namespace biovision_v1
