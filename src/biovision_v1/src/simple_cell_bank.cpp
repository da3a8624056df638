#include "biovision_v1/simple_cell_bank.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "biovision_v1/fourier_transform.hpp"
#include "biovision_v1/gabor_kernel.hpp"
#include "biovision_common/parallel_arena.hpp"

namespace biovision_v1
{
namespace
{
// Kernel spectrum entries below this fraction of its peak are left out of the product: their
// contribution is below the float rounding of the responses.
constexpr double kNegligibleSpectrum = 1e-6;

int roundUp(int value, int multiple)
{
  return (value + multiple - 1) / multiple * multiple;
}
}  // namespace

std::vector<SimpleCellBank::SpectrumRun> SimpleCellBank::supportRuns(const cv::Mat& spectrum, const cv::Size& grid)
{
  // Squared magnitudes in double against the squared floor: the same entries as |h| <= floor, without a
  // square root per entry (recognition re-plans its pyramid for every region size: under perf on
  // loop_bench this function was 3.4% of the whole perception process, cv::norm per entry).
  const auto squared = [](const cv::Vec2f& v) { return double(v[0]) * v[0] + double(v[1]) * v[1]; };
  double peak2 = 0.0;
  for (int y = 0; y < spectrum.rows; ++y)
  {
    const cv::Vec2f* row = spectrum.ptr<cv::Vec2f>(y);
    for (int x = 0; x < spectrum.cols; ++x)
      peak2 = std::max(peak2, squared(row[x]));
  }
  const double floor = kNegligibleSpectrum * std::sqrt(peak2), floor2 = floor * floor;
  std::vector<SpectrumRun> runs;
  for (int y = 0; y < spectrum.rows; ++y)
  {
    const cv::Vec2f* row = spectrum.ptr<cv::Vec2f>(y);
    int x = 0;
    while (x < spectrum.cols)
    {
      if (squared(row[x]) <= floor2)
      {
        ++x;
        continue;
      }
      // A run ends at a negligible entry or at a grid block boundary (where the fold wraps).
      int end = x + 1;
      while (end < spectrum.cols && end % grid.width != 0 && squared(row[end]) > floor2)
        ++end;
      runs.push_back(SpectrumRun{y, x, y % grid.height, x % grid.width, std::vector<cv::Vec2f>(row + x, row + end)});
      x = end;
    }
  }
  return runs;
}

SimpleCellBank::SimpleCellBank(const GaborParameters& parameters) : parameters_(parameters)
{
  parameters_.validate();
}

int SimpleCellBank::dftLength(int n, bool coarse)
{
  if (!coarse || n <= 8 || n > (1 << 26))
    return cv::getOptimalDFTSize(n);
  for (int scale = 1;; scale *= 2)
    for (int m : {8, 10, 12, 15})
      if (m * scale >= n)
        return m * scale;
}

void SimpleCellBank::plan(const cv::Size& image_size, bool odd_pairs)
{
  ++uses_;
  std::vector<ScalePlan> plans;
  const int n_scales = static_cast<int>(parameters_.wavelengths.size());
  // Own padding and DFT size of each scale.
  for (double wavelength : parameters_.wavelengths)
  {
    ScalePlan p;
    p.wavelength = wavelength;
    p.decimation = parameters_.decimation(wavelength);
    const int d = p.decimation;
    p.padding = roundUp(parameters_.radius(wavelength), d);
    // The grid DFT (padded / d) gets an efficient size; the full-resolution DFT is d times that.
    p.padded.width = d * dftLength((image_size.width + 2 * p.padding + d - 1) / d, coarse_dft_sizes_);
    p.padded.height = d * dftLength((image_size.height + 2 * p.padding + d - 1) / d, coarse_dft_sizes_);
    p.spectrum_source = static_cast<int>(plans.size());
    plans.push_back(std::move(p));
  }
  // A scale reuses the image spectrum of the widest-padded (coarsest) scale when that costs less in
  // larger inverse DFTs than its own forward DFT would: true for coarse scales, whose grids are tiny.
  const ScalePlan& widest = plans.back();
  for (int s = 0; s + 1 < n_scales; ++s)
  {
    ScalePlan& p = plans[s];
    const int d = p.decimation;
    if (widest.padded.width % d || widest.padded.height % d || widest.padding % d)
      continue;
    const double own_area = p.padded.area(), shared_area = widest.padded.area();
    if (parameters_.orientations * (shared_area - own_area) / (d * d) < own_area)
    {
      p.padding = widest.padding;
      p.padded = widest.padded;
      p.spectrum_source = n_scales - 1;
    }
  }
  // Everything below depends on the image size only through these DFT sizes.
  std::vector<cv::Size> key;
  for (const ScalePlan& p : plans)
    key.push_back(p.padded);

  auto hit = std::find_if(cache_.begin(), cache_.end(), [&key](const PlanSet& set) { return set.key == key; });
  if (hit == cache_.end())
  {
    if (static_cast<int>(cache_.size()) >= kPlanCacheSize)
      cache_.erase(std::min_element(cache_.begin(), cache_.end(),
                                    [](const PlanSet& a, const PlanSet& b) { return a.last_use < b.last_use; }));
    for (ScalePlan& p : plans)
      buildSpectra(p, odd_pairs);
    ++plans_built_;
    cache_.push_back(PlanSet{std::move(key), std::move(plans), odd_pairs, 0});
    hit = cache_.end() - 1;
  }
  else if (odd_pairs && !hit->odd_pairs)
  {
    for (ScalePlan& p : hit->plans)
      buildSpectra(p, true);
    hit->odd_pairs = true;
  }
  hit->last_use = uses_;
  current_ = static_cast<int>(hit - cache_.begin());
}

void SimpleCellBank::buildSpectra(ScalePlan& p, bool odd_pairs) const
{
  const int d = p.decimation;
  const cv::Size grid(p.padded.width / d, p.padded.height / d);
  const bool runs = p.runs.empty();  // a second call (computeOdd after compute) adds the odd pairs only
  odd_pairs = odd_pairs && d == 1 && p.odd_pair_spectra.empty();
  for (int i = 0; i < parameters_.orientations && (runs || odd_pairs); ++i)
  {
    const GaborKernel kernel(p.wavelength, parameters_.theta(i), parameters_);
    const int r = kernel.radius();
    // Flipped kernel h(u) = k(-u), wrapped around the origin: convolving with h correlates with k.
    cv::Mat h(p.padded, CV_32FC2, cv::Scalar::all(0));
    for (int y = -r; y <= r; ++y)
      for (int x = -r; x <= r; ++x)
      {
        const int wy = (-y + p.padded.height) % p.padded.height;
        const int wx = (-x + p.padded.width) % p.padded.width;
        h.at<cv::Vec2f>(wy, wx) = cv::Vec2f(kernel.even().at<float>(y + r, x + r),
                                            kernel.odd().at<float>(y + r, x + r));
      }
    if (runs)
    {
      cv::Mat spectrum;
      FourierTransform::forward(h, spectrum);
      // 1/d^2 for the fold, 1/grid area for the unscaled inverse DFT of compute().
      spectrum *= 1.0 / (double(d) * d * grid.area());
      p.runs.push_back(supportRuns(spectrum, grid));
    }
    if (odd_pairs)
    {
      // Odd-only pairs: orientation i goes to the real part, i+1 to the imaginary part.
      std::vector<cv::Mat> parts;
      cv::split(h, parts);
      if (i % 2 == 0)
        p.odd_pair_spectra.push_back(cv::Mat(p.padded, CV_32FC2, cv::Scalar::all(0)));
      cv::Mat pair_parts[2];
      cv::split(p.odd_pair_spectra.back(), pair_parts);
      parts[1].copyTo(pair_parts[i % 2]);
      cv::merge(pair_parts, 2, p.odd_pair_spectra.back());
    }
  }
  // The pairs were filled in the spatial domain; transform them once complete.
  if (odd_pairs)
    for (cv::Mat& pair : p.odd_pair_spectra)
    {
      FourierTransform::forward(pair, pair);
      pair *= 1.0 / p.padded.area();  // computeOdd's inverse DFT is unscaled
    }
}

std::vector<int> SimpleCellBank::spectrumSources() const
{
  std::vector<int> sources;
  for (const ScalePlan& p : current())
    if (std::find(sources.begin(), sources.end(), p.spectrum_source) == sources.end())
      sources.push_back(p.spectrum_source);
  return sources;
}

void SimpleCellBank::padImage(const cv::Mat& gray, const ScalePlan& p, cv::Mat& padded)
{
  FourierTransform::releaseIfShared(padded);  // a copy of this bank may hold it
  cv::copyMakeBorder(gray, padded, p.padding, p.padded.height - gray.rows - p.padding, p.padding,
                     p.padded.width - gray.cols - p.padding, cv::BORDER_REFLECT_101);
}

std::vector<cv::Mat> SimpleCellBank::imageSpectra(const cv::Mat& gray) const
{
  const int n_scales = static_cast<int>(current().size());
  // Image spectra, one per distinct padding (coarse scales share the widest one).
  const std::vector<int> sources = spectrumSources();
  // The padded images and spectra are the bank's, kept for the next call (fresh ones were a third of
  // BioBin's page faults); the returned spectra share them until the caller lets go.
  if (static_cast<int>(padded_images_.size()) < n_scales)  // computeOddPairs() may keep more
  {
    padded_images_.resize(n_scales);
    image_spectra_.resize(n_scales);
  }
  biovision_common::parallelFor(cv::Range(0, static_cast<int>(sources.size())), [&](const cv::Range& range) {
    for (int k = range.start; k < range.end; ++k)
    {
      const int s = sources[k];
      const ScalePlan& p = current()[s];
      padImage(gray, p, padded_images_[s]);
      FourierTransform::forward(padded_images_[s], image_spectra_[s]);
    }
  });
  std::vector<cv::Mat> image_spectra(n_scales);
  for (int s : sources)
    image_spectra[s] = image_spectra_[s];
  return image_spectra;
}

std::vector<std::vector<cv::Mat>> SimpleCellBank::computeOddPairs(const cv::Mat& gray)
{
  return std::move(computeOddPairsBatch({gray}).front());
}

std::vector<std::vector<std::vector<cv::Mat>>> SimpleCellBank::computeOddPairsBatch(const std::vector<cv::Mat>& grays)
{
  if (grays.empty())
    throw std::invalid_argument("SimpleCellBank::computeOddPairsBatch: no image");
  for (const cv::Mat& gray : grays)
    if (gray.dims != 2 || gray.type() != CV_32FC1 || gray.empty() || gray.size() != grays.front().size())
      throw std::invalid_argument(
          "SimpleCellBank::computeOddPairsBatch: the images must be non-empty 2-D CV_32FC1 of one size");
  const cv::Size size = grays.front().size();
  plan(size, true);
  for (const ScalePlan& p : current())
    if (p.decimation != 1)
      throw std::invalid_argument("SimpleCellBank::computeOdd needs min_grid_wavelength 0 (decimation 1)");
  const int n_images = static_cast<int>(grays.size());
  const int n_scales = static_cast<int>(current().size());
  const int n_pairs = (parameters_.orientations + 1) / 2;
  const std::vector<int> sources = spectrumSources();
  // The images' spectra first, then every image's inverse DFTs, each as one parallel loop over all images:
  // a stereo pair's two forward DFTs run side by side instead of one after the other on one thread.
  const int n_slots = n_images * n_scales;
  if (static_cast<int>(padded_images_.size()) < n_slots)
  {
    padded_images_.resize(n_slots);
    image_spectra_.resize(n_slots);
  }
  const int n_sources = static_cast<int>(sources.size());
  biovision_common::parallelFor(cv::Range(0, n_images * n_sources), [&](const cv::Range& range) {
    for (int job = range.start; job < range.end; ++job)
    {
      const int i = job / n_sources, s = sources[job % n_sources];
      padImage(grays[i], current()[s], padded_images_[i * n_scales + s]);
      FourierTransform::forward(padded_images_[i * n_scales + s], image_spectra_[i * n_scales + s]);
    }
  });
  std::vector<std::vector<std::vector<cv::Mat>>> out(
      n_images, std::vector<std::vector<cv::Mat>>(n_scales, std::vector<cv::Mat>(n_pairs)));
  if (static_cast<int>(pair_products_.size()) < n_slots * n_pairs)
    pair_products_.resize(size_t(n_slots) * n_pairs);
  biovision_common::parallelFor(cv::Range(0, n_slots * n_pairs), [&](const cv::Range& range) {
    for (int job = range.start; job < range.end; ++job)
    {
      const int i = job / (n_scales * n_pairs), s = job / n_pairs % n_scales, pair = job % n_pairs;
      const ScalePlan& p = current()[s];
      // One buffer per job, kept for the next call (a fresh one per call was a quarter of BioBin's page
      // faults); the returned view shares it, so it is written again only once the caller has let go.
      cv::Mat& product = pair_products_[job];
      FourierTransform::releaseIfShared(product);
      FourierTransform::multiplySpectra(image_spectra_[i * n_scales + p.spectrum_source], p.odd_pair_spectra[pair],
                                        product);
      FourierTransform::inverseUnscaled(product, product);  // the pair spectra carry the 1/N
      out[i][s][pair] = product(cv::Rect(p.padding, p.padding, size.width, size.height));
    }
  });
  return out;
}

std::vector<std::vector<cv::Mat>> SimpleCellBank::computeOdd(const cv::Mat& gray)
{
  const std::vector<std::vector<cv::Mat>> pairs = computeOddPairs(gray);
  const int n_orient = parameters_.orientations;
  const int n_pairs = (n_orient + 1) / 2;
  std::vector<std::vector<cv::Mat>> out(pairs.size(), std::vector<cv::Mat>(n_orient));
  // The splits in parallel too, as they were inside the transforms' loop.
  biovision_common::parallelFor(cv::Range(0, static_cast<int>(pairs.size()) * n_pairs), [&](const cv::Range& range) {
    for (int job = range.start; job < range.end; ++job)
    {
      const int s = job / n_pairs, pair = job % n_pairs;
      cv::Mat parts[2];
      cv::split(pairs[s][pair], parts);
      out[s][2 * pair] = parts[0];
      if (2 * pair + 1 < n_orient)
        out[s][2 * pair + 1] = parts[1];
    }
  });
  return out;
}

std::vector<ScaleResponses> SimpleCellBank::compute(const cv::Mat& gray)
{
  CV_Assert(gray.type() == CV_32FC1 && !gray.empty());
  plan(gray.size(), false);
  const int n_scales = static_cast<int>(current().size());
  const int n_orient = parameters_.orientations;

  const std::vector<cv::Mat> image_spectra = imageSpectra(gray);

  std::vector<ScaleResponses> out(n_scales);
  for (int s = 0; s < n_scales; ++s)
  {
    out[s].wavelength = current()[s].wavelength;
    out[s].decimation = current()[s].decimation;
    out[s].even.resize(n_orient);
    out[s].odd.resize(n_orient);
  }
  // One job per (scale, orientation): fold the product spectrum onto the grid, invert, crop. The folded
  // spectra and the split responses are the bank's, kept for the next call (fresh ones per call were
  // most of the recognition pyramid's page faults); a response the caller still holds is never reused.
  folded_.resize(size_t(n_scales) * n_orient);
  kept_responses_.resize(size_t(n_scales) * n_orient * 2);
  biovision_common::parallelFor(cv::Range(0, n_scales * n_orient), [&](const cv::Range& range) {
    for (int job = range.start; job < range.end; ++job)
    {
      const int s = job / n_orient, i = job % n_orient;
      const ScalePlan& p = current()[s];
      const int d = p.decimation;
      const cv::Size grid(p.padded.width / d, p.padded.height / d);
      cv::Mat& folded = folded_[job];
      folded.create(grid, CV_32FC2);
      folded.setTo(cv::Scalar::all(0));
      for (const SpectrumRun& run : p.runs[i])
      {
        const cv::Vec2f* f = image_spectra[p.spectrum_source].ptr<cv::Vec2f>(run.row) + run.col;
        cv::Vec2f* g = folded.ptr<cv::Vec2f>(run.grid_row) + run.grid_col;
        const cv::Vec2f* h = run.h.data();
        for (size_t k = 0, n = run.h.size(); k < n; ++k)
        {
          g[k][0] += f[k][0] * h[k][0] - f[k][1] * h[k][1];
          g[k][1] += f[k][0] * h[k][1] + f[k][1] * h[k][0];
        }
      }
      FourierTransform::inverseUnscaled(folded, folded);  // the kernel spectra carry the 1/N
      const int h = (gray.rows + d - 1) / d, w = (gray.cols + d - 1) / d;
      const cv::Mat valid = folded(cv::Rect(p.padding / d, p.padding / d, w, h));
      cv::Mat& even = kept_responses_[2 * size_t(job)];
      cv::Mat& odd = kept_responses_[2 * size_t(job) + 1];
      FourierTransform::releaseIfShared(even);
      FourierTransform::releaseIfShared(odd);
      even.create(h, w, CV_32F);
      odd.create(h, w, CV_32F);
      cv::Mat parts[2] = {even, odd};
      cv::split(valid, parts);
      out[s].even[i] = even;
      out[s].odd[i] = odd;
    }
  });
  return out;
}
}  // namespace biovision_v1
