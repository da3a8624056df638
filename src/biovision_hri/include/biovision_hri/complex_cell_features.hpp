#pragma once

#include <memory>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "biovision_hri/block_map.hpp"
#include "biovision_hri/feature_layout.hpp"
#include "biovision_v1/simple_cell_bank.hpp"

namespace biovision_hri
{
/// HOG-like features on V1 complex cells (thesis §2.3, L376-L390).
///
/// The "gradient" is the complex cell C_i = sqrt(E_i^2 + O_i^2) of biovision_v1's Gabor bank at one
/// wavelength and N_theta orientations, at full resolution. Cells sum C_i over cell x cell px (HOG's
/// pooling; the thesis does not say sum or max), blocks concatenate block_cells^2 cells and are L2
/// normalised (no Gaussian window, no L2-Hys clipping: L386). Everything is dense: blockMap() holds the
/// normalised block at every pixel, and a window at (x, y) is the blocks at (x + bx*cell, y + by*cell);
/// window() equals extracting the window on its own (tested), without recomputing anything.
///
/// Not thread-safe (the Gabor banks cache their kernel spectra per image size): one instance per thread.
/// One bank is kept per image size (up to kCachedSizes, least recently used dropped), so the levels of a
/// pyramid that repeats every frame never re-plan their kernel spectra (re-planning cost ~8 kernel DFTs
/// per level and frame: most of the frame time before).
class ComplexCellFeatures
{
public:
  /// Throws std::invalid_argument for an invalid layout.
  explicit ComplexCellFeatures(const FeatureLayout& layout);

  /// Complex cells of a gray image (CV_32FC1 in [0, 1], see biovision_v1::InputImage): one CV_32F map
  /// per orientation, same size as the image. Throws std::invalid_argument for an empty or non-float image.
  std::vector<cv::Mat> complexCells(const cv::Mat& gray);

  /// Dense normalised blocks for pooling cells of `cell_size` px. Empty when the image is smaller than
  /// one block. Throws std::invalid_argument for cell_size < 1 or cells of the wrong count/type.
  BlockMap blockMap(const std::vector<cv::Mat>& cells, int cell_size) const;
  /// The same into `map`, reusing its memory when the size repeats (the detector's per-frame maps).
  void blockMap(const std::vector<cv::Mat>& cells, int cell_size, BlockMap& map) const;

  /// Writes the featureCount() values of the window whose top-left pixel is (x, y) to `out`. The window
  /// must lie inside the map (x + windowSide(cell) <= image width); throws std::out_of_range otherwise.
  void window(const BlockMap& map, int x, int y, float* out) const;

  /// Features of one patch (any size; resized to the 42x42 base window with INTER_AREA/LINEAR), as a
  /// 1 x featureCount() CV_32F row. For training and evaluation on crops; the Gabor filters see the
  /// patch reflected at its borders (BORDER_REFLECT_101).
  cv::Mat patchFeatures(const cv::Mat& gray_patch);

  const FeatureLayout& layout() const { return layout_; }

  /// Image sizes whose kernel spectra are kept.
  static constexpr size_t kCachedSizes = 16;

private:
  biovision_v1::SimpleCellBank& bankFor(const cv::Size& size);

  FeatureLayout layout_;
  biovision_v1::GaborParameters gabor_;
  mutable cv::Mat cell_sums_, integral_;  ///< blockMap()'s scratch, reused
  /// Most recently used first.
  std::vector<std::pair<cv::Size, std::unique_ptr<biovision_v1::SimpleCellBank>>> banks_;
};
}  // namespace biovision_hri
