#include "biovision_bringup/peer_saliency_orb.hpp"

#include <algorithm>
#include <filesystem>
#include <map>
#include <stdexcept>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace biovision_bringup
{
PeerSaliencyOrb::PeerSaliencyOrb(const std::vector<std::pair<std::string, cv::Mat>>& views, const Parameters& p) : p_(p)
{
  if (p.max_regions < 1 || p.orb_features < 1 || p.min_matches < 3 || !(p.ratio > 0 && p.ratio <= 1) ||
      !(p.inlier_distance > 0) || p.region_margin < 0)
    throw std::invalid_argument(
        "PeerSaliencyOrb: max_regions, orb_features >= 1, min_matches >= 3, ratio in (0, 1], "
        "inlier_distance > 0, region_margin >= 0");
  orb_ = cv::ORB::create(p.orb_features);
  saliency_ = cv::saliency::StaticSaliencySpectralResidual::create();
  for (const auto& [label, image] : views)
  {
    if (image.empty())
      throw std::invalid_argument("PeerSaliencyOrb: empty view of '" + label + "'");
    cv::Mat gray = image;
    if (image.channels() == 3)
      cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
    View v;
    v.label = label;
    orb_->detectAndCompute(gray, cv::noArray(), v.keypoints, v.descriptors);
    if (!v.descriptors.empty())
      views_.push_back(std::move(v));
  }
  orb_->setMaxFeatures(p.orb_features);
}

std::vector<std::pair<std::string, cv::Mat>> PeerSaliencyOrb::loadViews(const std::string& dir)
{
  namespace fs = std::filesystem;
  std::vector<std::pair<std::string, cv::Mat>> views;
  if (fs::is_directory(dir))
    for (const auto& label_dir : fs::directory_iterator(dir))
      if (label_dir.is_directory())
        for (const auto& file : fs::directory_iterator(label_dir.path()))
        {
          const cv::Mat image = cv::imread(file.path().string(), cv::IMREAD_GRAYSCALE);
          if (!image.empty())
            views.emplace_back(label_dir.path().filename().string(), image);
        }
  if (views.empty())
    throw std::runtime_error("PeerSaliencyOrb: no views in '" + dir + "' (expected <dir>/<label>/<image>)");
  std::sort(views.begin(), views.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return views;
}

std::vector<cv::Rect> PeerSaliencyOrb::regions(const cv::Mat& gray)
{
  cv::Mat map, binary;
  if (!saliency_->computeSaliency(gray, map))
    return {};
  map.convertTo(map, CV_32F);
  if (!saliency_->computeBinaryMap(map, binary))
    return {};
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(binary, labels, stats, centroids, 8, CV_32S);
  std::vector<std::pair<int, cv::Rect>> blobs;
  for (int i = 1; i < n; ++i)
    blobs.emplace_back(stats.at<int>(i, cv::CC_STAT_AREA),
                       cv::Rect(stats.at<int>(i, cv::CC_STAT_LEFT), stats.at<int>(i, cv::CC_STAT_TOP),
                                stats.at<int>(i, cv::CC_STAT_WIDTH), stats.at<int>(i, cv::CC_STAT_HEIGHT)));
  std::sort(blobs.begin(), blobs.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<cv::Rect> out;
  for (const auto& b : blobs)
  {
    if (static_cast<int>(out.size()) >= p_.max_regions)
      break;
    out.push_back(b.second);
  }
  return out;
}

std::vector<PeerSaliencyOrb::Detection> PeerSaliencyOrb::process(const cv::Mat& gray,
                                                                 std::vector<cv::Rect>* regions_out)
{
  if (gray.type() != CV_8UC1 || gray.empty())
    throw std::invalid_argument("PeerSaliencyOrb::process: expects a non-empty CV_8UC1 image");
  const std::vector<cv::Rect> boxes = regions(gray);
  if (regions_out)
    *regions_out = boxes;
  std::vector<Detection> found;
  const cv::Rect image_rect(0, 0, gray.cols, gray.rows);
  for (size_t r = 0; r < boxes.size(); ++r)
  {
    const cv::Rect box = cv::Rect(boxes[r].x - p_.region_margin, boxes[r].y - p_.region_margin,
                                  boxes[r].width + 2 * p_.region_margin, boxes[r].height + 2 * p_.region_margin) &
                         image_rect;
    cv::Mat mask = cv::Mat::zeros(gray.size(), CV_8U);
    mask(box).setTo(255);
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat descriptors;
    orb_->detectAndCompute(gray, mask, keypoints, descriptors);
    if (descriptors.empty())
      continue;
    // Best view: the most RANSAC-verified ratio-test matches.
    Detection best;
    for (const View& v : views_)
    {
      std::vector<std::vector<cv::DMatch>> knn;
      matcher_.knnMatch(descriptors, v.descriptors, knn, 2);
      std::vector<cv::Point2f> from, to;
      for (const auto& m : knn)
        if (m.size() == 2 && m[0].distance < p_.ratio * m[1].distance)
        {
          from.push_back(v.keypoints[m[0].trainIdx].pt);
          to.push_back(keypoints[m[0].queryIdx].pt);
        }
      if (static_cast<int>(from.size()) < p_.min_matches)
        continue;
      std::vector<uchar> inliers;
      const cv::Mat t = cv::estimateAffinePartial2D(from, to, inliers, cv::RANSAC, p_.inlier_distance);
      if (t.empty())
        continue;
      std::vector<cv::Point2f> in_points;
      for (size_t i = 0; i < inliers.size(); ++i)
        if (inliers[i])
          in_points.push_back(to[i]);
      if (static_cast<int>(in_points.size()) >= p_.min_matches && static_cast<int>(in_points.size()) > best.matches)
      {
        best.label = v.label;
        best.matches = static_cast<int>(in_points.size());
        best.box = cv::boundingRect(in_points);
        best.region_rank = static_cast<int>(r);
      }
    }
    if (best.matches > 0)
      found.push_back(best);
  }
  return found;
}
}  // namespace biovision_bringup
