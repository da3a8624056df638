#include "biovision_recognition/v1_feature_pyramid.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "biovision_v1/end_stopped_cells.hpp"

namespace biovision_recognition
{
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
    if (static_cast<int>(k) < first_level)
    {
      level.responses = {};
      level.pooled.release();
      continue;
    }
    level.responses = banks_[k].compute(images[k]).front();
    const int n = parameters_.orientations;
    std::vector<cv::Mat> maps(parameters_.pooling_phases * n);
    for (int i = 0; i < n; ++i)
    {
      cv::dilate(level.responses.even[i], maps[i], pooling_disk_);
      cv::dilate(level.responses.odd[i], maps[n + i], pooling_disk_);
      if (parameters_.pooling_phases == 4)
      {
        // OFF phases: the strongest negative response, which the signed maximum discards.
        cv::erode(level.responses.even[i], maps[2 * n + i], pooling_disk_);
        cv::erode(level.responses.odd[i], maps[3 * n + i], pooling_disk_);
        maps[2 * n + i] *= -1.f;
        maps[3 * n + i] *= -1.f;
      }
    }
    cv::merge(maps, level.pooled);
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
