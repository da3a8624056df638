#include "biovision_v1/simple_cell_bank.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "biovision_v1/gabor_kernel.hpp"

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

void SimpleCellBank::plan(const cv::Size& image_size)
{
  if (image_size == planned_size_)
    return;
  plans_.clear();
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
    p.padded.width = d * cv::getOptimalDFTSize((image_size.width + 2 * p.padding + d - 1) / d);
    p.padded.height = d * cv::getOptimalDFTSize((image_size.height + 2 * p.padding + d - 1) / d);
    p.spectrum_source = static_cast<int>(plans_.size());
    plans_.push_back(std::move(p));
  }
  // A scale reuses the image spectrum of the widest-padded (coarsest) scale when that costs less in
  // larger inverse DFTs than its own forward DFT would: true for coarse scales, whose grids are tiny.
  const ScalePlan& widest = plans_.back();
  for (int s = 0; s + 1 < n_scales; ++s)
  {
    ScalePlan& p = plans_[s];
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
  for (ScalePlan& p : plans_)
  {
    const int d = p.decimation;
    const cv::Size grid(p.padded.width / d, p.padded.height / d);
    for (int i = 0; i < parameters_.orientations; ++i)
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
      cv::Mat spectrum;
      cv::dft(h, spectrum, cv::DFT_COMPLEX_OUTPUT);
      spectrum *= 1.0 / (d * d);
      p.runs.push_back(supportRuns(spectrum, grid));
      if (d == 1)
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
    for (cv::Mat& pair : p.odd_pair_spectra)
      cv::dft(pair, pair, cv::DFT_COMPLEX_OUTPUT);
  }
  planned_size_ = image_size;
}

std::vector<cv::Mat> SimpleCellBank::imageSpectra(const cv::Mat& gray) const
{
  const int n_scales = static_cast<int>(plans_.size());
  // Image spectra, one per distinct padding (coarse scales share the widest one).
  std::vector<cv::Mat> image_spectra(n_scales);
  std::vector<int> sources;
  for (const ScalePlan& p : plans_)
    if (std::find(sources.begin(), sources.end(), p.spectrum_source) == sources.end())
      sources.push_back(p.spectrum_source);
  cv::parallel_for_(cv::Range(0, static_cast<int>(sources.size())), [&](const cv::Range& range) {
    for (int k = range.start; k < range.end; ++k)
    {
      const int s = sources[k];
      const ScalePlan& p = plans_[s];
      cv::Mat padded;
      cv::copyMakeBorder(gray, padded, p.padding, p.padded.height - gray.rows - p.padding, p.padding,
                         p.padded.width - gray.cols - p.padding, cv::BORDER_REFLECT_101);
      cv::dft(padded, image_spectra[s], cv::DFT_COMPLEX_OUTPUT);
    }
  });

  return image_spectra;
}

std::vector<std::vector<cv::Mat>> SimpleCellBank::computeOdd(const cv::Mat& gray)
{
  CV_Assert(gray.type() == CV_32FC1 && !gray.empty());
  plan(gray.size());
  for (const ScalePlan& p : plans_)
    if (p.decimation != 1)
      throw std::invalid_argument("SimpleCellBank::computeOdd needs min_grid_wavelength 0 (decimation 1)");
  const std::vector<cv::Mat> image_spectra = imageSpectra(gray);
  const int n_scales = static_cast<int>(plans_.size());
  const int n_orient = parameters_.orientations;
  const int n_pairs = (n_orient + 1) / 2;
  std::vector<std::vector<cv::Mat>> out(n_scales, std::vector<cv::Mat>(n_orient));
  cv::parallel_for_(cv::Range(0, n_scales * n_pairs), [&](const cv::Range& range) {
    cv::Mat product, response;
    for (int job = range.start; job < range.end; ++job)
    {
      const int s = job / n_pairs, pair = job % n_pairs;
      const ScalePlan& p = plans_[s];
      cv::mulSpectrums(image_spectra[p.spectrum_source], p.odd_pair_spectra[pair], product, 0);
      cv::idft(product, response, cv::DFT_COMPLEX_OUTPUT | cv::DFT_SCALE);
      const cv::Mat valid = response(cv::Rect(p.padding, p.padding, gray.cols, gray.rows));
      cv::Mat parts[2];
      cv::split(valid, parts);
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
  plan(gray.size());
  const int n_scales = static_cast<int>(plans_.size());
  const int n_orient = parameters_.orientations;

  const std::vector<cv::Mat> image_spectra = imageSpectra(gray);

  std::vector<ScaleResponses> out(n_scales);
  for (int s = 0; s < n_scales; ++s)
  {
    out[s].wavelength = plans_[s].wavelength;
    out[s].decimation = plans_[s].decimation;
    out[s].even.resize(n_orient);
    out[s].odd.resize(n_orient);
  }
  // One job per (scale, orientation): fold the product spectrum onto the grid, invert, crop.
  cv::parallel_for_(cv::Range(0, n_scales * n_orient), [&](const cv::Range& range) {
    cv::Mat folded, response;
    for (int job = range.start; job < range.end; ++job)
    {
      const int s = job / n_orient, i = job % n_orient;
      const ScalePlan& p = plans_[s];
      const int d = p.decimation;
      const cv::Size grid(p.padded.width / d, p.padded.height / d);
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
      cv::idft(folded, response, cv::DFT_COMPLEX_OUTPUT | cv::DFT_SCALE);
      const int h = (gray.rows + d - 1) / d, w = (gray.cols + d - 1) / d;
      const cv::Mat valid = response(cv::Rect(p.padding / d, p.padding / d, w, h));
      cv::Mat parts[2] = {out[s].even[i], out[s].odd[i]};
      cv::split(valid, parts);
      out[s].even[i] = parts[0];
      out[s].odd[i] = parts[1];
    }
  });
  return out;
}
}  // namespace biovision_v1
