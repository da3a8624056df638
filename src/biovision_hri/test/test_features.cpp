#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "biovision_hri/complex_cell_features.hpp"

using namespace biovision_hri;

namespace
{
cv::Mat texture(cv::Size size, uint64_t seed)
{
  cv::Mat noise(size, CV_32F);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::UNIFORM, 0.0, 1.0);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), 1.5);
  cv::normalize(noise, noise, 0.0, 1.0, cv::NORM_MINMAX);
  return noise;
}

/// The window descriptor computed the slow way, straight from the complex cells: per block, per cell,
/// the sum over the cell's pixels, then the block's L2 normalisation.
std::vector<float> referenceWindow(const std::vector<cv::Mat>& cells, const FeatureLayout& l, int cell, int x0, int y0)
{
  std::vector<float> out;
  const int n = l.orientations;
  const double eps = l.epsilon * (l.block_cells * cell) * (l.block_cells * cell);
  for (int by = 0; by < l.window_blocks; ++by)
    for (int bx = 0; bx < l.window_blocks; ++bx)
    {
      std::vector<double> block;
      for (int cy = 0; cy < l.block_cells; ++cy)
        for (int cx = 0; cx < l.block_cells; ++cx)
          for (int o = 0; o < n; ++o)
          {
            double sum = 0;
            const int x = x0 + (bx + cx) * cell, y = y0 + (by + cy) * cell;
            for (int v = y; v < y + cell; ++v)
              for (int u = x; u < x + cell; ++u)
                sum += cells[o].at<float>(v, u);
            block.push_back(sum);
          }
      double norm2 = 0;
      for (double v : block)
        norm2 += v * v;
      for (double v : block)
        out.push_back(static_cast<float>(v / std::sqrt(norm2 + eps * eps)));
    }
  return out;
}
}  // namespace

TEST(FeatureLayout, TheThesisLayoutHas1152ValuesInA42PixelWindow)
{
  const FeatureLayout l;
  EXPECT_EQ(l.featureCount(), 1152);  // 6x6 blocks x 2x2 cells x 8 orientations
  EXPECT_EQ(l.windowSide(6), 42);
  EXPECT_EQ(l.windowSide(10), 70);
  EXPECT_EQ(l.blockLength(), 32);
}

TEST(FeatureLayout, ValidateNamesTheFieldOutOfRange)
{
  FeatureLayout l;
  l.cell_size = 2;
  try
  {
    l.validate();
    FAIL() << "cell_size 2 accepted";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("cell_size"), std::string::npos) << e.what();
  }
  l = FeatureLayout();
  l.orientations = 13;
  EXPECT_THROW(l.validate(), std::invalid_argument);
  l = FeatureLayout();
  l.wavelength = 3.0;  // a half-resolution grid needs lambda >= 4 (2 samples per wavelength)
  EXPECT_THROW(l.validate(), std::invalid_argument);
  l.grid_step = 1;
  EXPECT_NO_THROW(l.validate());
  l.grid_step = 3;
  EXPECT_THROW(l.validate(), std::invalid_argument);
  l = FeatureLayout();
  l.clip = 1.5;
  EXPECT_THROW(l.validate(), std::invalid_argument);
}

TEST(ComplexCellFeatures, TheHalfResolutionGridGivesNearlyTheFullResolutionFeatures)
{
  // grid_step 2 (the default, for speed) against grid_step 1: the complex cells differ by the linear
  // interpolation only, and the pooled, normalised window features barely.
  FeatureLayout full_layout;
  full_layout.grid_step = 1;
  ComplexCellFeatures full{full_layout}, half{FeatureLayout()};
  const cv::Mat image = texture(cv::Size(96, 80), 6);
  const std::vector<cv::Mat> a = full.complexCells(image), b = half.complexCells(image);
  ASSERT_EQ(a.size(), b.size());
  double peak = 0, worst = 0;
  for (size_t o = 0; o < a.size(); ++o)
  {
    ASSERT_EQ(b[o].size(), image.size());
    double hi = 0;
    cv::minMaxLoc(a[o], nullptr, &hi);
    peak = std::max(peak, hi);
    worst = std::max(worst, cv::norm(a[o], b[o], cv::NORM_INF));
  }
  EXPECT_LT(worst, 0.35 * peak) << "interpolated complex cells far from the full-resolution ones";
  EXPECT_GT(worst, 0.0) << "the two grids should not be identical";
  std::vector<float> fa(full_layout.featureCount()), fb(full_layout.featureCount());
  full.window(full.blockMap(a, 6), 20, 16, fa.data());
  half.window(half.blockMap(b, 6), 20, 16, fb.data());
  double dot = 0, na = 0, nb = 0;
  for (size_t i = 0; i < fa.size(); ++i)
  {
    dot += fa[i] * fb[i];
    na += fa[i] * fa[i];
    nb += fb[i] * fb[i];
  }
  EXPECT_GT(dot / std::sqrt(na * nb), 0.98) << "window features: cosine similarity";
}

TEST(ComplexCellFeatures, L2HysClipsLargeValuesAndKeepsTheBlockLength)
{
  FeatureLayout plain, hys;
  hys.clip = 0.2;
  ComplexCellFeatures f{plain}, g{hys};
  cv::Mat image(60, 60, CV_32F, cv::Scalar(0.2));
  image.colRange(30, 60).setTo(0.8);  // one strong edge: a few dominant values per block
  const BlockMap a = f.blockMap(f.complexCells(image), 6), b = g.blockMap(g.complexCells(image), 6);
  const float* va = a.at(20, 20);
  const float* vb = b.at(20, 20);
  double na = 0, nb = 0, max_a = 0, max_b = 0;
  for (int k = 0; k < a.channels; ++k)
  {
    na += va[k] * va[k];
    nb += vb[k] * vb[k];
    max_a = std::max(max_a, static_cast<double>(va[k]));
    max_b = std::max(max_b, static_cast<double>(vb[k]));
  }
  EXPECT_NEAR(std::sqrt(nb), std::sqrt(na), 1e-4);
  EXPECT_GT(max_a, 0.2 * std::sqrt(na)) << "the edge block should have values above the clip";
  EXPECT_LT(max_b, max_a) << "clipping lowers the largest value";
}

TEST(ComplexCellFeatures, APatchGivesOneRowOf1152Values)
{
  ComplexCellFeatures f{FeatureLayout()};
  const cv::Mat row = f.patchFeatures(texture(cv::Size(42, 42), 1));
  EXPECT_EQ(row.rows, 1);
  EXPECT_EQ(row.cols, 1152);
  EXPECT_EQ(row.type(), CV_32F);
  // Any size is resized to the base window first.
  EXPECT_EQ(f.patchFeatures(texture(cv::Size(60, 60), 2)).cols, 1152);
}

TEST(ComplexCellFeatures, AUniformPatchHasNoResponse)
{
  ComplexCellFeatures f{FeatureLayout()};
  const cv::Mat row = f.patchFeatures(cv::Mat(42, 42, CV_32F, cv::Scalar(0.5)));
  EXPECT_LT(cv::norm(row, cv::NORM_INF), 1e-3);
}

TEST(ComplexCellFeatures, EdgesRespondInTheirOrientationChannel)
{
  // theta_i is the direction of the modulation (the edge's normal): a vertical edge (intensity changing
  // along x) drives orientation 0, a horizontal edge orientation N/2 = 4.
  const FeatureLayout l;
  ComplexCellFeatures f{l};
  for (const bool vertical : {true, false})
  {
    cv::Mat image(42, 42, CV_32F, cv::Scalar(0.2));
    if (vertical)
      image.colRange(21, 42).setTo(0.8);
    else
      image.rowRange(21, 42).setTo(0.8);
    const cv::Mat row = f.patchFeatures(image);
    // The block at block row 2, column 2 (pixels 12..24 on both axes) holds the edge at 21.
    const float* block = row.ptr<float>() + (2 * l.window_blocks + 2) * l.blockLength();
    std::vector<double> per_orientation(l.orientations, 0.0);
    for (int c = 0; c < l.block_cells * l.block_cells; ++c)
      for (int o = 0; o < l.orientations; ++o)
        per_orientation[o] += block[c * l.orientations + o];
    const int best = static_cast<int>(std::max_element(per_orientation.begin(), per_orientation.end()) -
                                      per_orientation.begin());
    EXPECT_EQ(best, vertical ? 0 : l.orientations / 2) << (vertical ? "vertical" : "horizontal") << " edge";
    EXPECT_GT(per_orientation[best], 3.0 * per_orientation[(best + l.orientations / 2) % l.orientations]);
  }
}

TEST(ComplexCellFeatures, BlocksAreL2NormalisedAndEpsilonOnlyShrinksThem)
{
  // epsilon 0: plain L2 (the thesis), every block of a textured image has unit length; the default
  // epsilon shrinks weak blocks towards 0 and never lengthens one.
  FeatureLayout plain;
  plain.epsilon = 0.0;
  ComplexCellFeatures f{plain}, g{FeatureLayout()};
  const cv::Mat image = texture(cv::Size(80, 60), 3);
  const BlockMap unit = f.blockMap(f.complexCells(image), 6);
  const BlockMap damped = g.blockMap(g.complexCells(image), 6);
  ASSERT_EQ(unit.data.rows, 60 - 12 + 1);
  ASSERT_EQ(unit.data.cols, 80 - 12 + 1);
  for (int y = 0; y < unit.data.rows; y += 7)
    for (int x = 0; x < unit.data.cols; x += 5)
    {
      double n2 = 0, d2 = 0;
      for (int k = 0; k < unit.channels; ++k)
      {
        n2 += unit.at(y, x)[k] * unit.at(y, x)[k];
        d2 += damped.at(y, x)[k] * damped.at(y, x)[k];
      }
      EXPECT_NEAR(std::sqrt(n2), 1.0, 1e-5);
      EXPECT_LE(std::sqrt(d2), std::sqrt(n2) + 1e-6);
      EXPECT_GT(std::sqrt(d2), 0.1);
    }
}

TEST(ComplexCellFeatures, TheDenseMapEqualsPerWindowExtraction)
{
  const FeatureLayout l;
  ComplexCellFeatures f{l};
  const cv::Mat image = texture(cv::Size(110, 90), 4);
  const std::vector<cv::Mat> cells = f.complexCells(image);
  for (const int cell : {6, 8})
  {
    const BlockMap map = f.blockMap(cells, cell);
    const int side = l.windowSide(cell);
    for (const cv::Point p : {cv::Point(0, 0), cv::Point(3, 7), cv::Point(110 - side, 90 - side)})
    {
      std::vector<float> dense(l.featureCount());
      f.window(map, p.x, p.y, dense.data());
      const std::vector<float> reference = referenceWindow(cells, l, cell, p.x, p.y);
      ASSERT_EQ(reference.size(), dense.size());
      double worst = 0;
      for (size_t i = 0; i < dense.size(); ++i)
        worst = std::max(worst, std::abs(static_cast<double>(dense[i]) - reference[i]));
      EXPECT_LT(worst, 1e-4) << "cell " << cell << " at " << p;
    }
    std::vector<float> out(l.featureCount());
    EXPECT_THROW(f.window(map, 110 - side + 1, 0, out.data()), std::out_of_range);
  }
}

TEST(ComplexCellFeatures, AnImageSmallerThanABlockHasAnEmptyMap)
{
  ComplexCellFeatures f{FeatureLayout()};
  EXPECT_TRUE(f.blockMap(f.complexCells(texture(cv::Size(11, 30), 5)), 6).empty());
  EXPECT_THROW(f.complexCells(cv::Mat()), std::invalid_argument);
  EXPECT_THROW(f.complexCells(cv::Mat(20, 20, CV_8U)), std::invalid_argument);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
