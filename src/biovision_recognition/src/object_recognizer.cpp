#include "biovision_recognition/object_recognizer.hpp"

#include <algorithm>
#include <chrono>
#include <map>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "biovision_recognition/hamming_matcher.hpp"

namespace biovision_recognition
{
namespace
{
V1FeaturePyramid::Parameters pyramidParameters(const V1Descriptor& descriptor, const ObjectRecognizer::Parameters& p)
{
  V1FeaturePyramid::Parameters pyramid = descriptor.pyramidParameters();
  pyramid.coarse_dft_sizes = p.coarse_dft_sizes;
  return pyramid;
}
}  // namespace

ObjectRecognizer::ObjectRecognizer(std::shared_ptr<const V1Descriptor> descriptor, const Parameters& parameters)
  : descriptor_(std::move(descriptor)), parameters_(parameters), pyramid_(pyramidParameters(*descriptor_, parameters_))
{
}

void ObjectRecognizer::setParameters(const Parameters& parameters)
{
  const bool rebuild = parameters.coarse_dft_sizes != parameters_.coarse_dft_sizes;
  parameters_ = parameters;
  if (rebuild)
    pyramid_ = V1FeaturePyramid(pyramidParameters(*descriptor_, parameters_));
}

ObjectRecognizer::RegionFeatures ObjectRecognizer::regionFeatures(const cv::Mat& gray, const cv::Rect& box,
                                                                  const std::vector<int>& levels)
{
  const cv::Rect image(0, 0, gray.cols, gray.rows);
  const int m = std::max(0, parameters_.region_margin);
  const cv::Rect crop = cv::Rect(box.x - m, box.y - m, box.width + 2 * m, box.height + 2 * m) & image;
  // Descriptors sample their keypoint's level and coarser ones (DescriptorLayout::scales >= 0), shape
  // adaptation a coarser one still: no level finer than the finest keypoint level is read.
  const int first_level = levels.empty() ? 0 : std::max(0, *std::min_element(levels.begin(), levels.end()));
  pyramid_.build(gray(crop).clone(), first_level);
  std::vector<biovision_v1::Keypoint> local;
  for (const auto& kp : pyramid_.detectKeypoints(levels))
  {
    const cv::Point2f p(kp.x + crop.x, kp.y + crop.y);
    if (p.x >= box.x && p.y >= box.y && p.x <= box.x + box.width - 1 && p.y <= box.y + box.height - 1)
      local.push_back(kp);
  }
  std::stable_sort(local.begin(), local.end(), [](const biovision_v1::Keypoint& a, const biovision_v1::Keypoint& b) {
    return a.strength > b.strength;
  });
  if (static_cast<int>(local.size()) > parameters_.max_keypoints)
    local.resize(std::max(0, parameters_.max_keypoints));
  RegionFeatures features;
  features.codes = descriptor_->compute(pyramid_, local);
  for (auto& kp : local)
  {
    kp.x += crop.x;
    kp.y += crop.y;
  }
  features.keypoints = std::move(local);
  return features;
}

ObjectView ObjectRecognizer::describe(const cv::Mat& gray, cv::Rect box, const std::string& label)
{
  const cv::Rect image(0, 0, gray.cols, gray.rows);
  if (box.area() == 0)
    box = image;
  box &= image;
  if (box.width < 8 || box.height < 8)
    throw std::invalid_argument("ObjectRecognizer::describe: the box does not overlap the image (or is under 8 px)");
  RegionFeatures f = regionFeatures(gray, box, parameters_.template_levels);
  ObjectView view;
  view.label = label;
  view.size = box.size();
  for (auto& kp : f.keypoints)
  {
    kp.x -= box.x;
    kp.y -= box.y;
  }
  view.keypoints = std::move(f.keypoints);
  view.codes = std::move(f.codes);
  return view;
}

std::string ObjectRecognizer::learnProblem(const ObjectView& view) const
{
  const int needed = std::max(parameters_.min_view_keypoints, parameters_.verifier.min_inliers);
  if (static_cast<int>(view.keypoints.size()) >= needed)
    return "";
  return "only " + std::to_string(view.keypoints.size()) + " keypoints in the box, " + std::to_string(needed) +
         " needed (min_view_keypoints): too little texture, or too far away, to learn";
}

std::vector<RecognizedObject> ObjectRecognizer::recognize(const cv::Mat& gray,
                                                          const std::vector<SearchRegion>& regions_in,
                                                          const ObjectMemory& memory, Statistics* statistics)
{
  const auto start = std::chrono::steady_clock::now();
  Statistics stats;
  const long spectra_before = pyramid_.kernelSpectraBuilt();
  std::vector<RecognizedObject> found;
  const cv::Rect image(0, 0, gray.cols, gray.rows);
  std::vector<SearchRegion> regions = regions_in;
  if (regions.empty())
    regions.push_back({image, 0});
  if (memory.bits() != descriptor_->model().bits())
    throw std::invalid_argument("ObjectRecognizer: the object memory's code length differs from the descriptor's");
  const GeometricVerifier verifier(parameters_.verifier);
  const HammingMatcher matcher(1);

  for (const auto& region : regions)
  {
    const double elapsed_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const cv::Rect box = region.box & image;
    if (box.width < parameters_.min_region_side || box.height < parameters_.min_region_side ||
        (parameters_.time_budget_ms > 0 && elapsed_ms > parameters_.time_budget_ms) || memory.codeCount() == 0)
    {
      ++stats.regions_skipped;
      continue;
    }
    ++stats.regions_processed;
    const RegionFeatures query = regionFeatures(gray, box, parameters_.keypoint_levels);
    stats.keypoints += static_cast<int>(query.keypoints.size());
    if (query.keypoints.empty())
      continue;

    std::vector<std::vector<HammingMatch>> hits;
    if (static_cast<int>(memory.codeCount()) >= parameters_.index_min_library &&
        memory.index().candidateFraction(parameters_.max_distance) < 0.01)
    {
      hits.resize(query.codes.size());
      for (size_t q = 0; q < query.codes.size(); ++q)
        hits[q] = memory.index().radiusSearch(query.codes.code(q), parameters_.max_distance);
    }
    else
      hits = matcher.radiusMatch(query.codes, memory.library(), parameters_.max_distance);

    // Per view: each query keypoint's nearest code of that view.
    std::map<uint32_t, std::pair<std::vector<cv::Point2f>, std::vector<cv::Point2f>>> per_view;
    for (size_t q = 0; q < hits.size(); ++q)
    {
      std::vector<uint32_t> seen;
      for (const auto& h : hits[q])  // nearest first
      {
        const uint32_t v = memory.viewOf(h.train);
        if (std::find(seen.begin(), seen.end(), v) != seen.end())
          continue;
        seen.push_back(v);
        const auto& tkp = memory.views()[v].keypoints[memory.keypointOf(h.train)];
        per_view[v].first.emplace_back(tkp.x, tkp.y);
        per_view[v].second.emplace_back(query.keypoints[q].x, query.keypoints[q].y);
      }
    }
    RecognizedObject best;
    for (const auto& [v, points] : per_view)
    {
      if (static_cast<int>(points.first.size()) < parameters_.verifier.min_inliers)
        continue;
      const GeometricVerifier::Result r = verifier.verify(points.first, points.second);
      if (!r.accepted || r.inliers <= best.matches)
        continue;
      const ObjectView& view = memory.views()[v];
      std::vector<cv::Point2f> corners{{0.f, 0.f},
                                       {static_cast<float>(view.size.width), 0.f},
                                       {static_cast<float>(view.size.width), static_cast<float>(view.size.height)},
                                       {0.f, static_cast<float>(view.size.height)}};
      cv::transform(corners, corners, r.transform);
      best.label = view.label;
      best.matches = r.inliers;
      best.score = std::min(1.0, static_cast<double>(r.inliers) / query.keypoints.size());
      best.box = cv::boundingRect(corners) & image;
      best.region_rank = region.rank;
      best.match_points.clear();
      for (size_t i = 0; i < r.inlier_mask.size() && i < points.second.size(); ++i)
        if (r.inlier_mask[i])
          best.match_points.push_back(points.second[i]);
    }
    if (!best.label.empty())
      found.push_back(best);
  }
  stats.kernel_spectra_built = pyramid_.kernelSpectraBuilt() - spectra_before;
  stats.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (statistics)
    *statistics = stats;
  return found;
}
}  // namespace biovision_recognition
