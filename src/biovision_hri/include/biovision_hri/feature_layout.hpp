#pragma once

namespace biovision_common
{
class PayloadReader;
class PayloadWriter;
}  // namespace biovision_common

namespace biovision_hri
{
/// Layout of the HOG-like window descriptor on V1 complex cells (thesis §2.3, L376-L390). It belongs to a
/// trained model (stored with it): a model only reads features laid out as it was trained on.
///
/// A window is `windowCells()` x `windowCells()` pooling cells of `cell_size` px; blocks of
/// `block_cells` x `block_cells` cells step by one cell (50% overlap for 2x2 blocks), so a window holds
/// `window_blocks` x `window_blocks` blocks. Feature order: block row, block column, cell row in the
/// block, cell column in the block, orientation. Thesis defaults: 6x6 px cells, 2x2 blocks, 6x6 blocks,
/// 8 orientations -> a 42x42 px window and 6*6*4*8 = 1152 values.
struct FeatureLayout
{
  /// lambda of the Gabor quadrature pair [px]. Thesis: 6 in the method text (L376), 4 "performed best"
  /// in its own evaluation (L398, also cheaper); 4 is used. [2, 16]
  double wavelength = 4.0;
  /// N_theta: orientations of the complex cells, used as oriented "gradient" channels without voting
  /// (L386; more than 8 gave no gain, L398). [4, 12]
  int orientations = 8;
  /// gamma of the Gabor envelope: sigma along the bar = sigma across / gamma, so the kernel's long side
  /// shrinks as gamma grows (1 = isotropic). biovision_v1's default 0.5. (0, 1]
  double aspect_ratio = 0.5;
  /// Pooling cell side at the base scale [px] (L390). [3, 16]
  int cell_size = 6;
  /// Block side in cells (L390: 2x2). [1, 4]
  int block_cells = 2;
  /// Window side in blocks (L390: 6x6 blocks in a 42x42 window). [1, 12]
  int window_blocks = 6;
  /// epsilon of the L2 block normalisation v / sqrt(|v|^2 + (epsilon * block pixels)^2), in complex-cell
  /// units per pixel: keeps a textureless block near 0 instead of dividing noise by ~0. [gap] in the
  /// thesis ("L2", no epsilon). Chosen on the validation part (faces, miss rate at 1e-4 FPPW): 0 -> 6.7%,
  /// 0.001 -> 6.3%, 0.01 -> 12.0%, 0.03 -> 23.3% (complex cells of natural scenes are ~0.01 per pixel, so
  /// larger values act as a contrast threshold). [0, 1]
  double epsilon = 0.001;
  /// Grid step of the Gabor responses [px]: 1 = full resolution; 2 = biovision_v1's exact half-resolution
  /// grid (the quadrature response is one-sided, lambda / 2 >= 2 samples per wavelength suffice), the
  /// complex cells then linearly interpolated to every pixel before pooling. Ours, for speed: 2 makes the
  /// inverse DFTs 4x smaller (complex cells 28 -> 8 ms per 320x240 frame, README "Speed"); pooling over
  /// 6x6 px cells hides the interpolation. Requires wavelength / grid_step >= 2. {1, 2}
  int grid_step = 2;
  /// L2-Hys (Dalal & Triggs' HOG): after L2 normalisation every value is clipped at `clip` and the block
  /// normalised again; 0 = plain L2 (the thesis, L386). Ours, chosen on the validation part (README). [0, 1]
  double clip = 0.0;

  /// Throws std::invalid_argument naming the offending field and its range.
  void validate() const;
  /// The fields in the stored models' order (LinearDetectorModel, HandPostureClassifier).
  void write(biovision_common::PayloadWriter& writer) const;
  /// Reads what write() wrote; throws what the reader throws (short payload) or validate() throws.
  static FeatureLayout read(biovision_common::PayloadReader& reader);
  /// Channels of one block: block_cells^2 * orientations (32 for the thesis layout).
  int blockLength() const { return block_cells * block_cells * orientations; }
  /// Values per window: window_blocks^2 * blockLength() (1152 for the thesis layout).
  int featureCount() const { return window_blocks * window_blocks * blockLength(); }
  /// Window side in cells: window_blocks + block_cells - 1 (7).
  int windowCells() const { return window_blocks + block_cells - 1; }
  /// Window side [px] for pooling cells of `cell` px (42 for 6 px cells).
  int windowSide(int cell) const { return windowCells() * cell; }
  bool operator==(const FeatureLayout& o) const
  {
    return wavelength == o.wavelength && orientations == o.orientations && aspect_ratio == o.aspect_ratio &&
           cell_size == o.cell_size && block_cells == o.block_cells && window_blocks == o.window_blocks &&
           epsilon == o.epsilon && grid_step == o.grid_step && clip == o.clip;
  }
};
}  // namespace biovision_hri
