#pragma once

// Image pairs with exact correspondence (Middlebury ground-truth disparities, HPatches homographies) for
// train_descriptor and descriptor_eval, split into disjoint training and test parts.

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "biovision_recognition/pair_sampler.hpp"
#include "biovision_common/eval/middlebury_dataset.hpp"
#include "biovision_v1/input_image.hpp"

using biovision_common::MiddleburyDataset;

namespace biovision_recognition
{
struct CorrespondencePair
{
  std::string name;
  cv::Mat a, b;              // 8-bit BGR
  cv::Mat homography;        // 3x3 CV_64F, A -> B; empty for stereo
  cv::Mat disparity, valid;  // stereo ground truth (left = A)
};

/// Which part of a dataset: scenes in name order alternate train, test, train, ...
inline bool inPart(size_t index, const std::string& part)
{
  return part == "all" || (part == "train" && index % 2 == 0) || (part == "test" && index % 2 == 1);
}

inline cv::Mat readHomography(const std::string& path)
{
  std::ifstream in(path);
  cv::Mat h(3, 3, CV_64F);
  for (int i = 0; i < 9; ++i)
    if (!(in >> h.at<double>(i / 3, i % 3)))
      throw std::runtime_error(path + ": expected 9 numbers");
  return h;
}

/// stereo_dir: a folder of Middlebury scenes (any layout MiddleburyDataset reads); sequence_dir: an
/// HPatches (1.ppm + H_1_k) or Oxford (img1.png + H1to2p) folder; targets: which k pair with image 1
/// (all_pairs: every ordered pair of image 1 and the targets, both directions).
inline std::vector<CorrespondencePair> loadCorrespondencePairs(const std::string& stereo_dir, const std::string& part,
                                                               const std::string& sequence_dir,
                                                               const std::vector<int>& targets, bool all_pairs = false)
{
  std::vector<CorrespondencePair> pairs;
  if (!stereo_dir.empty())
  {
    const auto scenes = biovision_common::MiddleburyDataset::load(stereo_dir);
    for (size_t i = 0; i < scenes.size(); ++i)
      if (inPart(i, part))
        pairs.push_back({"stereo/" + scenes[i].name, scenes[i].left, scenes[i].right, cv::Mat(), scenes[i].ground_truth,
                         scenes[i].nonoccluded});
  }
  if (!sequence_dir.empty())
  {
    const bool oxford = std::ifstream(sequence_dir + "/img1.png").good();
    const cv::Mat first = cv::imread(sequence_dir + (oxford ? "/img1.png" : "/1.ppm"), cv::IMREAD_COLOR);
    if (first.empty())
      throw std::runtime_error(sequence_dir + ": neither 1.ppm nor img1.png");
    // Image k and H_1_k of every target (image 1: identity).
    std::vector<std::pair<cv::Mat, cv::Mat>> views{{first, cv::Mat::eye(3, 3, CV_64F)}};
    std::vector<int> index{1};
    for (int k : targets)
    {
      const std::string image = sequence_dir +
                                (oxford ? "/img" + std::to_string(k) + ".png" : "/" + std::to_string(k) + ".ppm");
      const std::string h = sequence_dir + (oxford ? "/H1to" + std::to_string(k) + "p" : "/H_1_" + std::to_string(k));
      views.emplace_back(cv::imread(image, cv::IMREAD_COLOR), readHomography(h));
      if (views.back().first.empty())
        throw std::runtime_error(image + ": cannot read");
      index.push_back(k);
    }
    // 1-k pairs; with all_pairs also every other ordered pair of these images, H_i_j = H_1_j H_1_i^-1.
    for (size_t i = 0; i < views.size(); ++i)
      for (size_t j = 0; j < views.size(); ++j)
      {
        if (i == j || (!all_pairs && i != 0))
          continue;
        CorrespondencePair p;
        p.name = "sequence/" + std::to_string(index[i]) + "-" + std::to_string(index[j]);
        p.a = views[i].first;
        p.b = views[j].first;
        p.homography = views[j].second * views[i].second.inv();
        pairs.push_back(p);
      }
  }
  return pairs;
}

/// Synthetic viewpoint changes of the pairs' real images, ASIFT's camera-tilt model: each image is
/// compressed by a tilt t in [1, max_tilt] along a random direction, scaled by s in [1/1.25, 1.25] and
/// turned by up to +-10 degrees (the descriptors are upright), about its centre. Rendered at twice the
/// size and reduced by area averaging, so compressed texture is low-passed as a camera would, not aliased.
/// Each distinct image gives `count` new pairs (image, warped image) with their exact homography.
inline std::vector<CorrespondencePair> syntheticViewpoints(const std::vector<CorrespondencePair>& pairs, int count,
                                                           double max_tilt, unsigned seed)
{
  std::vector<CorrespondencePair> out;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<const uchar*> seen;
  auto warpAll = [&](const cv::Mat& image, const std::string& name) {
    if (std::find(seen.begin(), seen.end(), image.data) != seen.end())
      return;
    seen.push_back(image.data);
    for (int k = 0; k < count; ++k)
    {
      const double tilt = 1.0 + (max_tilt - 1.0) * unit(rng), phi = CV_PI * unit(rng);
      const double scale = std::pow(1.25, 2.0 * unit(rng) - 1.0), psi = (20.0 * unit(rng) - 10.0) * CV_PI / 180.0;
      const cv::Matx22d rot_phi(std::cos(phi), -std::sin(phi), std::sin(phi), std::cos(phi));
      const cv::Matx22d rot_psi(std::cos(psi), -std::sin(psi), std::sin(psi), std::cos(psi));
      const cv::Matx22d a = scale * rot_psi * rot_phi.t() * cv::Matx22d(1.0 / tilt, 0.0, 0.0, 1.0) * rot_phi;
      const cv::Point2d c((image.cols - 1) / 2.0, (image.rows - 1) / 2.0);
      const cv::Vec2d t = cv::Vec2d(c.x, c.y) - a * cv::Vec2d(c.x, c.y);
      const cv::Matx33d h(a(0, 0), a(0, 1), t[0], a(1, 0), a(1, 1), t[1], 0, 0, 1);
      // Twice the resolution: pixel centres x2 = 2 x1 + 0.5.
      const cv::Matx33d up(2, 0, 0.5, 0, 2, 0.5, 0, 0, 1);
      const cv::Matx33d h2 = up * h;
      cv::Mat big, warped;
      cv::warpAffine(image, big, cv::Mat(cv::Matx23d(h2(0, 0), h2(0, 1), h2(0, 2), h2(1, 0), h2(1, 1), h2(1, 2))),
                     cv::Size(2 * image.cols, 2 * image.rows), cv::INTER_LINEAR, cv::BORDER_CONSTANT);
      cv::resize(big, warped, image.size(), 0, 0, cv::INTER_AREA);
      CorrespondencePair p;
      p.name = "warp/" + name + "/" + std::to_string(k);
      p.a = image;
      p.b = warped;
      p.homography = cv::Mat(h).clone();
      out.push_back(p);
    }
  };
  for (const auto& pair : pairs)
  {
    warpAll(pair.a, pair.name + "a");
    if (!pair.homography.empty())
      warpAll(pair.b, pair.name + "b");
  }
  return out;
}

inline PairSampler::Pairs samplePairs(PairSampler& sampler, const CorrespondencePair& pair, const V1FeaturePyramid& a,
                                      const V1FeaturePyramid& b)
{
  return pair.homography.empty() ? sampler.fromDisparity(a, b, pair.disparity, pair.valid)
                                 : sampler.fromHomography(a, b, pair.homography);
}
}  // namespace biovision_recognition
