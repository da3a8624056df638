#include "biovision_hri/sliding_window_detector.hpp"

#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

#include "biovision_hri/non_maximum_suppression.hpp"

namespace biovision_hri
{
namespace
{
void check(bool ok, const std::string& message)
{
  if (!ok)
    throw std::invalid_argument("SlidingWindowDetector::Parameters: " + message);
}

typedef float Float8 __attribute__((vector_size(32)));

/// Scores of `cols` windows of one row: out[i] = bias + sum over the window's blocks of w_block . block,
/// block b of window i being at blocks[b] + i * window_step floats (channels a multiple of 8). Blocks in
/// the outer loop, so each block row is read as one stream; one 8-wide accumulator per window (in `acc`,
/// cols entries), one horizontal sum per window at the end. Cloned for AVX2+FMA (one binary for every
/// x86-64, as biovision_recognition's kernels).
__attribute__((target_clones("arch=haswell", "default"))) void scoreRow(const float* w, const float* const* blocks,
                                                                        int block_count, int channels,
                                                                        size_t window_step, int cols, float bias,
                                                                        Float8* acc, float* out)
{
  for (int i = 0; i < cols; ++i)
    acc[i] = Float8{0.f, 0.f, 0.f, 0.f, 0.f, 0.f, 0.f, 0.f};
  for (int b = 0; b < block_count; ++b)
  {
    const float* wb = w + static_cast<size_t>(b) * channels;
    for (int k = 0; k < channels; k += 8)
    {
      Float8 wk;
      std::memcpy(&wk, wb + k, sizeof wk);
      const float* v = blocks[b] + k;
      for (int i = 0; i < cols; ++i, v += window_step)
      {
        Float8 x;  // unaligned load
        std::memcpy(&x, v, sizeof x);
        acc[i] += wk * x;
      }
    }
  }
  for (int i = 0; i < cols; ++i)
  {
    const Float8 a = acc[i];
    out[i] = bias + (((a[0] + a[4]) + (a[1] + a[5])) + ((a[2] + a[6]) + (a[3] + a[7])));
  }
}

/// w . v for channels not a multiple of 8 (layouts other than the thesis' 8 orientations).
inline float dot(const float* w, const float* v, int n)
{
  float s = 0.f;
  for (int k = 0; k < n; ++k)
    s += w[k] * v[k];
  return s;
}
}  // namespace

void SlidingWindowDetector::Parameters::validate() const
{
  check(stride >= 1 && stride <= 8, "stride must be in [1, 8] px, got " + std::to_string(stride));
  check(max_cell_size >= 3 && max_cell_size <= 16,
        "max_cell_size must be in [3, 16] px, got " + std::to_string(max_cell_size));
  check(std::isfinite(min_size) && min_size >= 16 && min_size <= 1000,
        "min_size must be in [16, 1000] px, got " + std::to_string(min_size));
  check(std::isfinite(max_size) && max_size >= min_size && max_size <= 4000,
        "max_size must be in [min_size, 4000] px, got " + std::to_string(max_size));
  check(std::isfinite(threshold) && threshold >= -5 && threshold <= 5,
        "threshold must be in [-5, 5], got " + std::to_string(threshold));
  check(nms_overlap > 0 && nms_overlap <= 1, "nms_overlap must be in (0, 1], got " + std::to_string(nms_overlap));
  check(max_detections >= 1 && max_detections <= 1000,
        "max_detections must be in [1, 1000], got " + std::to_string(max_detections));
  check(max_image_side >= 64 && max_image_side <= 8000,
        "max_image_side must be in [64, 8000] px, got " + std::to_string(max_image_side));
}

SlidingWindowDetector::SlidingWindowDetector(LinearDetectorModel model, const Parameters& parameters)
  : model_(std::move(model)), parameters_(parameters), features_((model_.validate(), model_.layout))
{
  setParameters(parameters);
}

void SlidingWindowDetector::setParameters(const Parameters& parameters)
{
  parameters.validate();
  if (parameters.max_cell_size < model_.layout.cell_size)
    throw std::invalid_argument("SlidingWindowDetector::Parameters: max_cell_size " +
                                std::to_string(parameters.max_cell_size) + " is below the model's cell size " +
                                std::to_string(model_.layout.cell_size));
  parameters_ = parameters;
}

cv::Mat SlidingWindowDetector::scoreMap(const BlockMap& map, int stride) const
{
  const FeatureLayout& l = model_.layout;
  const int last = (l.window_blocks - 1) * map.cell_size;
  if (map.empty() || map.data.rows <= last || map.data.cols <= last)
    return cv::Mat();
  const int rows = (map.data.rows - last - 1) / stride + 1, cols = (map.data.cols - last - 1) / stride + 1;
  cv::Mat scores(rows, cols, CV_32F);
  const int channels = map.channels, blocks = l.window_blocks;
  const float* w = model_.weights.data();
  const int block_count = blocks * blocks;
  cv::parallel_for_(cv::Range(0, rows), [&](const cv::Range& range) {
    std::vector<const float*> row_blocks(static_cast<size_t>(block_count));
    std::vector<Float8> acc(static_cast<size_t>(cols));
    for (int j = range.start; j < range.end; ++j)
    {
      float* out = scores.ptr<float>(j);
      for (int by = 0; by < blocks; ++by)
        for (int bx = 0; bx < blocks; ++bx)
          row_blocks[static_cast<size_t>(by * blocks + bx)] = map.at(j * stride + by * map.cell_size,
                                                                     bx * map.cell_size);
      if (channels % 8 == 0)
      {
        scoreRow(w, row_blocks.data(), block_count, channels, static_cast<size_t>(stride) * channels, cols, model_.bias,
                 acc.data(), out);
        continue;
      }
      for (int i = 0; i < cols; ++i)
      {
        float s = model_.bias;
        for (int b = 0; b < block_count; ++b)
          s += dot(w + static_cast<size_t>(b) * channels,
                   row_blocks[static_cast<size_t>(b)] + static_cast<size_t>(i) * stride * channels, channels);
        out[i] = s;
      }
    }
  });
  return scores;
}

std::vector<Detection> SlidingWindowDetector::scan(const cv::Mat& gray, Statistics* statistics, bool keep_all)
{
  const FeatureLayout& l = model_.layout;
  const Parameters& p = parameters_;
  const int base_side = l.windowSide(l.cell_size);
  const double level_step = static_cast<double>(l.cell_size) / (p.max_cell_size + 1);
  std::vector<Detection> found;
  Statistics stats;
  double scale = base_side / p.min_size;  // level px per image px
  for (int level = 0; level < 64; ++level, scale *= level_step)
  {
    if (base_side / scale > p.max_size + 1e-9)
      break;
    const cv::Size size(cvRound(gray.cols * scale), cvRound(gray.rows * scale));
    if (size.width < base_side || size.height < base_side)
      break;
    cv::Mat level_image;
    if (size == gray.size())
      level_image = gray;
    else
      cv::resize(gray, level_image, size, 0, 0, scale < 1.0 ? cv::INTER_AREA : cv::INTER_LINEAR);
    const std::vector<cv::Mat> cells = features_.complexCells(level_image);
    ++stats.levels;
    const double sx = static_cast<double>(size.width) / gray.cols, sy = static_cast<double>(size.height) / gray.rows;
    for (int cell = l.cell_size; cell <= p.max_cell_size; ++cell)
    {
      const double side = l.windowSide(cell);
      if (side / sx < p.min_size * 0.98 || side / sx > p.max_size * 1.02)  // rounding of the level size
        continue;
      if (maps_.size() <= static_cast<size_t>(stats.levels - 1) * 17 + static_cast<size_t>(cell))
        maps_.resize(static_cast<size_t>(stats.levels - 1) * 17 + static_cast<size_t>(cell) + 1);
      BlockMap& map = maps_[static_cast<size_t>(stats.levels - 1) * 17 + static_cast<size_t>(cell)];
      features_.blockMap(cells, cell, map);
      const cv::Mat scores = scoreMap(map, p.stride);
      stats.windows += static_cast<long>(scores.total());
      for (int j = 0; j < scores.rows; ++j)
        for (int i = 0; i < scores.cols; ++i)
        {
          const float s = scores.at<float>(j, i);
          if (!keep_all && s <= p.threshold)
            continue;
          Detection d;
          d.box = cv::Rect2f(static_cast<float>(i * p.stride / sx), static_cast<float>(j * p.stride / sy),
                             static_cast<float>(side / sx), static_cast<float>(side / sy));
          d.score = s;
          d.scale = static_cast<float>(sx);
          d.cell_size = cell;
          d.level = stats.levels - 1;
          d.origin = cv::Point(i * p.stride, j * p.stride);
          found.push_back(d);
        }
    }
  }
  if (statistics)
  {
    statistics->windows += stats.windows;
    statistics->levels += stats.levels;
  }
  return found;
}

std::vector<Detection> SlidingWindowDetector::detect(const cv::Mat& gray, cv::Rect region, Statistics* statistics)
{
  const auto start = std::chrono::steady_clock::now();
  if (gray.empty() || gray.type() != CV_32FC1)
    throw std::invalid_argument("SlidingWindowDetector::detect: expected a non-empty CV_32FC1 image");
  const cv::Rect image_rect(0, 0, gray.cols, gray.rows);
  region = region.area() > 0 ? (region & image_rect) : image_rect;
  if (region.width > parameters_.max_image_side || region.height > parameters_.max_image_side)
    throw std::invalid_argument("SlidingWindowDetector::detect: region " + std::to_string(region.width) + "x" +
                                std::to_string(region.height) + " exceeds max_image_side " +
                                std::to_string(parameters_.max_image_side));
  std::vector<Detection> found;
  if (region.width >= parameters_.min_size && region.height >= parameters_.min_size)
  {
    found = scan(gray(region), statistics, false);
    for (Detection& d : found)
      d.box += cv::Point2f(static_cast<float>(region.x), static_cast<float>(region.y));
    found = nonMaximumSuppression(std::move(found), parameters_.nms_overlap);
    if (static_cast<int>(found.size()) > parameters_.max_detections)
      found.resize(parameters_.max_detections);
  }
  if (statistics)
    statistics->milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return found;
}

void SlidingWindowDetector::lastFeatures(const Detection& detection, float* out) const
{
  const size_t index = static_cast<size_t>(detection.level) * 17 + static_cast<size_t>(detection.cell_size);
  if (detection.level < 0 || detection.cell_size < 1 || index >= maps_.size() || maps_[index].empty())
    throw std::out_of_range("SlidingWindowDetector::lastFeatures: no block map of level " +
                            std::to_string(detection.level) + ", cell " + std::to_string(detection.cell_size) +
                            " from the last scan");
  features_.window(maps_[index], detection.origin.x, detection.origin.y, out);
}

std::vector<Detection> SlidingWindowDetector::scoreAllWindows(const cv::Mat& gray, Statistics* statistics)
{
  if (gray.empty() || gray.type() != CV_32FC1)
    throw std::invalid_argument("SlidingWindowDetector::scoreAllWindows: expected a non-empty CV_32FC1 image");
  return scan(gray, statistics, true);
}
}  // namespace biovision_hri
