#pragma once

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace biovision_common
{
/// Synthetic grey images (CV_32FC1 in [0, 1]) for the packages' unit tests: one definition of the
/// scenes the recognition and HRI tests paste their objects into. Deterministic for a seed.
struct SyntheticImages
{
  /// A distinctive "object" of size x size px: 40 random filled circles, rectangles and lines of random
  /// grey levels on 0.5, blurred by sigma 0.8 (the keypoints and descriptors have texture to find).
  static cv::Mat randomShapes(int size, unsigned seed)
  {
    cv::Mat img(size, size, CV_32F, cv::Scalar(0.5));
    cv::RNG rng(seed);
    for (int i = 0; i < 40; ++i)
    {
      const cv::Point c(rng.uniform(0, size), rng.uniform(0, size));
      const double v = rng.uniform(0.05, 0.95);
      if (i % 3 == 0)
        cv::circle(img, c, rng.uniform(3, size / 6), v, cv::FILLED);
      else if (i % 3 == 1)
        cv::rectangle(img, cv::Rect(c.x, c.y, rng.uniform(4, size / 4), rng.uniform(4, size / 4)), v, cv::FILLED);
      else
        cv::line(img, c, cv::Point(rng.uniform(0, size), rng.uniform(0, size)), v, rng.uniform(1, 4));
    }
    cv::GaussianBlur(img, img, cv::Size(), 0.8);
    return img;
  }

  /// Gaussian noise (mean 0.5, `sigma`) blurred by `blur` px and stretched to [low, high]: a smooth
  /// background (sigma 0.08, blur 6, 0.35-0.65: nearly featureless) or a texture (0.2, 2, 0.1-0.9).
  static cv::Mat smoothNoise(cv::Size size, unsigned seed, double sigma = 0.08, double blur = 6.0, double low = 0.35,
                             double high = 0.65)
  {
    cv::Mat n(size, CV_32F);
    cv::RNG rng(seed);
    rng.fill(n, cv::RNG::NORMAL, 0.5, sigma);
    cv::GaussianBlur(n, n, cv::Size(), blur);
    cv::normalize(n, n, low, high, cv::NORM_MINMAX);
    return n;
  }

  /// `object` rotated by `degrees` and scaled by `scale` about its centre, pasted with its top-left corner
  /// at `at` into a copy of `scene`; the warp's border mode `border` (its constant 0.5). `where` gets the
  /// pasted square. Throws cv::Exception when the square leaves the scene.
  static cv::Mat paste(const cv::Mat& object, const cv::Mat& scene, double degrees, double scale, cv::Point at,
                       int border, cv::Rect* where)
  {
    cv::Mat out = scene.clone();
    const cv::Point2f c(object.cols / 2.f, object.rows / 2.f);
    const int side = cvRound(object.cols * scale);
    cv::Mat m = cv::getRotationMatrix2D(c, degrees, scale);
    m.at<double>(0, 2) += side / 2.0 - c.x;
    m.at<double>(1, 2) += side / 2.0 - c.y;
    cv::Mat warped;
    cv::warpAffine(object, warped, m, cv::Size(side, side), cv::INTER_LINEAR, border, cv::Scalar(0.5));
    *where = cv::Rect(at.x, at.y, side, side);
    warped.copyTo(out(*where));
    return out;
  }
};
}  // namespace biovision_common
