#include "biovision_recognition/v1_feature_pyramid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "biovision_v1/end_stopped_cells.hpp"

namespace biovision_recognition
{
namespace
{
// The pooling's element-wise passes, cloned for AVX-512 and AVX2 (the baseline build is SSE2 only).
__attribute__((target_clones("arch=skylake-avx512", "arch=haswell", "default"))) void maxInto(float* out,
                                                                                              const float* in, size_t n)
{
  for (size_t i = 0; i < n; ++i)
    out[i] = std::max(out[i], in[i]);
}

__attribute__((target_clones("arch=skylake-avx512", "arch=haswell", "default"))) void minInto(float* out,
                                                                                              const float* in, size_t n)
{
  for (size_t i = 0; i < n; ++i)
    out[i] = std::min(out[i], in[i]);
}
}  // namespace

V1FeaturePyramid::V1FeaturePyramid(const Parameters& parameters) : parameters_(parameters)
{
  if (parameters.max_levels < 1 || parameters.min_level_size < 4)
    throw std::invalid_argument("V1FeaturePyramid: max_levels must be >= 1 and min_level_size >= 4");
  if (parameters.pooling_diameter < 1 || parameters.pooling_diameter > 16)
    throw std::invalid_argument("V1FeaturePyramid: pooling_diameter must be in [1, 16]");
  if (parameters.pooling_phases != 2 && parameters.pooling_phases != 4)
    throw std::invalid_argument("V1FeaturePyramid: pooling_phases must be 2 or 4");
  const int d = parameters.pooling_diameter;
  pooling_disk_ = cv::Mat::zeros(d, d, CV_8U);
  const double r = d / 2.0;
  for (int y = 0; y < d; ++y)
    for (int x = 0; x < d; ++x)
      if ((y + 0.5 - r) * (y + 0.5 - r) + (x + 0.5 - r) * (x + 0.5 - r) <= r * r)
        pooling_disk_.at<uint8_t>(y, x) = 1;
  // The disk as rows of contiguous columns, offsets from cv::dilate's anchor (d/2, d/2).
  for (int y = 0; y < d; ++y)
  {
    int first = d, last = -1;
    for (int x = 0; x < d; ++x)
      if (pooling_disk_.at<uint8_t>(y, x))
      {
        first = std::min(first, x);
        last = x;
      }
    if (last < 0)
      continue;
    const cv::Vec2i interval(first - d / 2, last - d / 2);
    auto it = std::find(pooling_intervals_.begin(), pooling_intervals_.end(), interval);
    if (it == pooling_intervals_.end())
      it = pooling_intervals_.insert(pooling_intervals_.end(), interval);
    pooling_rows_.push_back({y - d / 2, static_cast<int>(it - pooling_intervals_.begin())});
  }
}

double V1FeaturePyramid::wavelengthOfLevel(int k)
{
  return kWavelength * std::pow(2.0, k / 2.0);
}

int V1FeaturePyramid::levelOfWavelength(double wavelength)
{
  if (!(wavelength > 0))
    return 0;
  return std::max(0, static_cast<int>(std::lround(2.0 * std::log2(wavelength / kWavelength))));
}

long V1FeaturePyramid::kernelSpectraBuilt() const
{
  long n = 0;
  for (const auto& bank : banks_)
    n += bank.plansBuilt();
  return n;
}

double V1FeaturePyramid::poolingCentreOffset() const
{
  // cv::dilate anchors a d x d element at (d/2, d/2): the disk's centre sits (d - 1)/2 - d/2 px from it.
  const int d = parameters_.pooling_diameter;
  return d / 2 - (d - 1) / 2.0;
}

cv::Point2f V1FeaturePyramid::toLevel(const cv::Point2f& p, int k) const
{
  const cv::Point2f s = levels_.at(k).scale;
  return {(p.x + 0.5f) / s.x - 0.5f, (p.y + 0.5f) / s.y - 0.5f};
}

cv::Point2f V1FeaturePyramid::toImage(const cv::Point2f& p, int k) const
{
  const cv::Point2f s = levels_.at(k).scale;
  return {(p.x + 0.5f) * s.x - 0.5f, (p.y + 0.5f) * s.y - 0.5f};
}

const V1FeaturePyramid::Level& V1FeaturePyramid::filtered(int k) const
{
  if (k < first_level_ || k >= levels())
    throw std::out_of_range("V1FeaturePyramid: level " + std::to_string(k) + " has no cells (filtered: " +
                            std::to_string(first_level_) + ".." + std::to_string(levels() - 1) + ")");
  return levels_[k];
}

void V1FeaturePyramid::build(const cv::Mat& gray, int first_level)
{
  if (gray.empty() || gray.type() != CV_32FC1)
    throw std::invalid_argument("V1FeaturePyramid::build: needs a non-empty CV_32FC1 image");
  if (first_level < 0)
    throw std::invalid_argument("V1FeaturePyramid::build: first_level must be >= 0");
  first_level_ = first_level;
  std::vector<cv::Mat> images{gray};
  while (static_cast<int>(images.size()) < parameters_.max_levels)
  {
    const size_t k = images.size();
    cv::Mat next;
    if (k == 1)
    {
      const cv::Size half_octave(static_cast<int>(std::lround(gray.cols / std::sqrt(2.0))),
                                 static_cast<int>(std::lround(gray.rows / std::sqrt(2.0))));
      if (std::min(half_octave.width, half_octave.height) < parameters_.min_level_size)
        break;
      cv::resize(gray, next, half_octave, 0, 0, cv::INTER_AREA);
    }
    else
    {
      const cv::Mat& src = images[k - 2];
      if (std::min((src.cols + 1) / 2, (src.rows + 1) / 2) < parameters_.min_level_size)
        break;
      cv::pyrDown(src, next);
    }
    images.push_back(next);
  }

  biovision_v1::GaborParameters gabor;
  gabor.wavelengths = {kWavelength};
  gabor.orientations = parameters_.orientations;
  gabor.sigma_per_wavelength = parameters_.sigma_per_wavelength;
  gabor.aspect_ratio = parameters_.aspect_ratio;
  gabor.support_sigmas = parameters_.support_sigmas;
  gabor.min_grid_wavelength = 0.0;  // full resolution on every level: pooling needs every pixel
  while (banks_.size() < images.size())
  {
    banks_.emplace_back(gabor);
    banks_.back().setCoarseDftSizes(parameters_.coarse_dft_sizes);
  }

  levels_.resize(images.size());
  for (size_t k = 0; k < images.size(); ++k)
  {
    Level& level = levels_[k];
    level.image = images[k];
    level.scale = {static_cast<float>(gray.cols) / images[k].cols, static_cast<float>(gray.rows) / images[k].rows};
    level.responses = {};  // let go first: the bank then writes the new responses into the same buffers
    if (static_cast<int>(k) < first_level)
    {
      level.pooled.release();
      continue;
    }
    level.responses = banks_[k].compute(images[k]).front();
    poolLevel(level);
  }
}

void V1FeaturePyramid::poolLevel(Level& level) const
{
  // Pooled on the interleaved ON responses (even 0..N-1, odd 0..N-1 per pixel), interleaved row by row
  // into a padded row: every pass runs along contiguous memory, and the ON and OFF halves of an output
  // pixel are two contiguous blocks. Planar cv::dilate / cv::erode maps and their 32-channel cv::merge
  // were a fifth of the pyramid's time (a 16-channel cv::merge alone was still 12% of it).
  const int n = parameters_.orientations, c = 2 * n;
  const bool off_phases = parameters_.pooling_phases == 4;
  const int h = level.responses.gridSize().height, w = level.responses.gridSize().width;
  std::vector<const cv::Mat*> planes;
  for (const cv::Mat& m : level.responses.even)
    planes.push_back(&m);
  for (const cv::Mat& m : level.responses.odd)
    planes.push_back(&m);
  level.pooled.create(h, w, CV_32FC(parameters_.pooling_phases * n));
  const int stride = level.pooled.channels();

  const int d = parameters_.pooling_diameter, pad = d;  // pad > every |column offset|
  const int intervals = static_cast<int>(pooling_intervals_.size());
  const size_t row_floats = size_t(w) * c;
  const int passes = off_phases ? 2 : 1;  // 0: max, 1: min
  // Per pass, interval and ring slot (row y in slot y % d): the row's extrema over the interval's columns.
  std::vector<float> ring(size_t(passes) * intervals * d * row_floats);
  std::vector<float> padded((size_t(w) + 2 * pad) * c);
  std::vector<float> column(size_t(passes) * row_floats);
  auto slot = [&](int pass, int interval, int y) {
    return ring.data() + ((size_t(pass) * intervals + interval) * d + y % d) * row_floats;
  };
  constexpr float kInf = std::numeric_limits<float>::infinity();
  auto horizontal = [&](int y) {
    float* row = padded.data() + size_t(pad) * c;
    for (int j = 0; j < c; ++j)
    {
      const float* in = planes[j]->ptr<float>(y);
      for (int x = 0; x < w; ++x)
        row[size_t(x) * c + j] = in[x];
    }
    for (int pass = 0; pass < passes; ++pass)
    {
      // Pixels outside the image take no part (cv::dilate's and cv::erode's default border).
      const float outside = pass == 0 ? -kInf : kInf;
      std::fill(padded.begin(), padded.begin() + size_t(pad) * c, outside);
      std::fill(padded.begin() + size_t(pad) * c + row_floats, padded.end(), outside);
      for (int k = 0; k < intervals; ++k)
      {
        const cv::Vec2i iv = pooling_intervals_[k];
        float* out = slot(pass, k, y);
        const float* first = padded.data() + size_t(pad + iv[0]) * c;
        std::copy(first, first + row_floats, out);
        for (int dx = iv[0] + 1; dx <= iv[1]; ++dx)
        {
          const float* in = padded.data() + size_t(pad + dx) * c;
          (pass == 0 ? maxInto : minInto)(out, in, row_floats);
        }
      }
    }
  };
  int dy_max = 0;
  for (const PoolingRow& pr : pooling_rows_)
    dy_max = std::max(dy_max, pr.dy);
  int rows_done = 0;  // rows whose horizontal extrema are in the ring
  for (int y = 0; y < h; ++y)
  {
    for (; rows_done < h && rows_done <= y + dy_max; ++rows_done)
      horizontal(rows_done);
    for (int pass = 0; pass < passes; ++pass)
    {
      float* col = column.data() + pass * row_floats;
      std::fill(col, col + row_floats, pass == 0 ? -kInf : kInf);
      for (const PoolingRow& pr : pooling_rows_)
      {
        const int yy = y + pr.dy;
        if (yy < 0 || yy >= h)
          continue;
        (pass == 0 ? maxInto : minInto)(col, slot(pass, pr.interval, yy), row_floats);
      }
    }
    float* out = level.pooled.ptr<float>(y);
    const float* col_max = column.data();
    const float* col_min = column.data() + row_floats;
    for (int x = 0; x < w; ++x, out += stride)
    {
      std::copy(col_max + size_t(x) * c, col_max + size_t(x + 1) * c, out);
      if (off_phases)
        for (int j = 0; j < c; ++j)
          out[c + j] = -col_min[size_t(x) * c + j];
    }
  }
}

std::vector<biovision_v1::Keypoint> V1FeaturePyramid::detectKeypoints(const std::vector<int>& levels) const
{
  const biovision_v1::KeypointDetector detector(parameters_.keypoints);
  // Levels are independent: detected in parallel, concatenated in the order asked.
  std::vector<std::vector<biovision_v1::Keypoint>> per_level(levels.size());
  cv::parallel_for_(cv::Range(0, static_cast<int>(levels.size())), [&](const cv::Range& r) {
    for (int i = r.start; i < r.end; ++i)
    {
      const int k = levels[i];
      if (k < first_level_ || k >= this->levels())
        continue;
      const biovision_v1::EndStoppedCells cells(levels_[k].responses);
      for (biovision_v1::Keypoint kp : detector.detect(levels_[k].responses, cells))
      {
        const cv::Point2f p = toImage({kp.x, kp.y}, k);
        kp.x = p.x;
        kp.y = p.y;
        kp.wavelength = static_cast<float>(wavelengthOfLevel(k));
        per_level[i].push_back(kp);
      }
    }
  });
  std::vector<biovision_v1::Keypoint> out;
  for (const auto& level : per_level)
    out.insert(out.end(), level.begin(), level.end());
  return out;
}
}  // namespace biovision_recognition
