#include "biovision_memory/view_scanner.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "biovision_memory/pose2d.hpp"

namespace biovision_memory
{
int ViewScan::binOf(double bearing) const
{
  if (bins.empty() || !(bin_width > 0.0))
    return -1;
  const double i = std::floor((bearing - bearing_min) / bin_width);
  return (i >= 0.0 && i < static_cast<double>(bins.size())) ? static_cast<int>(i) : -1;
}

ViewScanner::ViewScanner(const ViewScanParameters& parameters) : parameters_(parameters)
{
  parameters_.validate();
}

ViewScan ViewScanner::scan(const cv::Mat& disparity, const DisparityCamera& camera,
                           const Eigen::Isometry3d& base_from_camera) const
{
  if (disparity.empty() || disparity.type() != CV_32FC1)
    throw std::invalid_argument("ViewScanner::scan: the disparity must be a non-empty CV_32FC1 image");
  camera.validate();
  const ViewScanParameters& p = parameters_;
  const int w = disparity.cols, h = disparity.rows;
  const Eigen::Matrix3d R = base_from_camera.linear();
  const Eigen::Vector3d t = base_from_camera.translation();
  auto bearingOfColumn = [&](double u) {
    const Eigen::Vector3d d = R * Eigen::Vector3d((u - camera.cx) / camera.fx, 0.0, 1.0);
    return std::atan2(d.y(), d.x());
  };

  ViewScan scan;
  scan.max_range = p.max_range;
  scan.camera_position = t.head<2>();
  scan.camera_height = t.z();
  scan.min_obstacle_height = p.min_obstacle_height;
  scan.strips.resize(p.strips);
  for (int i = 0; i < p.strips; ++i)
    scan.strips[i].centre_bearing = bearingOfColumn((i + 0.5) * w / p.strips - 0.5);
  // Bins over the view's bearings (image left = larger bearing), with a margin for the tilt's fan-out.
  const double left = bearingOfColumn(-0.5), right = bearingOfColumn(w - 0.5);
  const double margin = 0.15;
  scan.bin_width = p.bin_width;
  scan.bearing_min = std::min(left, right) - margin;
  const double span = std::abs(Pose2D::normalizeAngle(left - right)) + 2 * margin;
  scan.bins.resize(static_cast<size_t>(std::ceil(span / p.bin_width)));
  std::vector<float> seen_far(scan.bins.size(), 0.0f);

  std::vector<std::vector<std::pair<float, Eigen::Vector2d>>> strip_obstacles(p.strips);
  std::vector<int> strip_valid(p.strips, 0), strip_total(p.strips, 0);
  const double fb = camera.fx * camera.baseline;
  const double camera_height = t.z();  // base_link's z = 0 is the floor
  for (int v = p.pixel_step / 2; v < h; v += p.pixel_step)
  {
    const float* row = disparity.ptr<float>(v);
    for (int u = p.pixel_step / 2; u < w; u += p.pixel_step)
    {
      const int strip = std::min(p.strips - 1, u * p.strips / w);
      ++strip_total[strip];
      const float d = row[u];
      if (!std::isfinite(d) || d <= 0.0f)
      {
        ++scan.invalid_pixels;
        continue;
      }
      ++scan.valid_pixels;
      ++strip_valid[strip];
      const double z = fb / d;
      const Eigen::Vector3d pt = R * Eigen::Vector3d((u - camera.cx) * z / camera.fx, (v - camera.cy) * z / camera.fy,
                                                     z) +
                                 t;
      const double range = std::hypot(pt.x(), pt.y());
      const double bearing = std::atan2(pt.y(), pt.x());
      const int bin = scan.binOf(bearing);
      if (pt.z() > p.max_obstacle_height)
        continue;  // passes over the robot: says nothing about the floor below it
      if (pt.z() >= p.min_obstacle_height)
      {
        if (range <= p.max_range)
        {
          strip_obstacles[strip].emplace_back(static_cast<float>(range), pt.head<2>());
          scan.obstacle_points.push_back(pt);
          if (bin >= 0)
            scan.bins[bin].obstacle_range = std::min(scan.bins[bin].obstacle_range, static_cast<float>(range));
        }
        else if (bin >= 0)
          seen_far[bin] = std::max(seen_far[bin], static_cast<float>(p.max_range));  // line of sight clear
        continue;
      }
      if (bin >= 0)  // floor
      {
        // The ray is lower than an obstacle from fraction f of its length on (f = 1: camera in the band).
        const double f = camera_height > p.min_obstacle_height
                             ? std::clamp((camera_height - p.min_obstacle_height) / (camera_height - pt.z()), 0.0, 1.0)
                             : 1.0;
        const double clear_from = (t.head<2>() + f * (pt.head<2>() - t.head<2>())).norm();
        ViewScan::Bin& b = scan.bins[bin];
        b.free_from = std::min(b.free_from, static_cast<float>(clear_from));
        const float from_camera = static_cast<float>((pt.head<2>() - t.head<2>()).norm());
        b.floor_near = std::min(b.floor_near, from_camera);
        b.floor_far = std::max(b.floor_far, from_camera);
        seen_far[bin] = std::max(seen_far[bin], static_cast<float>(std::min(range, p.max_range)));
      }
    }
  }
  for (size_t b = 0; b < scan.bins.size(); ++b)
  {
    ViewScan::Bin& bin = scan.bins[b];
    bin.free_to = std::min(bin.obstacle_range, seen_far[b]);
  }
  for (int i = 0; i < p.strips; ++i)
  {
    ViewScan::Strip& s = scan.strips[i];
    auto& obstacles = strip_obstacles[i];
    if (static_cast<int>(obstacles.size()) >= p.min_obstacle_pixels)
    {
      auto kth = obstacles.begin() + (p.min_obstacle_pixels - 1);
      std::nth_element(obstacles.begin(), kth, obstacles.end(),
                       [](const auto& a, const auto& b) { return a.first < b.first; });
      s.nearest_range = kth->first;
      s.nearest_point = kth->second;
      s.observed = true;
    }
    else
      s.observed = strip_total[i] > 0 && strip_valid[i] >= p.min_valid_fraction * strip_total[i];
  }
  return scan;
}
}  // namespace biovision_memory
