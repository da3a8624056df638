#pragma once

// Image pairs with exact correspondence (Middlebury ground-truth disparities, HPatches homographies) for
// train_descriptor and descriptor_eval, split into disjoint training and test parts.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core/persistence.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "biovision_recognition/pair_sampler.hpp"
#include "biovision_common/eval/middlebury_dataset.hpp"
#include "biovision_common/eval/source_split.hpp"
#include "biovision_v1/input_image.hpp"

using biovision_common::MiddleburyDataset;

namespace biovision_recognition
{
/// What syntheticPair() did to make view B (drawn per pair), so that an evaluation can pool by condition.
struct SyntheticViewChange
{
  double tilt = 1.0;        // foreshortening ratio of the affine part (1: none; the ASIFT range is 1..4)
  double scale = 1.0;       // uniform magnification
  double blur_sigma = 0.0;  // Gaussian blur of view B [px]; 0: not blurred
  bool noise = false;       // Gaussian noise (sigma 2 grey levels) added to view B
};

struct CorrespondencePair
{
  std::string name;
  cv::Mat a, b;                                  // 8-bit BGR
  cv::Mat homography;                            // 3x3 CV_64F, A -> B; empty for stereo
  cv::Mat disparity, valid;                      // stereo ground truth (left = A)
  std::optional<SyntheticViewChange> synthetic;  // set by syntheticPair() only
};

/// The descriptor's split by image source (issue #22): Middlebury scenes, image collections' sources
/// and flow sequences are dev (training) or held out (evaluation) by name, half each. Aloe and
/// RubberWhale are held out whatever their hash: Debian's opencv-doc ships copies of them
/// (aloeL/aloeR, rubberwhale1/2), and opencv-doc is evaluation material.
inline const biovision_common::SourceSplit& descriptorSplit()
{
  static const biovision_common::SourceSplit split("biovision-descriptor", 0.5, {"aloe", "rubberwhale"});
  return split;
}

/// The dev part is split again by source into this many folds; fold 0 is the validation part, on which a
/// training variant is chosen, so that the held-out part decides nothing (issue #22).
constexpr int kValidationFolds = 4;

/// Whether `part` names a part of the split by source ("heldout", "dev", "fit", "validation").
inline bool isSourcePart(const std::string& part)
{
  return part == "heldout" || part == "dev" || part == "fit" || part == "validation";
}

/// Whether `source` (a scene, sequence or collection source) is in `part` of descriptorSplit(): "heldout"
/// (evaluation only), "dev" (training), its two disjoint parts "fit" (variants train here) and "validation"
/// (variants are compared here), or "all". Throws std::invalid_argument for another part.
inline bool inSourcePart(const std::string& source, const std::string& part)
{
  if (part == "all")
    return true;
  if (!isSourcePart(part))
    throw std::invalid_argument("inSourcePart: unknown part '" + part + "'");
  const bool heldout = descriptorSplit().isTest(source);
  if (part == "heldout" || heldout)
    return part == "heldout" && heldout;
  const bool validation = descriptorSplit().fold(source, kValidationFolds) == 0;
  return part == "dev" || (part == "validation") == validation;
}

/// The part of the image collections that goes with `part` of the stereo scenes: the same part for a split
/// by source, `otherwise` for the old name-order parts ("train", "test") and "all".
inline std::string collectionPart(const std::string& part, const std::string& otherwise)
{
  return isSourcePart(part) ? part : otherwise;
}

/// Which part of a dataset. "train"/"test": scenes in name order alternate train, test, train, ... (the
/// committed models up to session 4); otherwise inSourcePart() by scene name.
inline bool inPart(size_t index, const std::string& part, const std::string& source = std::string())
{
  if (part == "train" || part == "test")
    return index % 2 == (part == "test" ? 1u : 0u);
  return inSourcePart(source, part);
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
      if (inPart(i, part, scenes[i].name))
        pairs.push_back({"stereo/" + scenes[i].name, scenes[i].left, scenes[i].right, cv::Mat(), scenes[i].ground_truth,
                         scenes[i].nonoccluded, std::nullopt});
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

/// One image of a collection and the source it belongs to.
struct SourceImage
{
  std::string source;  ///< SourceSplit key: the first path component under the collection's folder
  std::string path;
};

/// Every image (png, jpg, ppm, pgm) under each folder, grouped by source: a file directly in the folder
/// is its own source (its stem), a subfolder is one source (a sequence, a scene, an object). At most
/// `per_source` images per source, evenly spaced in name order. Only sources in `part` (inSourcePart()).
/// Paths under /usr/share/doc/opencv-doc are refused: those images are evaluation material. Throws std::runtime_error naming a folder that does not exist.
inline std::vector<SourceImage> listSourceImages(const std::vector<std::string>& folders, int per_source,
                                                 const std::string& part)
{
  namespace fs = std::filesystem;
  std::vector<SourceImage> out;
  for (const auto& folder : folders)
  {
    if (!fs::is_directory(folder))
      throw std::runtime_error(folder + ": not a folder");
    if (fs::weakly_canonical(folder).string().rfind("/usr/share/doc/opencv-doc", 0) == 0)
      throw std::runtime_error(folder + ": opencv-doc images are evaluation material, never training");
    std::map<std::string, std::vector<std::string>> by_source;
    for (const auto& e : fs::recursive_directory_iterator(folder))
    {
      if (!e.is_regular_file())
        continue;
      std::string ext = e.path().extension().string();
      std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
      if (ext != ".png" && ext != ".jpg" && ext != ".jpeg" && ext != ".ppm" && ext != ".pgm")
        continue;
      const fs::path relative = fs::relative(e.path(), folder);
      const std::string source = std::distance(relative.begin(), relative.end()) > 1 ? relative.begin()->string()
                                                                                     : relative.stem().string();
      by_source[source].push_back(e.path().string());
    }
    for (auto& [source, files] : by_source)
    {
      if (!inSourcePart(source, part))
        continue;
      std::sort(files.begin(), files.end());
      const size_t n = std::min(files.size(), static_cast<size_t>(std::max(1, per_source)));
      for (size_t k = 0; k < n; ++k)
        out.push_back({biovision_common::SourceSplit::key(source), files[(2 * k + 1) * files.size() / (2 * n)]});
    }
  }
  return out;
}

/// A synthetic view of `image`: a homography with the ASIFT camera-tilt model (tilt t along a random
/// direction, log-uniform in [1, max_tilt]; ASIFT samples t up to 4 = 75.5 degrees), scale in
/// [1/1.3, 1.3], in-plane turn within +-10 degrees (the descriptors are upright), and a perspective term
/// (the far side up to 15% smaller), about the centre; with `photometric`, view B also gets a gain
/// (0.6-1.4), gamma (0.7-1.4), offset (+-20), and half the time a Gaussian blur (sigma 0.5-2 px) and
/// sensor noise (sigma 2). Rendered at twice the size and reduced by area averaging.
inline CorrespondencePair syntheticPair(const cv::Mat& image, const std::string& name, double max_tilt,
                                        bool photometric, std::mt19937& rng)
{
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  SyntheticViewChange change;
  const double tilt = std::exp(std::log(max_tilt) * unit(rng)), phi = CV_PI * unit(rng);
  const double scale = std::pow(1.3, 2.0 * unit(rng) - 1.0), psi = (20.0 * unit(rng) - 10.0) * CV_PI / 180.0;
  const cv::Matx22d rot_phi(std::cos(phi), -std::sin(phi), std::sin(phi), std::cos(phi));
  const cv::Matx22d rot_psi(std::cos(psi), -std::sin(psi), std::sin(psi), std::cos(psi));
  const cv::Matx22d a = scale * rot_psi * rot_phi.t() * cv::Matx22d(1.0 / tilt, 0.0, 0.0, 1.0) * rot_phi;
  const cv::Point2d c((image.cols - 1) / 2.0, (image.rows - 1) / 2.0);
  // Perspective: w = 1 + p.(x - c), |p| up to 0.15 / half the diagonal, in a random direction.
  const double theta = 2 * CV_PI * unit(rng), strength = 0.15 * unit(rng) / (0.5 * std::hypot(image.cols, image.rows));
  const cv::Vec2d pv(strength * std::cos(theta), strength * std::sin(theta));
  const cv::Matx33d centre(1, 0, -c.x, 0, 1, -c.y, 0, 0, 1), back(1, 0, c.x, 0, 1, c.y, 0, 0, 1);
  const cv::Matx33d core(a(0, 0), a(0, 1), 0, a(1, 0), a(1, 1), 0, pv[0], pv[1], 1);
  const cv::Matx33d h = back * core * centre;
  const cv::Matx33d up(2, 0, 0.5, 0, 2, 0.5, 0, 0, 1);
  cv::Mat big, warped;
  cv::warpPerspective(image, big, cv::Mat(up * h), cv::Size(2 * image.cols, 2 * image.rows), cv::INTER_LINEAR,
                      cv::BORDER_CONSTANT);
  cv::resize(big, warped, image.size(), 0, 0, cv::INTER_AREA);
  if (photometric)
  {
    const double gain = 0.6 + 0.8 * unit(rng), gamma = std::exp(std::log(0.7) + std::log(2.0) * unit(rng));
    const double offset = 40.0 * unit(rng) - 20.0;
    cv::Mat lut(1, 256, CV_8U);
    for (int i = 0; i < 256; ++i)
      lut.at<uchar>(i) = cv::saturate_cast<uchar>(255.0 * std::pow(gain * i / 255.0, gamma) + offset);
    cv::LUT(warped, lut, warped);
    if (unit(rng) < 0.5)
    {
      const double sigma = 0.5 + 1.5 * unit(rng);
      cv::GaussianBlur(warped, warped, cv::Size(), sigma, sigma);
      change.blur_sigma = sigma;
    }
    if (unit(rng) < 0.5)
    {
      cv::Mat noise(warped.size(), CV_16SC(warped.channels()));
      cv::randn(noise, 0, 2.0);
      cv::Mat w16;
      warped.convertTo(w16, CV_16S);
      w16 += noise;
      w16.convertTo(warped, CV_8U);
      change.noise = true;
    }
  }
  CorrespondencePair p;
  p.name = name;
  p.a = image;
  p.b = warped;
  p.homography = cv::Mat(h).clone();
  change.tilt = tilt;
  change.scale = scale;
  p.synthetic = change;
  return p;
}

/// A graded viewpoint change of `image` for evaluation: the view of a camera turned by `degrees` about
/// the image's vertical axis (planar scene, affine approximation: x compressed by cos(degrees)), about
/// the centre, no other change. 0 degrees gives the identity.
inline CorrespondencePair tiltPair(const cv::Mat& image, const std::string& name, double degrees)
{
  const double t = std::cos(degrees * CV_PI / 180.0);
  const cv::Point2d c((image.cols - 1) / 2.0, (image.rows - 1) / 2.0);
  const cv::Matx33d h(t, 0, c.x * (1 - t), 0, 1, 0, 0, 0, 1);
  const cv::Matx33d up(2, 0, 0.5, 0, 2, 0.5, 0, 0, 1);
  cv::Mat big, warped;
  cv::warpPerspective(image, big, cv::Mat(up * h), cv::Size(2 * image.cols, 2 * image.rows), cv::INTER_LINEAR,
                      cv::BORDER_CONSTANT);
  cv::resize(big, warped, image.size(), 0, 0, cv::INTER_AREA);
  CorrespondencePair p;
  p.name = name;
  p.a = image;
  p.b = warped;
  p.homography = cv::Mat(h).clone();
  return p;
}

/// A homography pair given as two images and an OpenCV FileStorage or plain-text 3x3 matrix (A -> B),
/// e.g. opencv-doc's graf1.png, graf3.png, H1to3p.xml. Throws std::runtime_error naming the file.
inline CorrespondencePair loadHomographyPair(const std::string& a, const std::string& b, const std::string& h_path)
{
  CorrespondencePair p;
  p.name = "pair/" + std::filesystem::path(a).stem().string() + "-" + std::filesystem::path(b).stem().string();
  p.a = cv::imread(a, cv::IMREAD_COLOR);
  p.b = cv::imread(b, cv::IMREAD_COLOR);
  if (p.a.empty() || p.b.empty())
    throw std::runtime_error(a + " or " + b + ": cannot read");
  if (h_path.size() > 4 && h_path.substr(h_path.size() - 4) == ".xml")
  {
    cv::FileStorage fs(h_path, cv::FileStorage::READ);
    if (!fs.isOpened() || fs.root().empty())
      throw std::runtime_error(h_path + ": no matrix");
    (*fs.root().begin()) >> p.homography;  // the first (only) entry, whatever its name (H13, ...)
    if (p.homography.rows != 3 || p.homography.cols != 3)
      throw std::runtime_error(h_path + ": not a 3x3 matrix");
    p.homography.convertTo(p.homography, CV_64F);
  }
  else
    p.homography = readHomography(h_path);
  return p;
}

inline PairSampler::Pairs samplePairs(PairSampler& sampler, const CorrespondencePair& pair, const V1FeaturePyramid& a,
                                      const V1FeaturePyramid& b)
{
  return pair.homography.empty() ? sampler.fromDisparity(a, b, pair.disparity, pair.valid)
                                 : sampler.fromHomography(a, b, pair.homography);
}
}  // namespace biovision_recognition
