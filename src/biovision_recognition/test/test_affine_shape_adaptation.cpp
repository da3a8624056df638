#include <gtest/gtest.h>

#include <cmath>

#include <opencv2/imgproc.hpp>

#include "biovision_recognition/affine_shape_adaptation.hpp"
#include "biovision_recognition/pooled_cell_features.hpp"
#include "test_images.hpp"

using namespace biovision_recognition;
using test_images::at;

namespace
{
double anisotropy(const cv::Matx22f& s)
{
  cv::Matx21f values;
  cv::eigen(cv::Matx22f(s), values);
  return values(0) / values(1);
}

/// Symmetric det-1 square root of J S^2 J^T: where the shape of the first view should land in the second.
cv::Matx22d expectedShape(const cv::Matx22d& j, const cv::Matx22d& s)
{
  const cv::Matx22d m = j * s * s.t() * j.t();
  const double det = std::sqrt(m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0));
  const double t = std::sqrt(m(0, 0) + m(1, 1) + 2 * det);
  cv::Matx22d r((m(0, 0) + det) / t, m(0, 1) / t, m(1, 0) / t, (m(1, 1) + det) / t);
  return r * (1.0 / std::sqrt(r(0, 0) * r(1, 1) - r(0, 1) * r(1, 0)));
}

/// A view of `image` foreshortened by j about its centre (the view's pixel p' = j (p - c) + c).
cv::Mat foreshortened(const cv::Mat& image, const cv::Matx22d& j, cv::Point2d& centre)
{
  centre = cv::Point2d((image.cols - 1) / 2.0, (image.rows - 1) / 2.0);
  const cv::Vec2d t = cv::Vec2d(centre.x, centre.y) - j * cv::Vec2d(centre.x, centre.y);
  cv::Mat view;
  cv::warpAffine(image, view, cv::Mat(cv::Matx23d(j(0, 0), j(0, 1), t[0], j(1, 0), j(1, 1), t[1])), image.size(),
                 cv::INTER_AREA, cv::BORDER_REFLECT);
  return view;
}

/// Keypoints on a (2 half + 1)^2 grid around the centre c of the frontal view and where j takes them in the
/// foreshortened view (wavelength scaled by sqrt det j).
void correspondingKeypoints(const cv::Point2d& c, const cv::Matx22d& j, int half, double spacing,
                            std::vector<biovision_v1::Keypoint>& frontal, std::vector<biovision_v1::Keypoint>& view)
{
  const double scale = std::sqrt(cv::determinant(j));
  for (int gy = -half; gy <= half; ++gy)
    for (int gx = -half; gx <= half; ++gx)
    {
      const cv::Vec2d d = j * cv::Vec2d(spacing * gx, spacing * gy);
      frontal.push_back(at(c.x + spacing * gx, c.y + spacing * gy, 8.0));
      view.push_back(at(c.x + d[0], c.y + d[1], 8.0 * scale));
    }
}

/// 2.5:1 foreshortening along 30 degrees, the magnitude of the test part's hardest viewpoint change.
cv::Matx22d strongForeshortening()
{
  const double c = std::cos(CV_PI / 6), s = std::sin(CV_PI / 6);
  const cv::Matx22d r(c, -s, s, c);
  return r * cv::Matx22d(0.4, 0, 0, 1.0) * r.t();
}
/// A frontal texture and its 2.5:1 foreshortened view, their pyramids, and keypoints that correspond.
struct ForeshortenedPair
{
  cv::Matx22d j = strongForeshortening();
  V1FeaturePyramid frontal, view;
  std::vector<biovision_v1::Keypoint> frontal_keypoints, view_keypoints;

  ForeshortenedPair(unsigned seed, int half, double spacing)
  {
    const cv::Mat a = test_images::texture(420, 420, seed, 2.0);
    cv::Point2d c;
    const cv::Mat b = foreshortened(a, j, c);
    frontal.build(a);
    view.build(b);
    correspondingKeypoints(c, j, half, spacing, frontal_keypoints, view_keypoints);
  }
};
}  // namespace

TEST(AffineShapeAdaptation, FollowsAForeshorteningOfTheSurface)
{
  const ForeshortenedPair pair(7, 1, 40.0);
  const auto& ka = pair.frontal_keypoints;
  const auto& kb = pair.view_keypoints;
  const AffineShapeAdaptation adaptation{AffineShapeAdaptation::Parameters()};
  int near = 0;
  double mean_anisotropy_b = 0.0;
  for (size_t i = 0; i < ka.size(); ++i)
  {
    const cv::Matx22f sa = adaptation.estimate(pair.frontal, ka[i]), sb = adaptation.estimate(pair.view, kb[i]);
    // Frobenius distance between det-1 shapes; the unadapted guess (identity) is ~1.1 away.
    near += cv::norm(cv::Matx22d(sb) - expectedShape(pair.j, cv::Matx22d(sa))) < 0.35;
    mean_anisotropy_b += anisotropy(sb) / ka.size();
  }
  EXPECT_GE(near, 7) << "of " << ka.size();
  EXPECT_GT(mean_anisotropy_b, 1.8);  // it did adapt: the view is 2.5:1
}

TEST(AffineShapeAdaptation, FlatAndDisabledGiveTheSquareGrid)
{
  V1FeaturePyramid flat;
  flat.build(cv::Mat(120, 120, CV_32F, cv::Scalar(0.5)));
  const AffineShapeAdaptation adaptation{AffineShapeAdaptation::Parameters()};
  EXPECT_EQ(adaptation.estimate(flat, at(60, 60, 8.0)), cv::Matx22f::eye());
  AffineShapeAdaptation::Parameters off;
  off.iterations = 0;
  V1FeaturePyramid textured;
  textured.build(test_images::texture(120, 120, 3, 2.0));
  EXPECT_EQ(AffineShapeAdaptation(off).estimate(textured, at(60, 60, 8.0)), cv::Matx22f::eye());
}

TEST(AffineShapeAdaptation, AnisotropyIsCappedOnStripes)
{
  // Stripes have no second direction: the shape would grow without bound.
  cv::Mat stripes(160, 160, CV_32F);
  for (int y = 0; y < stripes.rows; ++y)
    for (int x = 0; x < stripes.cols; ++x)
      stripes.at<float>(y, x) = 0.5f + 0.3f * static_cast<float>(std::sin(2 * CV_PI * (x + 0.3 * y) / 9.0));
  V1FeaturePyramid pyramid;
  pyramid.build(stripes);
  AffineShapeAdaptation::Parameters p;
  p.max_anisotropy = 3.0;
  const cv::Matx22f s = AffineShapeAdaptation(p).estimate(pyramid, at(80, 80, 8.0));
  EXPECT_NEAR(cv::determinant(s), 1.0, 1e-3);
  EXPECT_LE(anisotropy(s), 3.0 + 1e-3);
  EXPECT_TRUE(cv::checkRange(cv::Mat(s)));
}

TEST(AffineShapeAdaptation, RejectsBadParameters)
{
  AffineShapeAdaptation::Parameters p;
  p.iterations = -1;
  EXPECT_THROW(AffineShapeAdaptation{p}, std::invalid_argument);
  p = {};
  p.max_anisotropy = 0.5;
  EXPECT_THROW(AffineShapeAdaptation{p}, std::invalid_argument);
  p = {};
  p.window_wavelengths = 0.0;
  EXPECT_THROW(AffineShapeAdaptation{p}, std::invalid_argument);
  DescriptorLayout layout;
  layout.shape.level_offset = 9;
  EXPECT_THROW(layout.validate(), std::invalid_argument);
}

TEST(PooledCellFeatures, ShapeAdaptationBringsAForeshortenedViewCloser)
{
  // The pooled cells of corresponding points of a frontal and a 2.5:1 foreshortened view: laying the grid
  // on the adapted shape must make them more alike (cosine of the unit-per-scale feature vectors). The
  // gain is modest in x itself (the cells' orientations are still foreshortened; only the grid follows),
  // the projection learned to weigh what survives.
  const ForeshortenedPair pair(11, 2, 30.0);
  DescriptorLayout adapted, square;
  adapted.scales = square.scales = {0, 1, 2, 3};
  square.shape.iterations = 0;
  auto similarity = [&](const DescriptorLayout& layout) {
    const PooledCellFeatures f(layout);
    const cv::Mat xa = f.extract(pair.frontal, pair.frontal_keypoints), xb = f.extract(pair.view, pair.view_keypoints);
    double sum = 0.0;
    for (int i = 0; i < xa.rows; ++i)
      sum += xa.row(i).dot(xb.row(i)) / (cv::norm(xa.row(i)) * cv::norm(xb.row(i)));
    return sum / xa.rows;
  };
  const double with = similarity(adapted), without = similarity(square);
  EXPECT_GT(with, without + 0.015) << "adapted " << with << ", square " << without;
}
