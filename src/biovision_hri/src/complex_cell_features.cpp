#include "biovision_hri/complex_cell_features.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

namespace biovision_hri
{
namespace
{
biovision_v1::GaborParameters gaborParameters(const FeatureLayout& layout)
{
  layout.validate();
  biovision_v1::GaborParameters p;
  p.wavelengths = {layout.wavelength};
  p.orientations = layout.orientations;
  p.aspect_ratio = layout.aspect_ratio;
  // grid_step 1: full resolution; 2: the exact half-resolution grid (lambda / 2 samples per wavelength).
  p.min_grid_wavelength = layout.grid_step == 1 ? 0.0 : layout.wavelength / layout.grid_step;
  return p;
}

/// One row of normalised blocks: block x concatenates, for cell rows cy and cell columns cx, the n
/// orientation sums at cell_rows[cy] + (x + cx * cell) * n; then v / sqrt(|v|^2 + eps2). Cloned for
/// AVX2 (one binary for every x86-64).
__attribute__((target_clones("arch=haswell", "default"))) void assembleBlockRow(const float* const* cell_rows,
                                                                                int block_cells, int n, int cell,
                                                                                int cols, float eps2, float clip,
                                                                                float* out)
{
  const int channels = block_cells * block_cells * n;
  for (int x = 0; x < cols; ++x, out += channels)
  {
    float* v = out;
    for (int cy = 0; cy < block_cells; ++cy)
      for (int cx = 0; cx < block_cells; ++cx, v += n)
      {
        const float* c = cell_rows[cy] + static_cast<size_t>(x + cx * cell) * n;
        for (int o = 0; o < n; ++o)
          v[o] = c[o];
      }
    float partial[8] = {0.f, 0.f, 0.f, 0.f, 0.f, 0.f, 0.f, 0.f};
    int k = 0;
    for (; k + 8 <= channels; k += 8)
      for (int l = 0; l < 8; ++l)
        partial[l] += out[k + l] * out[k + l];
    float sum2 = ((partial[0] + partial[4]) + (partial[1] + partial[5])) +
                 ((partial[2] + partial[6]) + (partial[3] + partial[7]));
    for (; k < channels; ++k)
      sum2 += out[k] * out[k];
    const float scale = 1.f / std::sqrt(sum2 + eps2 + 1e-20f);
    for (k = 0; k < channels; ++k)
      out[k] *= scale;
    if (clip > 0.f)
    {
      // L2-Hys: clip, then back to the length the block had after the first step (< 1 for a weak block:
      // epsilon's shrinkage is kept, noise is not blown up to unit length).
      const float length = std::sqrt(sum2) * scale;
      float again = 0.f;
      for (k = 0; k < channels; ++k)
      {
        out[k] = std::min(out[k], clip);
        again += out[k] * out[k];
      }
      const float rescale = length / std::sqrt(again + 1e-20f);
      for (k = 0; k < channels; ++k)
        out[k] *= rescale;
    }
  }
}

/// Grid sample (j, k) is pixel (2k, 2j): even pixels copy it, odd ones average their two neighbours (the
/// last odd row/column repeats the last sample).
cv::Mat upsampleTwice(const cv::Mat& grid, const cv::Size& size)
{
  cv::Mat out(size, CV_32F);
  const int gw = grid.cols, gh = grid.rows;
  std::vector<float> row(static_cast<size_t>(size.width));
  auto expandRow = [&](const float* g, float* o) {
    for (int x = 0; x < size.width; ++x)
    {
      const int k = x / 2;
      o[x] = (x % 2 == 0 || k + 1 >= gw) ? g[std::min(k, gw - 1)] : 0.5f * (g[k] + g[k + 1]);
    }
  };
  for (int y = 0; y < size.height; ++y)
  {
    const int j = y / 2;
    float* o = out.ptr<float>(y);
    if (y % 2 == 0 || j + 1 >= gh)
      expandRow(grid.ptr<float>(std::min(j, gh - 1)), o);
    else
    {
      expandRow(grid.ptr<float>(j), o);
      expandRow(grid.ptr<float>(j + 1), row.data());
      for (int x = 0; x < size.width; ++x)
        o[x] = 0.5f * (o[x] + row[static_cast<size_t>(x)]);
    }
  }
  return out;
}
}  // namespace

ComplexCellFeatures::ComplexCellFeatures(const FeatureLayout& layout) : layout_(layout), gabor_(gaborParameters(layout))
{
  gabor_.validate();
}

biovision_v1::SimpleCellBank& ComplexCellFeatures::bankFor(const cv::Size& size)
{
  for (size_t i = 0; i < banks_.size(); ++i)
    if (banks_[i].first == size)
    {
      std::rotate(banks_.begin(), banks_.begin() + static_cast<long>(i), banks_.begin() + static_cast<long>(i) + 1);
      return *banks_.front().second;
    }
  if (banks_.size() >= kCachedSizes)
    banks_.pop_back();
  banks_.insert(banks_.begin(), {size, std::make_unique<biovision_v1::SimpleCellBank>(gabor_)});
  return *banks_.front().second;
}

std::vector<cv::Mat> ComplexCellFeatures::complexCells(const cv::Mat& gray)
{
  if (gray.empty() || gray.type() != CV_32FC1)
    throw std::invalid_argument("ComplexCellFeatures: expected a non-empty CV_32FC1 image");
  std::vector<cv::Mat> cells = bankFor(gray.size()).compute(gray).front().complexCells();
  if (cells.front().size() != gray.size())
    for (cv::Mat& c : cells)
      c = upsampleTwice(c, gray.size());
  return cells;
}

BlockMap ComplexCellFeatures::blockMap(const std::vector<cv::Mat>& cells, int cell_size) const
{
  BlockMap map;
  blockMap(cells, cell_size, map);
  return map;
}

void ComplexCellFeatures::blockMap(const std::vector<cv::Mat>& cells, int cell_size, BlockMap& map) const
{
  if (cell_size < 1)
    throw std::invalid_argument("ComplexCellFeatures::blockMap: cell_size must be >= 1, got " +
                                std::to_string(cell_size));
  if (static_cast<int>(cells.size()) != layout_.orientations)
    throw std::invalid_argument("ComplexCellFeatures::blockMap: expected " + std::to_string(layout_.orientations) +
                                " complex-cell maps, got " + std::to_string(cells.size()));
  map.cell_size = cell_size;
  map.channels = layout_.blockLength();
  const cv::Size size = cells.front().size();
  const int block_side = layout_.block_cells * cell_size;
  const int rows = size.height - block_side + 1, cols = size.width - block_side + 1;
  if (rows <= 0 || cols <= 0)
  {
    map.data.release();
    return;
  }

  // Cell sums at every top-left position from one integral image per orientation:
  // cell(y, x)[o] = sum of C_o over [x, x + cell) x [y, y + cell).
  const int n = layout_.orientations;
  const int cell_rows = size.height - cell_size + 1, cell_cols = size.width - cell_size + 1;
  cv::Mat& cell_sums = cell_sums_;  // reused: fresh pages of a large map cost more than filling them
  cell_sums.create(cell_rows, cell_cols, CV_32FC(n));
  for (int o = 0; o < n; ++o)
  {
    if (cells[o].type() != CV_32FC1 || cells[o].size() != size)
      throw std::invalid_argument("ComplexCellFeatures::blockMap: complex-cell maps must be CV_32FC1 of one size");
    cv::Mat& integral = integral_;
    cv::integral(cells[o], integral, CV_64F);
    for (int y = 0; y < cell_rows; ++y)
    {
      const double* top = integral.ptr<double>(y);
      const double* bottom = integral.ptr<double>(y + cell_size);
      float* out = cell_sums.ptr<float>(y) + o;
      for (int x = 0; x < cell_cols; ++x)
        out[x * n] = static_cast<float>(bottom[x + cell_size] - bottom[x] - top[x + cell_size] + top[x]);
    }
  }

  // Blocks: block_cells^2 cells one cell apart, L2 normalised with epsilon scaled to the block's pixels.
  const int channels = map.channels;
  const double eps = layout_.epsilon * block_side * block_side;
  const float eps2 = static_cast<float>(eps * eps);
  map.data.create(rows, cols, CV_32FC(channels));
  const int bc = layout_.block_cells;
  cv::parallel_for_(cv::Range(0, rows), [&](const cv::Range& range) {
    std::vector<const float*> cell_rows_of_block(static_cast<size_t>(bc));
    for (int y = range.start; y < range.end; ++y)
    {
      for (int cy = 0; cy < bc; ++cy)
        cell_rows_of_block[static_cast<size_t>(cy)] = cell_sums.ptr<float>(y + cy * cell_size);
      assembleBlockRow(cell_rows_of_block.data(), bc, n, cell_size, cols, eps2, static_cast<float>(layout_.clip),
                       map.data.ptr<float>(y));
    }
  });
}

void ComplexCellFeatures::window(const BlockMap& map, int x, int y, float* out) const
{
  const int step = map.cell_size;
  const int last = (layout_.window_blocks - 1) * step;
  if (map.empty() || x < 0 || y < 0 || x + last >= map.data.cols || y + last >= map.data.rows)
    throw std::out_of_range("ComplexCellFeatures::window: window at (" + std::to_string(x) + ", " + std::to_string(y) +
                            ") does not fit the block map");
  for (int by = 0; by < layout_.window_blocks; ++by)
    for (int bx = 0; bx < layout_.window_blocks; ++bx)
    {
      const float* block = map.at(y + by * step, x + bx * step);
      for (int k = 0; k < map.channels; ++k)
        *out++ = block[k];
    }
}

cv::Mat ComplexCellFeatures::patchFeatures(const cv::Mat& gray_patch)
{
  if (gray_patch.empty() || gray_patch.type() != CV_32FC1)
    throw std::invalid_argument("ComplexCellFeatures::patchFeatures: expected a non-empty CV_32FC1 patch");
  const int side = layout_.windowSide(layout_.cell_size);
  cv::Mat patch = gray_patch;
  if (patch.cols != side || patch.rows != side)
    cv::resize(gray_patch, patch, cv::Size(side, side), 0, 0,
               gray_patch.cols > side ? cv::INTER_AREA : cv::INTER_LINEAR);
  const BlockMap map = blockMap(complexCells(patch), layout_.cell_size);
  cv::Mat row(1, layout_.featureCount(), CV_32F);
  window(map, 0, 0, row.ptr<float>());
  return row;
}
}  // namespace biovision_hri
