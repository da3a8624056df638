#include "biovision_hri/complex_cell_features.hpp"

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
  p.min_grid_wavelength = 0.0;  // full resolution: windows slide at any pixel
  return p;
}
}  // namespace

ComplexCellFeatures::ComplexCellFeatures(const FeatureLayout& layout) : layout_(layout), bank_(gaborParameters(layout))
{
}

std::vector<cv::Mat> ComplexCellFeatures::complexCells(const cv::Mat& gray)
{
  if (gray.empty() || gray.type() != CV_32FC1)
    throw std::invalid_argument("ComplexCellFeatures: expected a non-empty CV_32FC1 image");
  return bank_.compute(gray).front().complexCells();
}

BlockMap ComplexCellFeatures::blockMap(const std::vector<cv::Mat>& cells, int cell_size) const
{
  if (cell_size < 1)
    throw std::invalid_argument("ComplexCellFeatures::blockMap: cell_size must be >= 1, got " +
                                std::to_string(cell_size));
  if (static_cast<int>(cells.size()) != layout_.orientations)
    throw std::invalid_argument("ComplexCellFeatures::blockMap: expected " + std::to_string(layout_.orientations) +
                                " complex-cell maps, got " + std::to_string(cells.size()));
  BlockMap map;
  map.cell_size = cell_size;
  map.channels = layout_.blockLength();
  const cv::Size size = cells.front().size();
  const int block_side = layout_.block_cells * cell_size;
  const int rows = size.height - block_side + 1, cols = size.width - block_side + 1;
  if (rows <= 0 || cols <= 0)
    return map;

  // Cell sums at every top-left position from one integral image per orientation:
  // cell(y, x)[o] = sum of C_o over [x, x + cell) x [y, y + cell).
  const int n = layout_.orientations;
  const int cell_rows = size.height - cell_size + 1, cell_cols = size.width - cell_size + 1;
  cv::Mat cell_sums(cell_rows, cell_cols, CV_32FC(n));
  for (int o = 0; o < n; ++o)
  {
    if (cells[o].type() != CV_32FC1 || cells[o].size() != size)
      throw std::invalid_argument("ComplexCellFeatures::blockMap: complex-cell maps must be CV_32FC1 of one size");
    cv::Mat integral;
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
  cv::parallel_for_(cv::Range(0, rows), [&](const cv::Range& range) {
    for (int y = range.start; y < range.end; ++y)
    {
      float* out = map.data.ptr<float>(y);
      for (int x = 0; x < cols; ++x, out += channels)
      {
        float* v = out;
        for (int cy = 0; cy < layout_.block_cells; ++cy)
        {
          const float* row = cell_sums.ptr<float>(y + cy * cell_size);
          for (int cx = 0; cx < layout_.block_cells; ++cx, v += n)
          {
            const float* c = row + static_cast<size_t>(x + cx * cell_size) * n;
            for (int o = 0; o < n; ++o)
              v[o] = c[o];
          }
        }
        float sum2 = 0.f;
        for (int k = 0; k < channels; ++k)
          sum2 += out[k] * out[k];
        const float scale = 1.f / std::sqrt(sum2 + eps2 + 1e-20f);
        for (int k = 0; k < channels; ++k)
          out[k] *= scale;
      }
    }
  });
  return map;
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
